// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// greet list                     the declared Greeter classes
// greet LOOKUP_NAME NAME         greet NAME with a plugin
// greet --uncaught LOOKUP_NAME   create a plugin without catching errors
// greet --library PATH           load a library with class_loader

#include <cstdio>
#include <memory>
#include <string>

#include "class_loader/class_loader.hpp"
#include "pluginlib/class_loader.hpp"
#include "pluginlib_base/greeter.hpp"

int main(int argc, char ** argv)
{
  const std::string mode = argc > 1 ? argv[1] : "list";
  if (mode == "--library" && argc > 2) {
    try {
      class_loader::ClassLoader loader(argv[2]);
      std::printf("LOADED %s\n", argv[2]);
    } catch (const std::exception & e) {
      std::printf("LOAD FAILED %s\n", e.what());
    }
    return 0;
  }
  pluginlib::ClassLoader<pluginlib_base::Greeter> loader("pluginlib_base", "pluginlib_base::Greeter");
  if (mode == "list") {
    for (const auto & name : loader.getDeclaredClasses()) {
      std::printf("DECLARED %s (%s) in %s\n", name.c_str(), loader.getClassType(name).c_str(),
        loader.getClassPackage(name).c_str());
    }
    return 0;
  }
  if (mode == "--uncaught" && argc > 2) {
    auto greeter = loader.createSharedInstance(argv[2]);
    std::printf("%s\n", greeter->greet("nobody").c_str());
    return 0;
  }
  try {
    auto greeter = loader.createSharedInstance(mode);
    std::printf("GREETING %s\n", greeter->greet(argc > 2 ? argv[2] : "world").c_str());
  } catch (const pluginlib::PluginlibException & e) {
    std::printf("PLUGIN FAILED %s\n", e.what());
    return 1;
  }
  return 0;
}
