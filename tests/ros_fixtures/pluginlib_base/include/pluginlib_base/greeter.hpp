// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

#ifndef PLUGINLIB_BASE__GREETER_HPP_
#define PLUGINLIB_BASE__GREETER_HPP_

#include <string>

namespace pluginlib_base
{

/// The base class of the greeter plugins.
class Greeter
{
public:
  virtual ~Greeter() = default;
  /// Greet someone.
  virtual std::string greet(const std::string & name) const = 0;
};

}  // namespace pluginlib_base

#endif  // PLUGINLIB_BASE__GREETER_HPP_
