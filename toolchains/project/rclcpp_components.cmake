# colcon-wasm project include for rclcpp_components (CMAKE_PROJECT_rclcpp_components_INCLUDE).
#
# Static composition: WebAssembly has no dlopen, so a component library cannot
# be loaded at run time. This file runs right after rclcpp_components'
# project() call and makes its installed CMake config end with
# rclcpp_components/rclcpp_components_static-extras.cmake (ament's
# <pkg>_CONFIG_EXTRAS_POST, included after rclcpp_components' own extras).
# That file replaces the node template and the registration macros, so that
# every package that calls rclcpp_components_register_node(s) links its
# components statically. No source file of rclcpp_components is changed.
# docs/composition.md explains the whole mechanism.

set(_colcon_wasm_components_dir "${CMAKE_CURRENT_LIST_DIR}/rclcpp_components")
list(APPEND rclcpp_components_CONFIG_EXTRAS_POST
  "${_colcon_wasm_components_dir}/rclcpp_components_static-extras.cmake")
install(
  FILES
    "${_colcon_wasm_components_dir}/node_main_static.cpp.in"
    "${_colcon_wasm_components_dir}/component_container_static.cpp.in"
  DESTINATION share/${PROJECT_NAME})
