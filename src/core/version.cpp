#include "iarap/core/version.h"

// src/CMakeLists.txt defines it for this file only, from VERSION, so that a new version recompiles one file.
#ifndef IARAP_VERSION_STRING
#error "IARAP_VERSION_STRING is defined by src/CMakeLists.txt"
#endif

namespace iarap {

std::string version() {
  return IARAP_VERSION_STRING;
}

} // namespace iarap
