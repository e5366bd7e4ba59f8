# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Link WebAssembly executables the way a ROS 2 system loads libraries.

Natively, ROS 2 loads code at run time: a component container `dlopen`s the
library the ament index names, pluginlib `dlopen`s the library of a plugin's
XML description, and every static registration object of a shared library
runs when the library is loaded. A WebAssembly executable is one static
link: nothing is loaded later, and the linker drops every archive member no
symbol refers to, which is exactly what a registration object is.

CMake runs the link launcher (:mod:`colcon_wasm.link.launcher`) around every
executable link of a `--wasm` build (`RULE_LAUNCH_LINK`, see
toolchains/wasm-ros.cmake). It

* keeps every class_loader registration (`CLASS_LOADER_REGISTER_CLASS`,
  `PLUGINLIB_EXPORT_CLASS`, `RCLCPP_COMPONENTS_REGISTER_NODE`) of every
  archive on the link line, as loading a shared library would;
* links the plugin libraries of every base class the executable loads with
  `pluginlib::ClassLoader<Base>`, from the ament index of the install space
  and its underlays (the library's *link closure*, recorded when its package
  was built, brings what the plugin needs);
* links every registered component into an executable that hosts a
  `rclcpp_components::ComponentManager` (a component container);
* writes the table of linked libraries that rcutils'
  `rcutils_load_shared_library()` consults instead of `dlopen`
  (patches/rcutils/0003), so `class_loader::ClassLoader(path)` succeeds for a
  linked library and fails with a clear message for another.

This package must stay importable with Python's site packages off and
without colcon: CMake runs it once per link.
"""
