# colcon-wasm toolchain layer over Emscripten's own toolchain file.
#
# colcon-wasm passes these cache variables (see colcon_wasm/cmake_args.py):
#   COLCON_WASM_EMSCRIPTEN_ROOT  Emscripten root (holds cmake/Modules/Platform)
#   COLCON_WASM_EMSCRIPTEN_BIN   folder of emcc, em++, emar, emranlib
#   COLCON_WASM_INSTALL_BASE     the wasm install base (packages find each other there)
#   COLCON_WASM_PTHREAD          ON/OFF: -pthread when compiling and linking
#   COLCON_WASM_PTHREAD_POOL_SIZE  workers started with each executable
#   COLCON_WASM_DEBUG            ON: -g and -sASSERTIONS=2
#   COLCON_WASM_OPT_LEVEL        1, 2, 3, s or z (Release flags)
#   COLCON_WASM_ENV              KEY=VALUE;... set while CMake configures (recipe env)
# This file is read again for every try_compile: the variables are forwarded
# through CMAKE_TRY_COMPILE_PLATFORM_VARIABLES.

set(_colcon_wasm_vars
  COLCON_WASM_EMSCRIPTEN_ROOT COLCON_WASM_EMSCRIPTEN_BIN COLCON_WASM_INSTALL_BASE
  COLCON_WASM_PTHREAD COLCON_WASM_PTHREAD_POOL_SIZE COLCON_WASM_DEBUG
  COLCON_WASM_OPT_LEVEL COLCON_WASM_ENV)
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES ${_colcon_wasm_vars})

if(NOT COLCON_WASM_EMSCRIPTEN_ROOT)
  message(FATAL_ERROR "colcon-wasm: COLCON_WASM_EMSCRIPTEN_ROOT is not set; "
    "this toolchain file is meant to be used through `colcon build --wasm`")
endif()
if(NOT DEFINED COLCON_WASM_PTHREAD)
  set(COLCON_WASM_PTHREAD ON)
endif()
if(NOT DEFINED COLCON_WASM_PTHREAD_POOL_SIZE OR COLCON_WASM_PTHREAD_POOL_SIZE STREQUAL "")
  set(COLCON_WASM_PTHREAD_POOL_SIZE 4)
endif()
if(NOT COLCON_WASM_OPT_LEVEL)
  set(COLCON_WASM_OPT_LEVEL 2)
endif()

# the recipe's per-package environment, for the configure step
foreach(_colcon_wasm_kv IN LISTS COLCON_WASM_ENV)
  string(FIND "${_colcon_wasm_kv}" "=" _colcon_wasm_eq)
  if(_colcon_wasm_eq GREATER 0)
    string(SUBSTRING "${_colcon_wasm_kv}" 0 ${_colcon_wasm_eq} _colcon_wasm_key)
    math(EXPR _colcon_wasm_eq "${_colcon_wasm_eq} + 1")
    string(SUBSTRING "${_colcon_wasm_kv}" ${_colcon_wasm_eq} -1 _colcon_wasm_value)
    set(ENV{${_colcon_wasm_key}} "${_colcon_wasm_value}")
  endif()
endforeach()

# the compilers of the chosen Emscripten, not whichever emcc is first on PATH
if(COLCON_WASM_EMSCRIPTEN_BIN)
  set(CMAKE_C_COMPILER "${COLCON_WASM_EMSCRIPTEN_BIN}/emcc" CACHE FILEPATH "Emscripten emcc")
  set(CMAKE_CXX_COMPILER "${COLCON_WASM_EMSCRIPTEN_BIN}/em++" CACHE FILEPATH "Emscripten em++")
  set(CMAKE_AR "${COLCON_WASM_EMSCRIPTEN_BIN}/emar" CACHE FILEPATH "Emscripten ar")
  set(CMAKE_RANLIB "${COLCON_WASM_EMSCRIPTEN_BIN}/emranlib" CACHE FILEPATH "Emscripten ranlib")
endif()
set(EMSCRIPTEN_ROOT_PATH "${COLCON_WASM_EMSCRIPTEN_ROOT}")
include("${COLCON_WASM_EMSCRIPTEN_ROOT}/cmake/Modules/Platform/Emscripten.cmake")

# Packages find each other in the install space: Emscripten.cmake searches
# packages, libraries and headers ONLY under CMAKE_FIND_ROOT_PATH. Prefixes
# that already lie under a root path are not re-rooted, so adding the install
# base makes every package installed there visible, and nothing of the host.
if(COLCON_WASM_INSTALL_BASE)
  list(APPEND CMAKE_FIND_ROOT_PATH "${COLCON_WASM_INSTALL_BASE}")
endif()

# flags for every compile and link
set(_colcon_wasm_common "-fexceptions")
if(COLCON_WASM_PTHREAD)
  string(APPEND _colcon_wasm_common " -pthread")
endif()
string(APPEND CMAKE_C_FLAGS_INIT " ${_colcon_wasm_common}")
string(APPEND CMAKE_CXX_FLAGS_INIT " ${_colcon_wasm_common}")

set(_colcon_wasm_link "${_colcon_wasm_common} -sALLOW_MEMORY_GROWTH=1 -sENVIRONMENT=web,worker,node -sEXIT_RUNTIME=1")
if(COLCON_WASM_PTHREAD)
  string(APPEND _colcon_wasm_link " -sPTHREAD_POOL_SIZE=${COLCON_WASM_PTHREAD_POOL_SIZE} -Wno-pthreads-mem-growth")
endif()
string(APPEND CMAKE_EXE_LINKER_FLAGS_INIT " ${_colcon_wasm_link}")

# Release (the default build type, see wasm-ros-cache.cmake)
set(CMAKE_C_FLAGS_RELEASE_INIT "-O${COLCON_WASM_OPT_LEVEL} -DNDEBUG")
set(CMAKE_CXX_FLAGS_RELEASE_INIT "-O${COLCON_WASM_OPT_LEVEL} -DNDEBUG")
set(CMAKE_EXE_LINKER_FLAGS_RELEASE_INIT "-O${COLCON_WASM_OPT_LEVEL}")
# debug mode
set(CMAKE_C_FLAGS_DEBUG_INIT "-g -O0")
set(CMAKE_CXX_FLAGS_DEBUG_INIT "-g -O0")
set(CMAKE_EXE_LINKER_FLAGS_DEBUG_INIT "-g -O0 -sASSERTIONS=2")

# no dlopen: static libraries only
set_property(GLOBAL PROPERTY TARGET_SUPPORTS_SHARED_LIBS FALSE)
