# colcon-wasm project include for libyaml_vendor (CMAKE_PROJECT_libyaml_vendor_INCLUDE).
#
# libyaml_vendor 1.2.2 always clones libyaml with ExternalProject_Add. This
# file runs right after its project() call and replaces that one external
# project with the libyaml the workspace's plain `yaml` package installed
# (the recipe makes libyaml_vendor depend on `yaml`). It lays out the same
# files the vendor's own libyaml build would (lib/libyaml.a and
# include/libyaml_vendor/yaml.h under libyaml_install/), which the vendor's
# CMakeLists installs unchanged. No download, no source patch.

include(ExternalProject)  # defines ExternalProject_Add once (include guard)

function(ExternalProject_Add name)
  if(NOT name MATCHES "^libyaml-")
    _ExternalProject_Add(${name} ${ARGN})
    return()
  endif()
  find_package(yaml REQUIRED CONFIG)
  if(NOT TARGET yaml)
    message(FATAL_ERROR "colcon-wasm: the 'yaml' package defines no 'yaml' target; "
      "libyaml_vendor needs the workspace's yaml package (src/yaml/libyaml)")
  endif()
  get_target_property(_location yaml IMPORTED_LOCATION_RELEASE)
  if(NOT _location)
    get_target_property(_location yaml IMPORTED_LOCATION_NOCONFIG)
  endif()
  if(NOT _location)
    get_target_property(_location yaml IMPORTED_LOCATION)
  endif()
  get_target_property(_includes yaml INTERFACE_INCLUDE_DIRECTORIES)
  if(NOT _location OR NOT EXISTS "${_location}")
    message(FATAL_ERROR "colcon-wasm: cannot locate the library of the 'yaml' "
      "package (found '${_location}')")
  endif()
  find_file(_yaml_h yaml.h PATHS ${_includes} NO_DEFAULT_PATH NO_CMAKE_FIND_ROOT_PATH)
  if(NOT _yaml_h)
    message(FATAL_ERROR "colcon-wasm: yaml.h not found in '${_includes}'")
  endif()
  set(_prefix "${CMAKE_CURRENT_BINARY_DIR}/libyaml_install")
  file(MAKE_DIRECTORY "${_prefix}/lib" "${_prefix}/include/libyaml_vendor")
  configure_file("${_location}" "${_prefix}/lib/libyaml.a" COPYONLY)
  configure_file("${_yaml_h}" "${_prefix}/include/libyaml_vendor/yaml.h" COPYONLY)
  add_custom_target(${name})
  message(STATUS "colcon-wasm: libyaml_vendor uses '${_location}' instead of cloning libyaml")
endfunction()
