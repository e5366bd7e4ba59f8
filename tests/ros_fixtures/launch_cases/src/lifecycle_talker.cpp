// Copyright 2026 colcon-wasm authors
// Licensed under the Apache License, Version 2.0

// A managed node, as the lifecycle demo's talker: it publishes
// "Lifecycle HelloWorld #N" on lifecycle_chatter only while active, and logs
// each transition callback.

#include <chrono>
#include <memory>
#include <string>

#include "lifecycle_msgs/msg/transition.hpp"
#include "rclcpp/rclcpp.hpp"
#include "rclcpp_lifecycle/lifecycle_node.hpp"
#include "rclcpp_lifecycle/lifecycle_publisher.hpp"
#include "std_msgs/msg/string.hpp"

using namespace std::chrono_literals;
using CallbackReturn = rclcpp_lifecycle::node_interfaces::LifecycleNodeInterface::CallbackReturn;

class LifecycleTalker : public rclcpp_lifecycle::LifecycleNode
{
public:
  LifecycleTalker()
  : rclcpp_lifecycle::LifecycleNode("lc_talker") {}

  CallbackReturn on_configure(const rclcpp_lifecycle::State &) override
  {
    publisher_ = create_publisher<std_msgs::msg::String>("lifecycle_chatter", 10);
    timer_ = create_wall_timer(200ms, [this]() {
          if (!publisher_->is_activated()) {
            return;
          }
          std_msgs::msg::String message;
          message.data = "Lifecycle HelloWorld #" + std::to_string(++count_);
          RCLCPP_INFO(get_logger(), "Lifecycle publisher is active. Publishing: [%s]",
          message.data.c_str());
          publisher_->publish(message);
        });
    RCLCPP_INFO(get_logger(), "on_configure() is called.");
    return CallbackReturn::SUCCESS;
  }

  CallbackReturn on_activate(const rclcpp_lifecycle::State & state) override
  {
    LifecycleNode::on_activate(state);
    RCLCPP_INFO(get_logger(), "on_activate() is called.");
    return CallbackReturn::SUCCESS;
  }

  CallbackReturn on_deactivate(const rclcpp_lifecycle::State & state) override
  {
    LifecycleNode::on_deactivate(state);
    RCLCPP_INFO(get_logger(), "on_deactivate() is called.");
    return CallbackReturn::SUCCESS;
  }

private:
  size_t count_ = 0;
  rclcpp_lifecycle::LifecyclePublisher<std_msgs::msg::String>::SharedPtr publisher_;
  rclcpp::TimerBase::SharedPtr timer_;
};

int main(int argc, char * argv[])
{
  rclcpp::init(argc, argv);
  auto node = std::make_shared<LifecycleTalker>();
  rclcpp::spin(node->get_node_base_interface());
  rclcpp::shutdown();
  return 0;
}
