// Internal: writes a file atomically: to a temporary file in the same folder, then renamed over the target,
// so a crash or a full disk never leaves a half-written mesh under the final name.
#pragma once
#include <string>

namespace iarap::io_detail {

// Replaces `path` with `contents`. Throws InputError naming the path and the system's reason.
void write_file_atomically(const std::string& path, const std::string& contents);

} // namespace iarap::io_detail
