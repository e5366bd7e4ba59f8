# colcon-wasm: pluginlib without dlopen.
#
# Included at the end of pluginlibConfig.cmake, after pluginlib's own extras
# (see colcon-wasm's project include toolchains/project/pluginlib.cmake).
# pluginlib_export_plugin_description_file() keeps upstream's behaviour
# (install the XML, register it in the ament index) and also records the
# link closure of every library the description names
# (colcon_wasm_capture_link_closure(), toolchains/wasm-ros.cmake). colcon-wasm's
# link launcher reads the ament index when it links an executable that uses
# pluginlib::ClassLoader<Base>, and links the plugins of Base from their
# closures.

# The library names of a plugin description: <library path="...">.
function(_colcon_wasm_plugin_libraries xml_file out_var)
  file(READ "${xml_file}" _text)
  string(REGEX MATCHALL "<library[^>]*[ \t\r\n]path[ \t\r\n]*=[ \t\r\n]*\"[^\"]+\"" _elements
    "${_text}")
  set(_names "")
  foreach(_element IN LISTS _elements)
    string(REGEX REPLACE ".*path[ \t\r\n]*=[ \t\r\n]*\"([^\"]+)\".*" "\\1" _path "${_element}")
    get_filename_component(_name "${_path}" NAME_WE)
    list(APPEND _names "${_name}")
  endforeach()
  set(${out_var} "${_names}" PARENT_SCOPE)
endfunction()

# The targets of this project (all directories), for names given as OUTPUT_NAME.
function(_colcon_wasm_project_targets directory out_var)
  get_property(_targets DIRECTORY "${directory}" PROPERTY BUILDSYSTEM_TARGETS)
  get_property(_subdirectories DIRECTORY "${directory}" PROPERTY SUBDIRECTORIES)
  foreach(_subdirectory IN LISTS _subdirectories)
    _colcon_wasm_project_targets("${_subdirectory}" _more)
    list(APPEND _targets ${_more})
  endforeach()
  set(${out_var} "${_targets}" PARENT_SCOPE)
endfunction()

# Record the closures of the libraries a description names (at the end of
# the project's configure, when every target is defined).
function(_colcon_wasm_capture_plugin_closures xml_file)
  _colcon_wasm_plugin_libraries("${xml_file}" _names)
  _colcon_wasm_project_targets("${CMAKE_SOURCE_DIR}" _targets)
  foreach(_name IN LISTS _names)
    string(REGEX REPLACE "^lib" "" _bare "${_name}")
    set(_found "")
    foreach(_target IN LISTS _targets)
      get_target_property(_output ${_target} OUTPUT_NAME)
      if(_target STREQUAL _name OR _target STREQUAL _bare OR
          (_output AND (_output STREQUAL _name OR _output STREQUAL _bare)))
        set(_found ${_target})
        break()
      endif()
    endforeach()
    if(_found)
      colcon_wasm_capture_link_closure(${_found})
    else()
      message(WARNING "colcon-wasm: the plugin description '${xml_file}' names the "
        "library '${_name}', which is no target of ${PROJECT_NAME}: its plugins cannot "
        "be linked into the executables that load them")
    endif()
  endforeach()
endfunction()

macro(pluginlib_export_plugin_description_file plugin_category relative_filename)
  _pluginlib_export_plugin_description_file(${plugin_category} ${relative_filename})
  if(COMMAND colcon_wasm_capture_link_closure)
    if(CMAKE_VERSION VERSION_LESS 3.19)
      _colcon_wasm_capture_plugin_closures("${CMAKE_CURRENT_SOURCE_DIR}/${relative_filename}")
    else()
      cmake_language(EVAL CODE "cmake_language(DEFER DIRECTORY [[${CMAKE_SOURCE_DIR}]] CALL _colcon_wasm_capture_plugin_closures [[${CMAKE_CURRENT_SOURCE_DIR}/${relative_filename}]])")
    endif()
  endif()
endmacro()
