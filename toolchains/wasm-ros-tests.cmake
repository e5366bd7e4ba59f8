# colcon-wasm: tests (--wasm-tests) and fault injection (--wasm-fault-injection).
#
# Included by wasm-ros.cmake (it may be read several times per project). Cache
# variables (colcon_wasm/testing/options.py):
#   COLCON_WASM_TESTS            ON: this package's tests are built (BUILD_TESTING=ON,
#                                see wasm-ros-cache.cmake)
#   COLCON_WASM_FAULT_INJECTION  ON: every package is compiled with
#                                RCUTILS_ENABLE_FAULT_INJECTION
#   COLCON_WASM_NODE             the Node.js that runs tests (default: node on PATH)

list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES
  COLCON_WASM_TESTS COLCON_WASM_FAULT_INJECTION COLCON_WASM_NODE)

# rcutils' test build defines RCUTILS_ENABLE_FAULT_INJECTION for itself and
# every package that uses it (a PUBLIC definition): the fault injection
# points (RCUTILS_CAN_RETURN_WITH_ERROR_OF, ...) of rcutils, rmw, rcl and
# the middleware are compiled in, and RCUTILS_FAULT_INJECTION_TEST can make
# each of them fail in turn.
if(COLCON_WASM_FAULT_INJECTION AND NOT _colcon_wasm_fault_injection_appended)
  set(_colcon_wasm_fault_injection_appended TRUE)
  string(APPEND CMAKE_C_FLAGS_INIT " -DRCUTILS_ENABLE_FAULT_INJECTION")
  string(APPEND CMAKE_CXX_FLAGS_INIT " -DRCUTILS_ENABLE_FAULT_INJECTION")
endif()

if(NOT COLCON_WASM_TESTS)
  return()
endif()

# CTest runs an executable target given as a test command
# (add_test(NAME n COMMAND target)) with Node.js. gtest and gmock
# executables also run by themselves (the link launcher, below).
if(NOT COLCON_WASM_NODE)
  find_program(COLCON_WASM_NODE NAMES node nodejs NO_CMAKE_FIND_ROOT_PATH)
endif()
if(COLCON_WASM_NODE)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${COLCON_WASM_NODE}")
endif()

# ament_lint_auto's linters (copyright, cpplint, uncrustify, ...) are Python
# tools that check the package's sources, the same for every target: they
# belong to the native build. `colcon test --wasm` records each one the
# package asks for as skipped, with that reason (colcon_wasm/testing/results.py).
if(NOT DEFINED AMENT_LINT_AUTO_EXCLUDE)
  set(AMENT_LINT_AUTO_EXCLUDE
    ament_cmake_clang_format ament_cmake_clang_tidy ament_cmake_copyright
    ament_cmake_cppcheck ament_cmake_cpplint ament_cmake_flake8
    ament_cmake_lint_cmake ament_cmake_mypy ament_cmake_pclint ament_cmake_pep257
    ament_cmake_pycodestyle ament_cmake_pyflakes ament_cmake_uncrustify
    ament_cmake_xmllint)
endif()

# Launch tests (add_launch_test) run Python launch_testing, which is not built
# for WebAssembly; and launch_testing_ament_cmake needs python_cmake_module,
# which looks for the target's CPython. Packages find it QUIET (ament_lint_auto
# does) and go without their launch tests.
if(NOT DEFINED CMAKE_DISABLE_FIND_PACKAGE_launch_testing_ament_cmake)
  set(CMAKE_DISABLE_FIND_PACKAGE_launch_testing_ament_cmake TRUE)
endif()

# The link launcher makes every executable that links gtest or gmock a
# Node.js test program (colcon_wasm/link/test_link.py).
get_property(_colcon_wasm_rule GLOBAL PROPERTY RULE_LAUNCH_LINK)
if(_colcon_wasm_rule AND NOT _colcon_wasm_rule MATCHES "--test-pre-js")
  string(REGEX REPLACE " --$"
    " --test-pre-js ${CMAKE_CURRENT_LIST_DIR}/test/node_test_pre.js --"
    _colcon_wasm_rule "${_colcon_wasm_rule}")
  set_property(GLOBAL PROPERTY RULE_LAUNCH_LINK "${_colcon_wasm_rule}")
endif()
unset(_colcon_wasm_rule)
