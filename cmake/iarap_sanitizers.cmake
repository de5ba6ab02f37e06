# IARAP_SANITIZE=ON: the whole build (library, tool, tests) under ASan + UBSan.
if(IARAP_SANITIZE)
  # -O1 keeps the instrumented build quick to compile and still readable in reports.
  # UBSan traps instead of calling its runtime: its runtime calls carry a static record per check (source
  # location, type names) with a pointer the loader relocates at every start, 2.2M relocations and 62 MB of
  # data in the test program alone, about 0.8 s per test process (CTest starts one per test). A trapped
  # check stops the process with SIGILL, and ASan prints its stack (ASAN_OPTIONS=handle_sigill=1, which
  # scripts/test.sh sets) down to the file and line of the undefined operation.
  # UBSan's null and alignment checks are left out: they guard every pointer and reference Eigen forms
  # and were two thirds of UBSan's compile time (laplacian_properties.cpp: 81 s with them, 57 without, 53
  # without UBSan), while ASan already stops a null dereference (SEGV, with its stack) and x86 reads
  # unaligned data correctly.
  add_compile_options(-fsanitize=address,undefined -fno-sanitize=null,alignment -fsanitize-undefined-trap-on-error
    -fno-omit-frame-pointer -O1)
  add_link_options(-fsanitize=address,undefined)
  # The instrumentation makes GCC 12 report maybe-uninitialized reads inside libstdc++'s <regex> and Eigen's
  # storage (through std::optional) that the Release build, which keeps the warning, does not show.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options(-Wno-maybe-uninitialized)
  endif()
endif()
