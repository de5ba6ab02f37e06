# Warnings for our own targets only; Eigen and SuiteSparse headers are included as SYSTEM.
function(iarap_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wno-unused-parameter)
endfunction()

if(IARAP_NATIVE)
  add_compile_options(-O3 -march=native)
endif()
