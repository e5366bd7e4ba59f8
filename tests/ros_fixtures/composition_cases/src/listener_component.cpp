// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "rclcpp_components/register_node_macro.hpp"
#include "std_msgs/msg/string.hpp"

namespace composition_cases
{

/// Logs what it hears on chatter.
class Listener : public rclcpp::Node
{
public:
  explicit Listener(const rclcpp::NodeOptions & options)
  : Node("case_listener", options)
  {
    subscription_ = create_subscription<std_msgs::msg::String>(
      "chatter", 10, [this](std_msgs::msg::String::ConstSharedPtr message) {
        RCLCPP_INFO(get_logger(), "case listener heard: '%s'", message->data.c_str());
      });
  }

private:
  rclcpp::Subscription<std_msgs::msg::String>::SharedPtr subscription_;
};

}  // namespace composition_cases

RCLCPP_COMPONENTS_REGISTER_NODE(composition_cases::Listener)
