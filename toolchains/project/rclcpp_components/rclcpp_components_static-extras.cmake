# colcon-wasm: static composition for rclcpp_components (WebAssembly has no dlopen).
#
# Installed by colcon-wasm's project include for rclcpp_components and
# included at the end of rclcpp_componentsConfig.cmake, after
# rclcpp_components' own extras, so the definitions below replace theirs:
#
# * rclcpp_components_register_nodes(<target> [RESOURCE_INDEX <index>] <class>...)
#   accepts the static library that add_library(<target> SHARED ...) becomes
#   on this platform, and records the classes on the target.
# * rclcpp_components_register_node(<target> PLUGIN <class> EXECUTABLE <exe>
#   [EXECUTOR <executor>] [RESOURCE_INDEX <index>]) builds <exe> from
#   node_main_static.cpp.in, with <target> linked in full (whole archive):
#   the component's RCLCPP_COMPONENTS_REGISTER_NODE registers its factory in
#   class_loader's registry before main(), and main() instantiates it from there.
# * rclcpp_components_static_container(<exe> COMPONENTS <target>...
#   [EXECUTOR <executor>]) (new) builds a component container that hosts the
#   components of the given targets (chosen at build time): it answers the
#   usual ~/_container/load_node, unload_node and list_nodes services.
#
# The ament resource index entries are written as before (class;lib/<archive>),
# so tools that list components still see them.

set(rclcpp_components_NODE_TEMPLATE "${rclcpp_components_SHARE_DIR}/node_main_static.cpp.in")
set(rclcpp_components_CONTAINER_TEMPLATE
  "${rclcpp_components_SHARE_DIR}/component_container_static.cpp.in")

# Link a static component library into an executable in full: nothing in the
# executable references the component's registration object, so a normal
# static link would drop it.
function(_rclcpp_components_link_whole_archive executable library)
  get_target_property(_type ${library} TYPE)
  if(NOT _type STREQUAL "STATIC_LIBRARY")
    message(FATAL_ERROR "colcon-wasm: component library '${library}' of '${executable}' "
      "is a ${_type}; WebAssembly builds need a static (or SHARED, which becomes static) "
      "library")
  endif()
  target_link_libraries(${executable}
    "-Wl,--whole-archive $<TARGET_FILE:${library}> -Wl,--no-whole-archive"
    ${library})
endfunction()

# Remember the component classes of a target (for containers) and in the
# ament resource index (as upstream does).
macro(_rclcpp_components_record_classes target resource_index)
  _rclcpp_components_register_package_hook()
  foreach(_class ${ARGN})
    set_property(TARGET ${target} APPEND PROPERTY COLCON_WASM_COMPONENT_CLASSES "${_class}")
    set(_RCLCPP_COMPONENTS_${resource_index}__NODES
      "${_RCLCPP_COMPONENTS_${resource_index}__NODES}${_class};lib/$<TARGET_FILE_NAME:${target}>\n")
    list(APPEND _RCLCPP_COMPONENTS_PACKAGE_RESOURCE_INDICES ${resource_index})
  endforeach()
endmacro()

macro(rclcpp_components_register_nodes target)
  if(NOT TARGET ${target})
    message(FATAL_ERROR
      "rclcpp_components_register_nodes() first argument '${target}' is not a target")
  endif()
  cmake_parse_arguments(_ARGS "" "RESOURCE_INDEX" "" ${ARGN})
  set(_resource_index "rclcpp_components")
  if(NOT "${_ARGS_RESOURCE_INDEX}" STREQUAL "")
    set(_resource_index ${_ARGS_RESOURCE_INDEX})
  endif()
  set(_unique_names)
  foreach(_arg ${_ARGS_UNPARSED_ARGUMENTS})
    if(_arg IN_LIST _unique_names)
      message(FATAL_ERROR "rclcpp_components_register_nodes() the plugin names "
        "must be unique (multiple '${_arg}')")
    endif()
    list(APPEND _unique_names "${_arg}")
  endforeach()
  _rclcpp_components_record_classes(${target} ${_resource_index} ${_unique_names})
endmacro()

macro(rclcpp_components_register_node target)
  cmake_parse_arguments(ARGS "" "PLUGIN;EXECUTABLE;EXECUTOR;RESOURCE_INDEX" "" ${ARGN})
  if(ARGS_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "rclcpp_components_register_node() called with unused "
      "arguments: ${ARGS_UNPARSED_ARGUMENTS}")
  endif()
  if("${ARGS_PLUGIN}" STREQUAL "")
    message(FATAL_ERROR "rclcpp_components_register_node macro requires a PLUGIN "
      "argument for target ${target}")
  endif()
  if("${ARGS_EXECUTABLE}" STREQUAL "")
    message(FATAL_ERROR "rclcpp_components_register_node macro requires a EXECUTABLE "
      "argument for target ${target}")
  endif()
  set(resource_index "rclcpp_components")
  if(NOT "${ARGS_RESOURCE_INDEX}" STREQUAL "")
    set(resource_index ${ARGS_RESOURCE_INDEX})
  endif()
  set(executor "SingleThreadedExecutor")
  if(NOT "${ARGS_EXECUTOR}" STREQUAL "")
    set(executor ${ARGS_EXECUTOR})
  endif()
  set(component ${ARGS_PLUGIN})
  set(node ${ARGS_EXECUTABLE})
  set(library_name "$<TARGET_FILE_NAME:${target}>")
  _rclcpp_components_record_classes(${target} ${resource_index} ${component})

  configure_file(${rclcpp_components_NODE_TEMPLATE}
    ${PROJECT_BINARY_DIR}/rclcpp_components/node_main_configured_${node}.cpp.in)
  file(GENERATE OUTPUT ${PROJECT_BINARY_DIR}/rclcpp_components/node_main_${node}.cpp
    INPUT ${PROJECT_BINARY_DIR}/rclcpp_components/node_main_configured_${node}.cpp.in)
  add_executable(${node} ${PROJECT_BINARY_DIR}/rclcpp_components/node_main_${node}.cpp)
  _rclcpp_components_link_whole_archive(${node} ${target})
  ament_target_dependencies(${node} "rclcpp" "class_loader" "rclcpp_components")
  install(TARGETS ${node} DESTINATION lib/${PROJECT_NAME})
endmacro()

function(rclcpp_components_static_container container)
  cmake_parse_arguments(ARGS "" "EXECUTOR" "COMPONENTS" ${ARGN})
  if(ARGS_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "rclcpp_components_static_container() called with unused "
      "arguments: ${ARGS_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT ARGS_COMPONENTS)
    message(FATAL_ERROR "rclcpp_components_static_container(${container}) needs "
      "COMPONENTS <target>...: the component libraries to host")
  endif()
  set(executor "SingleThreadedExecutor")
  if(NOT "${ARGS_EXECUTOR}" STREQUAL "")
    set(executor ${ARGS_EXECUTOR})
  endif()
  set(components "")
  foreach(_target ${ARGS_COMPONENTS})
    if(NOT TARGET ${_target})
      message(FATAL_ERROR "rclcpp_components_static_container(${container}): "
        "'${_target}' is not a target")
    endif()
    get_property(_classes TARGET ${_target} PROPERTY COLCON_WASM_COMPONENT_CLASSES)
    if(NOT _classes)
      message(FATAL_ERROR "rclcpp_components_static_container(${container}): "
        "'${_target}' has no registered components; call "
        "rclcpp_components_register_nodes(${_target} <class>...) before")
    endif()
    foreach(_class ${_classes})
      string(APPEND components "  {\"${PROJECT_NAME}\", \"${_class}\"},\n")
    endforeach()
  endforeach()
  configure_file(${rclcpp_components_CONTAINER_TEMPLATE}
    ${PROJECT_BINARY_DIR}/rclcpp_components/container_main_${container}.cpp @ONLY)
  add_executable(${container} ${PROJECT_BINARY_DIR}/rclcpp_components/container_main_${container}.cpp)
  foreach(_target ${ARGS_COMPONENTS})
    _rclcpp_components_link_whole_archive(${container} ${_target})
  endforeach()
  ament_target_dependencies(${container} "rclcpp" "class_loader" "rclcpp_components")
  install(TARGETS ${container} DESTINATION lib/${PROJECT_NAME})
endfunction()
