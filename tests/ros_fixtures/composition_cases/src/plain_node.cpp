// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// A plain node with its own main(), compiled into the component library too
// (natively harmless; a whole-archive link would see two main()s).

#include <memory>

#include "rclcpp/rclcpp.hpp"

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  auto node = std::make_shared<rclcpp::Node>("plain_node");
  RCLCPP_INFO(node->get_logger(), "plain node up");
  rclcpp::spin(node);
  rclcpp::shutdown();
  return 0;
}
