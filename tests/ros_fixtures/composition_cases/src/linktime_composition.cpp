// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Link-time composition as ros2/demos' composition/src/linktime_composition.cpp
// does it: the component libraries are linked, and every class registered
// under the library path "" is instantiated.

#include <memory>
#include <string>
#include <vector>

#include "class_loader/class_loader.hpp"
#include "rclcpp/rclcpp.hpp"
#include "rclcpp_components/node_factory.hpp"

int main(int argc, char * argv[])
{
  rclcpp::init(argc, argv);
  rclcpp::Logger logger = rclcpp::get_logger("linktime_composition");
  rclcpp::executors::SingleThreadedExecutor exec;
  rclcpp::NodeOptions options;
  std::vector<std::unique_ptr<class_loader::ClassLoader>> loaders;
  std::vector<rclcpp_components::NodeInstanceWrapper> node_wrappers;

  // all classes from libraries linked by the linker (rather than dlopen)
  // are registered under the library_path ""
  loaders.push_back(std::make_unique<class_loader::ClassLoader>(""));
  auto classes = loaders.back()->getAvailableClasses<rclcpp_components::NodeFactory>();
  for (const auto & clazz : classes) {
    RCLCPP_INFO(logger, "Instantiate class %s", clazz.c_str());
    auto node_factory = loaders.back()->createInstance<rclcpp_components::NodeFactory>(clazz);
    auto wrapper = node_factory->create_node_instance(options);
    node_wrappers.push_back(wrapper);
    exec.add_node(wrapper.get_node_base_interface());
  }
  if (classes.empty()) {
    RCLCPP_ERROR(logger, "no component is linked");
    return 1;
  }
  exec.spin();
  rclcpp::shutdown();
  return 0;
}
