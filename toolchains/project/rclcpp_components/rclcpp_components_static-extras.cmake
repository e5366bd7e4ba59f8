# colcon-wasm: composition without dlopen for rclcpp_components.
#
# Installed by colcon-wasm's project include for rclcpp_components and
# included at the end of rclcpp_componentsConfig.cmake, after
# rclcpp_components' own extras (docs/composition.md). What upstream does at
# run time with dlopen is done at link time by colcon-wasm's link launcher
# (colcon_wasm/link/): it keeps every component registration of the archives
# an executable links, and links every registered component into an
# executable that hosts a ComponentManager. So this file only:
#
# * lets rclcpp_components_register_nodes() accept the static library that
#   add_library(<target> SHARED ...) becomes on this platform (upstream
#   refuses anything but a shared library), and records the library's link
#   closure so that containers can link it;
# * makes rclcpp_components_register_node() link the component library into
#   the executable it generates (upstream's executable loads it by name at
#   run time); the executable's source is upstream's node_main.cpp.in;
# * adds rclcpp_components_static_container(), a container that hosts only
#   the components of the targets it is given.
#
# The ament resource index entries are written as before (class;lib/<archive>).

# Remember the component classes of a target (for static containers), write
# the ament resource index entries as upstream does, and record the link
# closure of the library.
macro(_rclcpp_components_record_classes target resource_index)
  _rclcpp_components_register_package_hook()
  foreach(_class ${ARGN})
    set_property(TARGET ${target} APPEND PROPERTY COLCON_WASM_COMPONENT_CLASSES "${_class}")
    set(_RCLCPP_COMPONENTS_${resource_index}__NODES
      "${_RCLCPP_COMPONENTS_${resource_index}__NODES}${_class};lib/$<TARGET_FILE_NAME:${target}>\n")
    list(APPEND _RCLCPP_COMPONENTS_PACKAGE_RESOURCE_INDICES ${resource_index})
  endforeach()
  if(COMMAND colcon_wasm_capture_link_closure)
    colcon_wasm_capture_link_closure(${target})
  endif()
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
  get_target_property(_colcon_wasm_type ${target} TYPE)
  if(NOT _colcon_wasm_type STREQUAL "STATIC_LIBRARY")
    message(FATAL_ERROR "rclcpp_components_register_nodes() first argument "
      "'${target}' is a ${_colcon_wasm_type}; a component library must be a library "
      "(add_library(${target} SHARED ...), which is static in WebAssembly builds)")
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

# Upstream's macro (which generates the executable from node_main.cpp.in),
# then the link of the component library: the generated main() creates a
# class_loader::ClassLoader for the library, which is linked (rcutils,
# patched by colcon-wasm, "loads" the linked libraries).
macro(rclcpp_components_register_node target)
  cmake_parse_arguments(_colcon_wasm_ARGS "" "PLUGIN;EXECUTABLE;EXECUTOR;RESOURCE_INDEX" ""
    ${ARGN})
  _rclcpp_components_register_node(${target} ${ARGN})
  target_link_libraries(${_colcon_wasm_ARGS_EXECUTABLE} ${target})
  if(COMMAND colcon_wasm_capture_link_closure)
    colcon_wasm_capture_link_closure(${target})
  endif()
  get_property(_colcon_wasm_classes TARGET ${target} PROPERTY COLCON_WASM_COMPONENT_CLASSES)
  if(NOT "${_colcon_wasm_ARGS_PLUGIN}" IN_LIST _colcon_wasm_classes)
    set_property(TARGET ${target} APPEND PROPERTY COLCON_WASM_COMPONENT_CLASSES
      "${_colcon_wasm_ARGS_PLUGIN}")
  endif()
endmacro()

set(rclcpp_components_CONTAINER_TEMPLATE
  "${rclcpp_components_SHARE_DIR}/component_container_static.cpp.in")

# rclcpp_components_static_container(<exe> COMPONENTS <target>... [EXECUTOR <executor>])
#
# A component container that hosts the components of the given targets only
# (colcon-wasm extra: the stock component_container hosts every component of
# the install space). It answers the usual ~/_container/load_node,
# unload_node and list_nodes services. Guard it with
# if(COMMAND rclcpp_components_static_container) in a package that also
# builds natively.
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
  target_link_libraries(${container} ${ARGS_COMPONENTS})
  ament_target_dependencies(${container} "rclcpp" "class_loader" "rclcpp_components")
  install(TARGETS ${container} DESTINATION lib/${PROJECT_NAME})
endfunction()
