// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Loads a plugin of its own package, as diagnostic_aggregator's
// aggregator_node does: the plugin description reaches the ament index only
// when the package is installed, after this executable was first linked.

#include <iostream>
#include <memory>
#include <string>

#include "pluginlib/class_loader.hpp"
#include "pluginlib_base/greeter.hpp"

int main(int argc, char ** argv)
{
  const std::string type = argc > 1 ? argv[1] : "pluginlib_greeters/Hello";
  const std::string name = argc > 2 ? argv[2] : "own package";
  pluginlib::ClassLoader<pluginlib_base::Greeter> loader(
    "pluginlib_base", "pluginlib_base::Greeter");
  try {
    std::shared_ptr<pluginlib_base::Greeter> greeter = loader.createSharedInstance(type);
    std::cout << "OWN GREETING " << greeter->greet(name) << std::endl;
  } catch (const pluginlib::PluginlibException & e) {
    std::cout << "OWN PLUGIN FAILED " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
