// Copyright 2026 colcon-wasm authors
// Licensed under the Apache License, Version 2.0

// Publishes "tick N" on `ticks` every `period_ms`, and after `count` ticks
// exits with the status `code` (parameters): a node that ends by itself,
// for OnProcessExit, respawn and Shutdown in launch files.

#include <chrono>
#include <memory>
#include <string>

#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/string.hpp"

int main(int argc, char * argv[])
{
  rclcpp::init(argc, argv);
  auto node = std::make_shared<rclcpp::Node>("exit_after");
  const int64_t count = node->declare_parameter<int64_t>("count", 3);
  const int64_t code = node->declare_parameter<int64_t>("code", 0);
  const int64_t period_ms = node->declare_parameter<int64_t>("period_ms", 200);
  const std::string word = node->declare_parameter<std::string>("word", "tick");
  auto publisher = node->create_publisher<std_msgs::msg::String>("ticks", 10);
  int64_t ticks = 0;
  auto timer = node->create_wall_timer(
    std::chrono::milliseconds(period_ms), [&]() {
      std_msgs::msg::String message;
      message.data = word + " " + std::to_string(++ticks);
      RCLCPP_INFO(node->get_logger(), "%s", message.data.c_str());
      publisher->publish(message);
      if (ticks >= count) {
        RCLCPP_INFO(node->get_logger(), "exiting with code %ld", static_cast<long>(code));
        rclcpp::shutdown();
      }
    });
  rclcpp::spin(node);
  return static_cast<int>(code);
}
