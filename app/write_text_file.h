// Atomic writing of the tool's text outputs (JSON reports).
#pragma once
#include <string>

namespace iarap::cli {

// Writes text to path through a temporary file in the same folder renamed over path, so that a reader
// never sees half a report. Throws InputError naming the path and the system's reason.
void write_text_file(const std::string& path, const std::string& text);

} // namespace iarap::cli
