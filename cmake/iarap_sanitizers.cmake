# IARAP_SANITIZE=ON: the whole build (library, tool, tests) under ASan + UBSan.
if(IARAP_SANITIZE)
  # -O1 keeps the instrumented build quick to compile and still readable in reports.
  # UBSan traps instead of calling its runtime: its runtime calls carry a static record per check (source
  # location, type names) with a pointer the loader relocates at every start, 2.2M relocations and 62 MB of
  # data in the test program alone, about 0.8 s per test process (CTest starts one per test). A trapped
  # check stops the process with SIGILL, and ASan prints its stack (ASAN_OPTIONS=handle_sigill=1, which
  # scripts/test.sh sets) down to the file and line of the undefined operation.
  add_compile_options(-fsanitize=address,undefined -fsanitize-undefined-trap-on-error -fno-omit-frame-pointer -O1)
  add_link_options(-fsanitize=address,undefined)
  # The instrumentation makes GCC 12 report maybe-uninitialized reads inside libstdc++'s <regex> and Eigen's
  # storage (through std::optional) that the Release build, which keeps the warning, does not show.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options(-Wno-maybe-uninitialized)
  endif()
endif()

# The test program is compiled at -O0 in this build: a third less compile time for its files, most of this
# build's; its own code is checked the same, only slower, and it mostly calls the library. The library binds
# its own function calls (-Bsymbolic-functions), so the -O0 copies of inline functions (Eigen's, ours) that the
# program carries never stand in for the library's own -O1 ones. Files named after OPTIMIZED run long loops of
# their own (brute-force references) and keep -O1, outside the unity batches. (The tool stays at -O1: at -O0
# its HTTP tests took longer than its compile saved.)
function(iarap_sanitized_program target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "OPTIMIZED")
  # Outside the unity batches in every build, so that both builds batch the same files (a name that two
  # files of one batch define would otherwise break one build only).
  set_source_files_properties(${arg_OPTIMIZED} TARGET_DIRECTORY ${target} PROPERTIES
    SKIP_UNITY_BUILD_INCLUSION ON)
  if(IARAP_SANITIZE)
    target_compile_options(${target} PRIVATE -O0)
    set_source_files_properties(${arg_OPTIMIZED} TARGET_DIRECTORY ${target} PROPERTIES
      COMPILE_OPTIONS -O1 SKIP_PRECOMPILE_HEADERS ON)
  endif()
endfunction()

function(iarap_sanitized_library target)
  if(IARAP_SANITIZE)
    target_link_options(${target} PRIVATE -Wl,-Bsymbolic-functions)
  endif()
endfunction()
