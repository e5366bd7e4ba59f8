# Project include of zenoh_pico (recipes/humble.yaml): the Zenoh gateway of
# colcon-wasm is built and tested with zenoh-pico 1.9.x only (its Emscripten
# port, patched by patches/zenoh_pico/, and its WebSocket link).
if(NOT PROJECT_VERSION VERSION_GREATER_EQUAL "1.9.0" OR NOT PROJECT_VERSION VERSION_LESS "1.10.0")
  message(FATAL_ERROR "colcon-wasm: zenoh-pico ${PROJECT_VERSION} in '${CMAKE_CURRENT_SOURCE_DIR}' "
    "is not the version the Zenoh gateway supports (1.9.x): check out the tag 1.9.0 "
    "(git -C <zenoh-pico> checkout 1.9.0), or skip it with --packages-skip zenoh_pico")
endif()
