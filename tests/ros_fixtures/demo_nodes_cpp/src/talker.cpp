// Copyright 2026 colcon-wasm authors
// Licensed under the Apache License, Version 2.0

// Publishes "Hello World: N" on chatter once a second, as demo_nodes_cpp's talker.

#include <chrono>
#include <memory>
#include <string>

#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/string.hpp"

using namespace std::chrono_literals;

class Talker : public rclcpp::Node
{
public:
  Talker()
  : Node("talker")
  {
    publisher_ = create_publisher<std_msgs::msg::String>("chatter", 10);
    timer_ = create_wall_timer(1s, [this]() {
          std_msgs::msg::String message;
          message.data = "Hello World: " + std::to_string(++count_);
          RCLCPP_INFO(get_logger(), "Publishing: '%s'", message.data.c_str());
          publisher_->publish(message);
        });
  }

private:
  size_t count_ = 0;
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr publisher_;
  rclcpp::TimerBase::SharedPtr timer_;
};

int main(int argc, char * argv[])
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<Talker>());
  rclcpp::shutdown();
  return 0;
}
