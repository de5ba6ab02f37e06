// Whether two paths of the command line name one file, so that a command never overwrites its input.
#pragma once
#include <string>

namespace iarap::cli {

// True when a and b name the same file (following links), or would once written.
bool same_file(const std::string& a, const std::string& b);

} // namespace iarap::cli
