# CTest driver (cmake -P): installs the iarap build into a temporary prefix, then configures, builds and
# runs tests/consumer against it. Variables: BUILD_DIR (the iarap build), SOURCE_DIR (tests/consumer),
# WORK_DIR (scratch), MESH (a mesh to read), GENERATOR, BUILD_TYPE, SANITIZE (ON: the build uses ASan/UBSan).
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR MESH GENERATOR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_consumer_test.cmake: ${var} not set")
  endif()
endforeach()

function(run_step name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "consumer test: ${name} failed (${result}):\n${output}")
  endif()
  message(STATUS "consumer test: ${name}: ok")
  set(step_output "${output}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
run_step(install ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")

set(flags "")
if(SANITIZE)
  set(flags "-fsanitize=address,undefined")
endif()
run_step(configure ${CMAKE_COMMAND} -S "${SOURCE_DIR}" -B "${WORK_DIR}/build" -G "${GENERATOR}"
  "-DCMAKE_PREFIX_PATH=${prefix}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}" "-DCMAKE_CXX_FLAGS=${flags}"
  "-DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON")
run_step(build ${CMAKE_COMMAND} --build "${WORK_DIR}/build")
run_step(run "${WORK_DIR}/build/consumer" "${MESH}")
if(NOT step_output MATCHES "vertices [0-9]+ faces [0-9]+")
  message(FATAL_ERROR "consumer test: unexpected output:\n${step_output}")
endif()
message(STATUS "consumer test: ${step_output}")
