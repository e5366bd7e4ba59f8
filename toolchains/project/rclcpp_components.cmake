# colcon-wasm project include for rclcpp_components (CMAKE_PROJECT_rclcpp_components_INCLUDE).
#
# Static composition: WebAssembly has no dlopen, so a component library cannot
# be loaded at run time. This file runs right after rclcpp_components'
# project() call and
# * makes its installed CMake config end with
#   rclcpp_components/rclcpp_components_static-extras.cmake (ament's
#   <pkg>_CONFIG_EXTRAS_POST, included after rclcpp_components' own extras),
#   which lets the registration macros take static libraries and link them;
# * installs the template of rclcpp_components_static_container() and
#   upstream's own container sources (share/rclcpp_components/colcon_wasm/),
#   from which colcon-wasm builds the stock containers again once the
#   components of the workspace are built (they host every component).
# No source file of rclcpp_components is changed. docs/composition.md
# explains the whole mechanism.

set(_colcon_wasm_components_dir "${CMAKE_CURRENT_LIST_DIR}/rclcpp_components")
list(APPEND rclcpp_components_CONFIG_EXTRAS_POST
  "${_colcon_wasm_components_dir}/rclcpp_components_static-extras.cmake")
install(
  FILES "${_colcon_wasm_components_dir}/component_container_static.cpp.in"
  DESTINATION share/${PROJECT_NAME})
install(
  FILES
    "${PROJECT_SOURCE_DIR}/src/component_container.cpp"
    "${PROJECT_SOURCE_DIR}/src/component_container_mt.cpp"
    "${PROJECT_SOURCE_DIR}/src/component_container_isolated.cpp"
  DESTINATION share/${PROJECT_NAME}/colcon_wasm/containers)
