# colcon-wasm toolchain layer over Emscripten's own toolchain file.
#
# colcon-wasm passes these cache variables (see colcon_wasm/options.py, whose
# OPTIONS table maps each --wasm option to its variable and holds the
# defaults; an unset setting stops the configure, see wasm-ros-require.cmake):
#   COLCON_WASM_EMSCRIPTEN_ROOT  Emscripten root (holds cmake/Modules/Platform)
#   COLCON_WASM_EMSCRIPTEN_BIN   folder of emcc, em++, emar, emranlib
#   COLCON_WASM_INSTALL_BASE     the wasm install base (packages find each other there)
#   COLCON_WASM_PTHREAD          ON/OFF: -pthread when compiling and linking
#   COLCON_WASM_PTHREAD_POOL_SIZE  workers started with each executable
#   COLCON_WASM_DEBUG            ON: -g and -sASSERTIONS=2
#   COLCON_WASM_OPT_LEVEL        1, 2, 3, s or z (Release compile flags)
#   COLCON_WASM_LINK_OPT_LEVEL   0, 1, 2, 3, s or z (Release link flags)
#   COLCON_WASM_ENV              KEY=VALUE;... set while CMake configures (recipe env)
#   COLCON_WASM_PYTHON           the interpreter running colcon (runs the compile launcher)
#   COLCON_WASM_COMPILER_LAUNCHER  ON (default when COLCON_WASM_PYTHON is set): compile
#                                through colcon_wasm/compile_launcher.py (clang directly)
#   COLCON_WASM_LAUNCHER_SCRIPT  that script; COLCON_WASM_LAUNCHER_CACHE: its cache folder
#   COLCON_WASM_LINK_LAUNCHER_SCRIPT  colcon_wasm/link/launcher.py: runs every executable link
#                                (RULE_LAUNCH_LINK), see colcon_wasm/link/__init__.py
#   COLCON_WASM_LLVM_NM, COLCON_WASM_LLVM_CXXFILT  the LLVM tools of the Emscripten in use
#   COLCON_WASM_UNDERLAYS        install bases of the underlays (a list), highest priority first
# This file is read again for every try_compile: the variables are forwarded
# through CMAKE_TRY_COMPILE_PLATFORM_VARIABLES, and so are the results of the
# probes below (COLCON_WASM_PROBED_*), which run once per build folder.

set(_colcon_wasm_vars
  COLCON_WASM_EMSCRIPTEN_ROOT COLCON_WASM_EMSCRIPTEN_BIN COLCON_WASM_INSTALL_BASE
  COLCON_WASM_PTHREAD COLCON_WASM_PTHREAD_POOL_SIZE COLCON_WASM_DEBUG
  COLCON_WASM_OPT_LEVEL COLCON_WASM_LINK_OPT_LEVEL COLCON_WASM_ENV COLCON_WASM_PYTHON
  COLCON_WASM_COMPILER_LAUNCHER COLCON_WASM_LAUNCHER_SCRIPT COLCON_WASM_LAUNCHER_CACHE
  COLCON_WASM_LINK_LAUNCHER_SCRIPT COLCON_WASM_LLVM_NM COLCON_WASM_LLVM_CXXFILT
  COLCON_WASM_UNDERLAYS
  COLCON_WASM_PROBED_CLANG_VERSION COLCON_WASM_PROBED_EMSCRIPTEN_VERSION
  COLCON_WASM_PROBED_CACHE)
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES ${_colcon_wasm_vars})

# the settings of the --wasm options: no defaults here (colcon_wasm/options.py)
include("${CMAKE_CURRENT_LIST_DIR}/wasm-ros-require.cmake")
colcon_wasm_require(COLCON_WASM_EMSCRIPTEN_ROOT COLCON_WASM_PTHREAD COLCON_WASM_PTHREAD_POOL_SIZE)

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

# Emscripten.cmake asks `emcc -v` (twice) and `em-config CACHE` every time it
# is read: at each project() and each try_compile, about 1 s of Python
# start-ups each time. Ask once per build folder, keep the answers in the
# cache, and let Emscripten.cmake find them.
if(COLCON_WASM_EMSCRIPTEN_BIN AND NOT COLCON_WASM_PROBED_CLANG_VERSION)
  execute_process(COMMAND "${COLCON_WASM_EMSCRIPTEN_BIN}/emcc" -v
    RESULT_VARIABLE _colcon_wasm_result ERROR_VARIABLE _colcon_wasm_output OUTPUT_QUIET)
  if(_colcon_wasm_result EQUAL 0 AND _colcon_wasm_output MATCHES "[Ee]mscripten")
    string(REGEX MATCH "clang version ([0-9.]+)" _colcon_wasm_unused "${_colcon_wasm_output}")
    set(_colcon_wasm_clang "${CMAKE_MATCH_1}")
    string(REGEX MATCH "emcc \\(.*\\) ([0-9.]+)" _colcon_wasm_unused "${_colcon_wasm_output}")
    if(_colcon_wasm_clang AND CMAKE_MATCH_1)
      set(COLCON_WASM_PROBED_CLANG_VERSION "${_colcon_wasm_clang}" CACHE INTERNAL
        "colcon-wasm: clang version of emcc")
      set(COLCON_WASM_PROBED_EMSCRIPTEN_VERSION "${CMAKE_MATCH_1}" CACHE INTERNAL
        "colcon-wasm: Emscripten version")
    endif()
  endif()
endif()
if(COLCON_WASM_PROBED_CLANG_VERSION)
  # Emscripten.cmake skips its own `emcc -v` when these are set
  set(CMAKE_C_COMPILER_VERSION "${COLCON_WASM_PROBED_CLANG_VERSION}")
  set(CMAKE_CXX_COMPILER_VERSION "${COLCON_WASM_PROBED_CLANG_VERSION}")
  set(EMSCRIPTEN_VERSION "${COLCON_WASM_PROBED_EMSCRIPTEN_VERSION}")
endif()
set(_colcon_wasm_platform "${COLCON_WASM_EMSCRIPTEN_ROOT}/cmake/Modules/Platform/Emscripten.cmake")
if(COLCON_WASM_EMSCRIPTEN_BIN AND NOT COLCON_WASM_PROBED_CACHE)
  execute_process(COMMAND "${COLCON_WASM_EMSCRIPTEN_BIN}/em-config" CACHE
    RESULT_VARIABLE _colcon_wasm_result OUTPUT_VARIABLE _colcon_wasm_output
    OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(_colcon_wasm_result EQUAL 0 AND IS_DIRECTORY "${_colcon_wasm_output}")
    set(COLCON_WASM_PROBED_CACHE "${_colcon_wasm_output}" CACHE INTERNAL
      "colcon-wasm: Emscripten's cache folder")
  endif()
endif()
if(COLCON_WASM_PROBED_CACHE)
  # a copy of Emscripten.cmake whose `em-config CACHE` is an echo of the
  # answer above; the original is used when that command is not found
  file(READ "${_colcon_wasm_platform}" _colcon_wasm_text)
  string(REGEX REPLACE
    "execute_process\\(COMMAND \"[^\"]*em-config\\\${EMCC_SUFFIX}\" \"CACHE\""
    "execute_process(COMMAND \"\${CMAKE_COMMAND}\" -E echo \"${COLCON_WASM_PROBED_CACHE}\""
    _colcon_wasm_patched "${_colcon_wasm_text}")
  if(NOT _colcon_wasm_patched STREQUAL _colcon_wasm_text)
    set(_colcon_wasm_copy "${CMAKE_BINARY_DIR}/CMakeFiles/colcon_wasm/Emscripten.cmake")
    if(EXISTS "${_colcon_wasm_copy}")
      file(READ "${_colcon_wasm_copy}" _colcon_wasm_text)
    endif()
    if(NOT _colcon_wasm_patched STREQUAL _colcon_wasm_text)
      file(WRITE "${_colcon_wasm_copy}" "${_colcon_wasm_patched}")
    endif()
    set(_colcon_wasm_platform "${_colcon_wasm_copy}")
  endif()
endif()
include("${_colcon_wasm_platform}")

# Packages find each other in the install space: Emscripten.cmake searches
# packages, libraries and headers ONLY under CMAKE_FIND_ROOT_PATH. Prefixes
# that already lie under a root path are not re-rooted, so adding the install
# base makes every package installed there visible, and nothing of the host.
if(COLCON_WASM_INSTALL_BASE)
  list(APPEND CMAKE_FIND_ROOT_PATH "${COLCON_WASM_INSTALL_BASE}")
endif()
# the underlays' install bases too (`--wasm-underlay`, COLCON_WASM_PREFIX_PATH)
foreach(_colcon_wasm_underlay IN LISTS COLCON_WASM_UNDERLAYS)
  list(APPEND CMAKE_FIND_ROOT_PATH "${_colcon_wasm_underlay}")
endforeach()

# flags for every compile and link (this file is read more than once per
# project: append once)
if(NOT _colcon_wasm_flags_appended)
  set(_colcon_wasm_flags_appended TRUE)
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
endif()

# The Release and Debug flags (--wasm-opt-level, --wasm-link-opt-level,
# --wasm-debug) are set in one place: wasm-ros-cache.cmake.

# Compile-only steps run clang directly (colcon_wasm/compile_launcher.py asks
# emcc once per set of flags which clang command it would run). A launcher
# the user sets (e.g. -DCMAKE_CXX_COMPILER_LAUNCHER=ccache) is kept.
if(NOT DEFINED COLCON_WASM_COMPILER_LAUNCHER)
  set(COLCON_WASM_COMPILER_LAUNCHER ON)
endif()
if(COLCON_WASM_COMPILER_LAUNCHER AND COLCON_WASM_PYTHON AND COLCON_WASM_LAUNCHER_SCRIPT)
  set(_colcon_wasm_launcher_cache "${COLCON_WASM_LAUNCHER_CACHE}")
  if(NOT _colcon_wasm_launcher_cache)
    set(_colcon_wasm_launcher_cache "${CMAKE_BINARY_DIR}/CMakeFiles/colcon_wasm/cflags")
  endif()
  foreach(_colcon_wasm_lang C CXX)
    if(NOT DEFINED CMAKE_${_colcon_wasm_lang}_COMPILER_LAUNCHER AND
        NOT DEFINED ENV{CMAKE_${_colcon_wasm_lang}_COMPILER_LAUNCHER})
      set(CMAKE_${_colcon_wasm_lang}_COMPILER_LAUNCHER
        "${COLCON_WASM_PYTHON}" -I -S "${COLCON_WASM_LAUNCHER_SCRIPT}"
        --cache "${_colcon_wasm_launcher_cache}" --root "${COLCON_WASM_EMSCRIPTEN_ROOT}" --)
    endif()
  endforeach()
endif()

# no dlopen: static libraries only
set_property(GLOBAL PROPERTY TARGET_SUPPORTS_SHARED_LIBS FALSE)

# Every executable link goes through the link launcher, which links what a
# ROS system would load at run time: class_loader registrations, the plugins
# pluginlib loads, the components a container hosts (colcon_wasm/link/).
set(_colcon_wasm_link_launcher "")
if(COLCON_WASM_PYTHON AND COLCON_WASM_LINK_LAUNCHER_SCRIPT AND COLCON_WASM_LLVM_NM)
  set(_colcon_wasm_link_cache "${COLCON_WASM_LAUNCHER_CACHE}")
  if(_colcon_wasm_link_cache)
    get_filename_component(_colcon_wasm_link_cache "${_colcon_wasm_link_cache}" DIRECTORY)
    set(_colcon_wasm_link_cache "${_colcon_wasm_link_cache}/link_launcher")
  else()
    set(_colcon_wasm_link_cache "${CMAKE_BINARY_DIR}/CMakeFiles/colcon_wasm/link")
  endif()
  set(_colcon_wasm_link_bases "${COLCON_WASM_INSTALL_BASE}")
  foreach(_colcon_wasm_underlay IN LISTS COLCON_WASM_UNDERLAYS)
    string(APPEND _colcon_wasm_link_bases ":${_colcon_wasm_underlay}")
  endforeach()
  set(_colcon_wasm_link_launcher
    "${COLCON_WASM_PYTHON} -I -S ${COLCON_WASM_LINK_LAUNCHER_SCRIPT} --cache ${_colcon_wasm_link_cache} --nm ${COLCON_WASM_LLVM_NM} --cxxfilt ${COLCON_WASM_LLVM_CXXFILT} --bases ${_colcon_wasm_link_bases}")
  set_property(GLOBAL PROPERTY RULE_LAUNCH_LINK "${_colcon_wasm_link_launcher} --")
endif()
set(_COLCON_WASM_TOOLCHAIN_DIR "${CMAKE_CURRENT_LIST_DIR}")

# colcon_wasm_capture_link_closure(<library>)
#
# Record what linking <library> needs (its link closure), installed as
# share/<pkg>/colcon_wasm/closures/<name>.json: executables that load the
# library at run time (a component container, a pluginlib user) link it
# from there. Called for component and plugin libraries by colcon-wasm's
# extras of rclcpp_components and pluginlib. It links a throw-away executable
# against the library with the link launcher in capture mode.
function(colcon_wasm_capture_link_closure library)
  if(NOT _colcon_wasm_link_launcher OR NOT TARGET ${library})
    return()
  endif()
  get_target_property(_type ${library} TYPE)
  if(NOT _type STREQUAL "STATIC_LIBRARY")
    return()  # an interface or object library: nothing of its own to link
  endif()
  get_target_property(_aliased ${library} ALIASED_TARGET)
  if(_aliased)
    set(library ${_aliased})
  endif()
  set(_probe colcon_wasm_closure__${library})
  if(TARGET ${_probe})
    return()
  endif()
  get_target_property(_name ${library} ARCHIVE_OUTPUT_NAME)
  if(NOT _name)
    get_target_property(_name ${library} OUTPUT_NAME)
  endif()
  if(NOT _name)
    set(_name ${library})
  endif()
  set(_out "${CMAKE_CURRENT_BINARY_DIR}/colcon_wasm_closures/${_name}.json")
  add_executable(${_probe} "${_COLCON_WASM_TOOLCHAIN_DIR}/link/closure_main.cpp")
  target_link_libraries(${_probe} PRIVATE ${library})
  set_target_properties(${_probe} PROPERTIES RULE_LAUNCH_LINK
    "${_colcon_wasm_link_launcher} --capture ${_out} --package ${PROJECT_NAME} --build-dir ${CMAKE_BINARY_DIR} --install-prefix ${CMAKE_INSTALL_PREFIX} --")
  install(FILES "${_out}" DESTINATION share/${PROJECT_NAME}/colcon_wasm/closures)
endfunction()

# tests and fault injection (--wasm-tests, --wasm-fault-injection)
if(COLCON_WASM_TESTS OR COLCON_WASM_FAULT_INJECTION)
  include("${CMAKE_CURRENT_LIST_DIR}/wasm-ros-tests.cmake")
endif()
