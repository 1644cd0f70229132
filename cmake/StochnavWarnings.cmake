# Private interface target carrying the project's warning and sanitizer flags. Everything the
# project builds links it: the framework, the CLI, the plugins, the tests and the fuzz targets.
add_library(stochnav_warnings INTERFACE)
target_compile_options(stochnav_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion
  # C++20 designated initializers leave defaulted members out on purpose.
  -Wno-missing-field-initializers)
# A unity source #includes the .cpp files, so GCC takes a pimpl's members of anonymous-namespace
# types (SampleReader::Impl, DavarAccumulator::Impl) for a header's and warns: spurious there;
# ordinary builds keep the warning, where it means something.
if(CMAKE_UNITY_BUILD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(stochnav_warnings INTERFACE -Wno-subobject-linkage)
endif()
if(STOCHNAV_WERROR)
  target_compile_options(stochnav_warnings INTERFACE -Werror)
endif()
if(STOCHNAV_SANITIZE)
  # GCC 12 at -O1 with these sanitizers reports libstdc++'s std::regex (std::function inside
  # _StateT) as maybe-uninitialized in cli_catalogue_tests: a flow-analysis false positive of
  # the instrumented code. The warning stays an error in the release build.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(stochnav_warnings INTERFACE -Wno-maybe-uninitialized)
  endif()
  # Every undefined-behaviour check but `null` and `alignment`: with Eigen those two instrument
  # every element access and took the instrumented compile from 44 s to 94 s on a unity batch
  # (GCC 12, -O1), the whole stage past CI's time. The address sanitizer reports a null
  # dereference itself (SEGV on unknown address 0x0), and Eigen asserts the alignment of its
  # fixed-size objects (assertions stay on in this build).
  target_compile_options(stochnav_warnings INTERFACE -fsanitize=address,undefined
                         -fno-sanitize=null,alignment -fno-omit-frame-pointer)
  target_link_options(stochnav_warnings INTERFACE -fsanitize=address,undefined)
endif()
if(STOCHNAV_THREAD_SANITIZE)
  target_compile_options(stochnav_warnings INTERFACE -fsanitize=thread)
  target_link_options(stochnav_warnings INTERFACE -fsanitize=thread)
endif()
