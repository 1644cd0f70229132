# stochnav_add_plugin(<target> KIND noise|aid SOURCES <src>...
#                     [OUTPUT_DIRECTORY <dir>] [INSTALL_DESTINATION <dir>])
#
# Builds a stochnav plugin: a MODULE library named stochnav_<target>.so (the loader scans for
# stochnav_*.so), linked with stochnav::framework and -Wl,--no-undefined (so a missing symbol
# fails the link, not the load), with hidden visibility (only the Boost.DLL aliases of the
# STOCHNAV_*_PLUGIN macro are exported). Shipped in the installed package and used by the
# in-tree plugins too, so the third-party path is built by every build.
#
#   OUTPUT_DIRECTORY     where the library is built (default: the current binary folder).
#                        Put it in a folder on the plugin search path (the config's folder,
#                        $STOCHNAV_PLUGIN_PATH) to have stochnav find it.
#   INSTALL_DESTINATION  install the library there (e.g. ${stochnav_PLUGIN_INSTALL_DIR}).
function(stochnav_add_plugin target)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "KIND;OUTPUT_DIRECTORY;INSTALL_DESTINATION" "SOURCES")
  if(NOT ARG_KIND MATCHES "^(noise|aid)$")
    message(FATAL_ERROR "stochnav_add_plugin(${target}): KIND must be noise or aid, got '${ARG_KIND}'")
  endif()
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "stochnav_add_plugin(${target}): SOURCES missing")
  endif()
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "stochnav_add_plugin(${target}): unknown arguments ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE stochnav::framework)
  target_compile_features(${target} PRIVATE cxx_std_20)
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    OUTPUT_NAME "stochnav_${target}"
    STOCHNAV_PLUGIN_KIND "${ARG_KIND}"
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  # Sanitizer runtimes leave symbols to the executable: no --no-undefined under them.
  if(NOT STOCHNAV_SANITIZE AND NOT STOCHNAV_THREAD_SANITIZE
     AND NOT CMAKE_CXX_FLAGS MATCHES "-fsanitize")
    target_link_options(${target} PRIVATE "LINKER:--no-undefined")
  endif()
  if(ARG_OUTPUT_DIRECTORY)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY "${ARG_OUTPUT_DIRECTORY}")
  endif()
  if(ARG_INSTALL_DESTINATION)
    install(TARGETS ${target} LIBRARY DESTINATION "${ARG_INSTALL_DESTINATION}")
  endif()
endfunction()
