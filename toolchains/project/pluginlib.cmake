# colcon-wasm project include for pluginlib (CMAKE_PROJECT_pluginlib_INCLUDE).
#
# pluginlib without dlopen: this file runs right after pluginlib's project()
# call and makes its installed CMake config end with
# pluginlib/pluginlib_static-extras.cmake (ament's <pkg>_CONFIG_EXTRAS_POST,
# included after pluginlib's own extras). That file makes
# pluginlib_export_plugin_description_file() also record the link closure of
# each library the plugin description names, so that colcon-wasm's link
# launcher can link the plugins into every executable that loads their base
# class (colcon_wasm/link/). No source file of pluginlib is changed;
# docs/composition.md explains the whole mechanism.

list(APPEND pluginlib_CONFIG_EXTRAS_POST
  "${CMAKE_CURRENT_LIST_DIR}/pluginlib/pluginlib_static-extras.cmake")
