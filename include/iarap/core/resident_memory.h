// The process's resident memory, for the memory figures of `bench` and the run reports (issue 44).
#pragma once
#include <cstddef>

namespace iarap {

// The largest resident set the process has had so far (getrusage's ru_maxrss), in bytes.
std::size_t peak_resident_bytes();

// The resident set now (/proc/self/statm), in bytes; 0 where the file cannot be read.
std::size_t current_resident_bytes();

} // namespace iarap
