# Private interface target carrying the project's warning and sanitizer flags.
add_library(stochnav_warnings INTERFACE)
target_compile_options(stochnav_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion
  # C++20 designated initializers leave defaulted members out on purpose.
  -Wno-missing-field-initializers)
if(STOCHNAV_WERROR)
  target_compile_options(stochnav_warnings INTERFACE -Werror)
endif()
if(STOCHNAV_SANITIZE)
  target_compile_options(stochnav_warnings INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer)
  target_link_options(stochnav_warnings INTERFACE -fsanitize=address,undefined)
endif()
