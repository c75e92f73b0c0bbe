# ALEGO_SANITIZE=ON builds every target of the package with AddressSanitizer (leak checking
# included) and UndefinedBehaviorSanitizer; scripts/test.sh --sanitize uses it. Undefined
# behaviour aborts instead of printing and going on, so that the test that hits it fails.
option(ALEGO_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
if(ALEGO_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer)
  # Line tables only: file:line in sanitizer stacks without the size of full debug info.
  if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    add_compile_options(-gline-tables-only)
  else()
    add_compile_options(-g1)
  endif()
  add_link_options(-fsanitize=address,undefined)
endif()
