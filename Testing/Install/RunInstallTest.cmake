# Installs the build tree into a private prefix, then configures, builds and runs a consumer
# project against it: the installed CMake package config must be complete on its own.
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... [-DSANITIZE=address,undefined]
#         -P RunInstallTest.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
function (run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "Command failed (${rc}): ${ARGN}\n${out}")
  endif ()
endfunction ()
run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix")
# A sanitized Refracta needs a sanitized consumer (the runtime must come first in the link).
set(flags "")
if (SANITIZE)
  set(flags "-DCMAKE_CXX_FLAGS=-fsanitize=${SANITIZE}")
endif ()
run("${CMAKE_COMMAND}" -S "${SOURCE_DIR}/Consumer" -B "${WORK_DIR}/consumer"
  "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix" -DCMAKE_BUILD_TYPE=Release ${flags})
run("${CMAKE_COMMAND}" --build "${WORK_DIR}/consumer")
run("${WORK_DIR}/consumer/consumer")
message(STATUS "installed package found, consumer built and ran")
