// The version of the iarap library. The repository's VERSION file is its one source: CMake reads it into
// the package version (find_package(iarap 0.1)) and compiles it into version() (src/core/version.cpp).
#pragma once
#include <string>

namespace iarap {

// "MAJOR.MINOR.PATCH" of the library that is loaded (not of the headers a program was compiled with).
std::string version();

} // namespace iarap
