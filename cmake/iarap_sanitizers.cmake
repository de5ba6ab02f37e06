# IARAP_SANITIZE=ON: the whole build (library, tool, tests) under ASan + UBSan.
if(IARAP_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
