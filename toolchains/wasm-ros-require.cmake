# colcon_wasm_require(<variable>...): stop when one is not set.
#
# colcon build --wasm passes every --wasm build setting as a cache variable
# (colcon_wasm/options.py: the one table of the options, their defaults and
# the variables they set). The toolchain files default none of them: an unset
# one means the file is used without colcon-wasm.
function(colcon_wasm_require)
  foreach(_colcon_wasm_variable IN LISTS ARGN)
    if(NOT DEFINED ${_colcon_wasm_variable} OR "${${_colcon_wasm_variable}}" STREQUAL "")
      message(FATAL_ERROR "colcon-wasm: ${_colcon_wasm_variable} is not set; colcon-wasm "
        "sets it (its default is in colcon_wasm/options.py): build with "
        "`colcon build --wasm`, which passes it, or pass -D${_colcon_wasm_variable}=<value>")
    endif()
  endforeach()
endfunction()
