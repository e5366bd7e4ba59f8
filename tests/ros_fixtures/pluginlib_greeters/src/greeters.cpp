// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

#include <cctype>
#include <string>

#include "pluginlib/class_list_macros.hpp"
#include "pluginlib_base/greeter.hpp"

namespace pluginlib_greeters
{

/// "Hello, <name>".
class Hello : public pluginlib_base::Greeter
{
public:
  std::string greet(const std::string & name) const override {return "Hello, " + name;}
};

/// "HELLO, <NAME>!".
class Shout : public pluginlib_base::Greeter
{
public:
  std::string greet(const std::string & name) const override
  {
    std::string text = "HELLO, " + name + "!";
    for (auto & c : text) {c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));}
    return text;
  }
};

}  // namespace pluginlib_greeters

PLUGINLIB_EXPORT_CLASS(pluginlib_greeters::Hello, pluginlib_base::Greeter)
PLUGINLIB_EXPORT_CLASS(pluginlib_greeters::Shout, pluginlib_base::Greeter)
