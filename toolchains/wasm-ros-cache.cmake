# colcon-wasm initial cache (`cmake -C`): what a ROS 2 workspace needs when
# cross-compiled to WebAssembly. Values given with -D on the command line
# (recipe cmake-args, then the user's --cmake-args) override these.

# static libraries only: WebAssembly has no dlopen here
set(BUILD_SHARED_LIBS OFF CACHE BOOL "colcon-wasm: static libraries only")
# tests: with --wasm-tests (COLCON_WASM_TESTS, see toolchains/wasm-ros-tests.cmake)
if(COLCON_WASM_TESTS)
  set(BUILD_TESTING ON CACHE BOOL "colcon-wasm: --wasm-tests" FORCE)
else()
  set(BUILD_TESTING OFF CACHE BOOL "colcon-wasm: tests are built with --wasm-tests" FORCE)
endif()

# the settings of the --wasm options: no defaults here (colcon_wasm/options.py)
include("${CMAKE_CURRENT_LIST_DIR}/wasm-ros-require.cmake")
colcon_wasm_require(COLCON_WASM_DEBUG COLCON_WASM_OPT_LEVEL COLCON_WASM_LINK_OPT_LEVEL)

if(COLCON_WASM_DEBUG)
  set(CMAKE_BUILD_TYPE Debug CACHE STRING "colcon-wasm: --wasm-debug")
else()
  set(CMAKE_BUILD_TYPE Release CACHE STRING "colcon-wasm: default build type")
endif()

# The Release and Debug flags: the one place they are set. As cache values
# (not the toolchain's *_INIT defaults) because CMake appends "-O3 -DNDEBUG"
# to those, which would override --wasm-opt-level.
foreach(_lang C CXX)
  set(CMAKE_${_lang}_FLAGS_RELEASE "-O${COLCON_WASM_OPT_LEVEL} -DNDEBUG" CACHE STRING
    "colcon-wasm: --wasm-opt-level")
  set(CMAKE_${_lang}_FLAGS_DEBUG "-g -O0" CACHE STRING "colcon-wasm: --wasm-debug")
endforeach()
set(CMAKE_EXE_LINKER_FLAGS_RELEASE "-O${COLCON_WASM_LINK_OPT_LEVEL}" CACHE STRING
  "colcon-wasm: --wasm-link-opt-level")
set(CMAKE_EXE_LINKER_FLAGS_DEBUG "-g -O0 -sASSERTIONS=2" CACHE STRING
  "colcon-wasm: --wasm-debug")

# one middleware, linked statically, no runtime selection (no dlopen)
set(RMW_IMPLEMENTATION rmw_wasm_cpp CACHE STRING "colcon-wasm: the one RMW")
set(RMW_IMPLEMENTATION_DISABLE_RUNTIME_SELECTION ON CACHE BOOL
  "colcon-wasm: no dlopen, the RMW is linked")
# Introspection type supports only: the recipe skips the DDS type support
# generators (rosidl_typesupport_fastrtps_c/cpp), so rosidl registers no other.
set(RCL_LOGGING_IMPLEMENTATION rcl_logging_noop CACHE STRING
  "colcon-wasm: no spdlog file logging in the browser")
set(TRACETOOLS_DISABLED ON CACHE BOOL "colcon-wasm: no LTTng in the browser")

# no host pkg-config: it would find host (x86) libraries
set(PKG_CONFIG_EXECUTABLE "PKG_CONFIG_EXECUTABLE-NOTFOUND" CACHE FILEPATH
  "colcon-wasm: no host pkg-config")

# vendor packages: never download or build a bundled copy when one is installed
set(FORCE_BUILD_VENDOR_PKG OFF CACHE BOOL "colcon-wasm: use installed packages")
