# Precompiled headers: Eigen, the standard library and GoogleTest are parsed once per target instead of
# once per file. Most files are small and spend most of their compile time in those headers (a test file:
# 4.1 s -> 1.6 s), which is most of CI's two builds (Release and the sanitizers).
option(IARAP_PRECOMPILED_HEADERS "Precompile the headers every file of a target includes" ON)

set(IARAP_PCH_COMMON <algorithm> <cmath> <limits> <memory> <optional> <string> <utility> <vector>
  <Eigen/Core> <Eigen/Geometry> <Eigen/SparseCore>)

function(iarap_precompile_headers target)
  if(IARAP_PRECOMPILED_HEADERS)
    target_precompile_headers(${target} PRIVATE ${IARAP_PCH_COMMON} ${ARGN})
  endif()
endfunction()
