// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

#include <chrono>
#include <memory>
#include <string>

#include "rclcpp/rclcpp.hpp"
#include "rclcpp_components/register_node_macro.hpp"
#include "std_msgs/msg/string.hpp"

namespace composition_cases
{

/// Publishes "case talker says N" on chatter, 5 times a second.
class Talker : public rclcpp::Node
{
public:
  explicit Talker(const rclcpp::NodeOptions & options)
  : Node("case_talker", options)
  {
    publisher_ = create_publisher<std_msgs::msg::String>("chatter", 10);
    timer_ = create_wall_timer(
      std::chrono::milliseconds(200), [this]() {
        std_msgs::msg::String message;
        message.data = "case talker says " + std::to_string(++count_);
        RCLCPP_INFO(get_logger(), "Publishing: '%s'", message.data.c_str());
        publisher_->publish(message);
      });
  }

private:
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr publisher_;
  rclcpp::TimerBase::SharedPtr timer_;
  int count_ = 0;
};

}  // namespace composition_cases

RCLCPP_COMPONENTS_REGISTER_NODE(composition_cases::Talker)
