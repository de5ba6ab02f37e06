# IARAP_SANITIZE=ON: the whole build (library, tool, tests) under ASan + UBSan.
if(IARAP_SANITIZE)
  # -O1 keeps the instrumented build quick to compile and still readable in reports.
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined -O1)
  add_link_options(-fsanitize=address,undefined)
endif()
