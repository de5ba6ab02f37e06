# The test program's own optimization. Its run spends its time in the library, which keeps the build's flags;
# its files are compiled for less (most of each build's compile time is theirs): -O1 in Release, -O0 under
# the sanitizers (checked the same, only slower). A unity batch of tests: 44 s at -O3, 33 s at -O1 (Release);
# the sanitizer build's test files 584 CPU s at -O1, 352 at -O0; the runs as long. The library binds its
# own calls (-Bsymbolic-functions, src/CMakeLists.txt), so the program's copies of inline functions (Eigen's,
# ours) never stand in for the library's. Files named after OPTIMIZED run brute-force references of their
# own and keep the build's level (-O1 under the sanitizers), outside the unity batches in every build, so
# that all builds batch the same files (a name defined by two files of one batch would break one build only).
function(iarap_test_optimization target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "OPTIMIZED")
  set_source_files_properties(${arg_OPTIMIZED} TARGET_DIRECTORY ${target} PROPERTIES
    SKIP_UNITY_BUILD_INCLUSION ON)
  if(IARAP_SANITIZE)
    target_compile_options(${target} PRIVATE -O0)
    set_source_files_properties(${arg_OPTIMIZED} TARGET_DIRECTORY ${target} PROPERTIES
      COMPILE_OPTIONS -O1 SKIP_PRECOMPILE_HEADERS ON)
  elseif(CMAKE_BUILD_TYPE STREQUAL "Release")
    target_compile_options(${target} PRIVATE -O1)
    set_source_files_properties(${arg_OPTIMIZED} TARGET_DIRECTORY ${target} PROPERTIES
      COMPILE_OPTIONS -O3 SKIP_PRECOMPILE_HEADERS ON)
  endif()
endfunction()
