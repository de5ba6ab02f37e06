# Warnings for our own targets only; Eigen and SuiteSparse headers are included as SYSTEM.
function(iarap_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wno-unused-parameter)
  # A unity build includes the .cpp files into one file, so GCC takes a class that holds a type of an
  # anonymous namespace for one declared in a header (where it would be an ODR hazard); it is not.
  if(CMAKE_UNITY_BUILD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-subobject-linkage)
  endif()
endfunction()

if(IARAP_NATIVE)
  add_compile_options(-O3 -march=native)
endif()
