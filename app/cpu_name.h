// The machine's CPU model, for benchmark reports.
#pragma once
#include <string>

namespace iarap::cli {

// The first "model name" of /proc/cpuinfo, or "unknown" where there is none (non-Linux, containers).
std::string cpu_name();

} // namespace iarap::cli
