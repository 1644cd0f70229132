# install -> relocate -> out-of-tree build -> load -> run, against the installed package only.
#   cmake -DBUILD_DIR=<stochnav build> -DSOURCE_DIR=<stochnav source> -DWORK_DIR=<scratch>
#         -DAPI_VERSION=<plugin API version> [-DGENERATOR=Ninja] -P package_test.cmake
cmake_minimum_required(VERSION 3.25)
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR API_VERSION)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "package_test: -D${var}= missing")
  endif()
endforeach()
if(NOT GENERATOR)
  set(GENERATOR "Ninja")
endif()

function(run)
  cmake_parse_arguments(ARG "" "EXPECT;OUTPUT" "COMMAND;ENV" ${ARGN})
  if(NOT DEFINED ARG_EXPECT)
    set(ARG_EXPECT 0)
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E env ${ARG_ENV} ${ARG_COMMAND}
    RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "$ ${ARG_COMMAND}\n${out}${err}")
  if(NOT code EQUAL ARG_EXPECT)
    message(FATAL_ERROR "exit code ${code}, expected ${ARG_EXPECT}: ${ARG_COMMAND}")
  endif()
  if(ARG_OUTPUT)
    set(${ARG_OUTPUT} "${out}${err}" PARENT_SCOPE)
  endif()
endfunction()

function(expect_match text pattern)
  if(NOT text MATCHES "${pattern}")
    message(FATAL_ERROR "output does not match '${pattern}'")
  endif()
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# Install, then move the prefix: the package must not remember where it was installed.
run(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/staging")
file(RENAME "${WORK_DIR}/staging" "${WORK_DIR}/prefix")
set(prefix "${WORK_DIR}/prefix")
set(stochnav "${prefix}/bin/stochnav")
# The documentation is installed with the package, its relative links intact.
foreach(doc README.md docs/user-guide.md docs/config-reference.md docs/sdk.md plugins/README.md)
  if(NOT EXISTS "${prefix}/share/doc/stochnav/${doc}")
    message(FATAL_ERROR "the package lacks share/doc/stochnav/${doc}")
  endif()
endforeach()
# No build-tree paths may leak into the installed tool's search.
set(clean_env "--unset=STOCHNAV_PLUGIN_PATH")

run(COMMAND "${stochnav}" plugins list ENV ${clean_env} OUTPUT listing)
expect_match("${listing}" "noise +white +${API_VERSION} +yes +${prefix}/lib[^ ]*/stochnav/plugins/stochnav_noise_white.so")
expect_match("${listing}" "gauss_markov")

foreach(example custom_noise_plugin custom_aid_plugin embed_runtime)
  run(COMMAND ${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples/${example}" -B "${WORK_DIR}/${example}"
              -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}")
  run(COMMAND ${CMAKE_COMMAND} --build "${WORK_DIR}/${example}")
endforeach()

set(plugin "${WORK_DIR}/custom_noise_plugin/stochnav_second_order_gauss_markov.so")
run(COMMAND "${stochnav}" plugins check "${plugin}" ENV ${clean_env} OUTPUT checked)
expect_match("${checked}" "noise +second_order_gauss_markov +${API_VERSION} +no")

# The plugin formats with fmt (it linked with --no-undefined against stochnav::framework alone)
# and passes the property checks, through the CLI and through the installed GoogleTest suite.
run(COMMAND "${stochnav}" plugins check "${plugin}" --params "{\"sigma\": 0.5, \"tau_c\": 30}"
    ENV ${clean_env} OUTPUT properties)
expect_match("${properties}" "second_order_gauss_markov \\(gyro\\): sigma = 0.5 deg/h, tau_c = 30 s; driving PSD")
expect_match("${properties}" "properties: .* hold")
run(COMMAND "${stochnav}" plugins check "${plugin}" --params "{\"sigma\": 0.5, \"tauc\": 30}"
    EXPECT 2 ENV ${clean_env} OUTPUT typo)
expect_match("${typo}" "--params/tauc: unknown key 'tauc'; did you mean 'tau_c'\\?")
run(COMMAND "${WORK_DIR}/custom_noise_plugin/second_order_gauss_markov_properties"
    ENV ${clean_env} OUTPUT suite)
expect_match("${suite}" "PASSED.* 10 tests")

# The out-of-tree aid passes the aid checks through the CLI and the installed GoogleTest suite,
# and the CLI rejects a survey that disagrees with the true state.
set(aid_plugin "${WORK_DIR}/custom_aid_plugin/stochnav_inclination_survey.so")
set(survey "${WORK_DIR}/custom_aid_plugin/survey.csv")
run(COMMAND "${stochnav}" plugins check "${aid_plugin}" --params "{\"sigma_deg\": 0.2}"
    --aid-data "${survey}" ENV ${clean_env} OUTPUT aid_checked)
expect_match("${aid_checked}" "aid +inclination_survey +${API_VERSION}")
expect_match("${aid_checked}"
  "aid: inclination_survey: surveyed inclination against the attitude's; column = \"inclination_deg\", sigma_deg = 0.2 deg")
expect_match("${aid_checked}" "properties: .* hold at t = 1 s")
run(COMMAND "${stochnav}" plugins check "${aid_plugin}" --params "{}" --aid-data "${survey}"
    --state "{\"inclination_deg\": 61}" EXPECT 2 ENV ${clean_env} OUTPUT aid_wrong)
expect_match("${aid_wrong}" "truth: z\\(0\\) = 0.0174533 at the true state")
run(COMMAND "${WORK_DIR}/custom_aid_plugin/inclination_survey_properties"
    ENV ${clean_env} OUTPUT aid_suite)
expect_match("${aid_suite}" "PASSED.* 10 tests")

# Found through STOCHNAV_PLUGIN_PATH, and through the config's folder.
run(COMMAND "${stochnav}" plugins list ENV "STOCHNAV_PLUGIN_PATH=${WORK_DIR}/custom_noise_plugin"
    OUTPUT listing)
expect_match("${listing}" "second_order_gauss_markov")
run(COMMAND "${stochnav}" plugins show "${WORK_DIR}/custom_noise_plugin/run.json" ENV ${clean_env}
    OUTPUT shown)
expect_match("${shown}" "error state: 21 states")
expect_match("${shown}" "gyro.second_order_gauss_markov +offset +15 +size 6")

# The embedding program: the demo (fit from simulated data), then the custom plugin's config.
run(COMMAND "${WORK_DIR}/embed_runtime/embed_runtime" --check ENV ${clean_env} OUTPUT demo)
expect_match("${demo}" "gauss_markov \\(gyro\\)")
expect_match("${demo}" "gyro.gauss_markov +3 states")
# The host's first 600 s aligned by the streaming aligner, the filter started from its result.
run(COMMAND "${WORK_DIR}/embed_runtime/embed_runtime" --align 600 --check ENV ${clean_env}
    OUTPUT aligned)
expect_match("${aligned}" "aligned over 600 s: heading sigma")
run(COMMAND "${WORK_DIR}/embed_runtime/embed_runtime" "${WORK_DIR}/custom_noise_plugin/run.json"
            --check ENV ${clean_env} OUTPUT custom)
expect_match("${custom}" "second_order_gauss_markov \\(gyro\\)")

# A config naming a plugin nobody provides: exit code 2 with the pointer.
file(WRITE "${WORK_DIR}/bad.json" "{\"data\": {\"imu\": \"custom_noise_plugin/imu.csv\"}, \"noise\": {\"gyro\": {\"plugin\": \"nope\"}, \"accel\": {\"plugin\": \"white\", \"params\": {\"N\": 1}}}}")
run(COMMAND "${stochnav}" plugins show "${WORK_DIR}/bad.json" EXPECT 2 ENV ${clean_env} OUTPUT bad)
expect_match("${bad}" "/noise/gyro/plugin: unknown noise plugin type 'nope'")
message(STATUS "package test passed")
