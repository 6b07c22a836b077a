# Helpers for Refracta's tests.
#
# refracta_add_gtest(NAME <name> SOURCES <files...> LINK <targets...> [LABELS <labels...>]
#                    [TIMEOUT <s>] [ENVIRONMENT <vars...>] [NEEDS_RENDER_WINDOW])
# builds one GoogleTest executable and registers it as one ctest test. NEEDS_RENDER_WINDOW: the
# program skips its tests where no render window can be opened (MapperTestUtilities.h), and
# ctest then reports it as skipped rather than passed. Every test gets private kernel caches
# inside the build tree (PoCL's in POCL_CACHE_DIR; Refracta's binary cache in XDG_CACHE_HOME's
# refracta/kernels, used on drivers without a cache of their own: on PoCL it stays off unless a
# test names a folder, vtkOpenCLContext::GetDriverCachesPrograms), so timings and results never
# depend on a warm home directory.
include(GoogleTest)

set(REFRACTA_TEST_ENVIRONMENT
  "POCL_CACHE_DIR=${CMAKE_BINARY_DIR}/Testing/pocl-cache"
  "XDG_CACHE_HOME=${CMAKE_BINARY_DIR}/Testing/cache"
  "REFRACTA_DATA_DIR=${CMAKE_SOURCE_DIR}/Data"
  "REFRACTA_TEST_OUTPUT_DIR=${CMAKE_BINARY_DIR}/Testing/Temporary"
  "REFRACTA_BASELINE_DIR=${CMAKE_SOURCE_DIR}/Testing/Baselines")

# refracta_test_needs_render_window(<test>): the test prints "no render window: <reason>" and
# stops where vtkRefractaRenderWindowCheck::CanOpen() is false (no X server for an X11 VTK);
# ctest then reports it as skipped, not failed and not passed.
function (refracta_test_needs_render_window name)
  set_tests_properties(${name} PROPERTIES SKIP_REGULAR_EXPRESSION "no render window: ")
endfunction ()

function (refracta_add_gtest)
  cmake_parse_arguments(PARSE_ARGV 0 arg "NEEDS_RENDER_WINDOW" "NAME;TIMEOUT" "SOURCES;LINK;LABELS;ENVIRONMENT")
  add_executable(${arg_NAME} ${arg_SOURCES})
  target_link_libraries(${arg_NAME} PRIVATE ${arg_LINK} GTest::gtest GTest::gtest_main)
  add_test(NAME ${arg_NAME} COMMAND ${arg_NAME} --gtest_color=no)
  if (NOT arg_TIMEOUT)
    set(arg_TIMEOUT 300)
  endif ()
  set_tests_properties(${arg_NAME} PROPERTIES
    TIMEOUT ${arg_TIMEOUT}
    LABELS "${arg_LABELS}"
    ENVIRONMENT "${REFRACTA_TEST_ENVIRONMENT};${arg_ENVIRONMENT}")
  if (arg_NEEDS_RENDER_WINDOW)
    refracta_test_needs_render_window(${arg_NAME})
  endif ()
endfunction ()

# refracta_add_python_test(NAME <name> SCRIPT <file> [LABELS ...] [ARGS ...] [NEEDS_RENDER_WINDOW])
# runs a script with the system Python (ParaView's VTK) and the build tree's refracta package on
# PYTHONPATH.
function (refracta_add_python_test)
  cmake_parse_arguments(PARSE_ARGV 0 arg "NEEDS_RENDER_WINDOW" "NAME;SCRIPT;TIMEOUT" "LABELS;ARGS")
  if (NOT REFRACTA_WRAP_PYTHON)
    return ()
  endif ()
  add_test(NAME ${arg_NAME} COMMAND "${Python3_EXECUTABLE}" "${arg_SCRIPT}" ${arg_ARGS})
  if (NOT arg_TIMEOUT)
    set(arg_TIMEOUT 300)
  endif ()
  set_tests_properties(${arg_NAME} PROPERTIES
    TIMEOUT ${arg_TIMEOUT}
    LABELS "python;${arg_LABELS}"
    ENVIRONMENT "${REFRACTA_TEST_ENVIRONMENT};PYTHONPATH=${CMAKE_BINARY_DIR}/${REFRACTA_PYTHON_SITE}")
  if (arg_NEEDS_RENDER_WINDOW)
    refracta_test_needs_render_window(${arg_NAME})
  endif ()
endfunction ()
