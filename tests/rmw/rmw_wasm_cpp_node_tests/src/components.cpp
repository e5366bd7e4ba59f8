// Copyright 2026 The colcon-wasm authors
//
// Licensed under the Apache License, Version 2.0 (the "License");
// you may not use this file except in compliance with the License.
// You may obtain a copy of the License at
//
//     http://www.apache.org/licenses/LICENSE-2.0
//
// Unless required by applicable law or agreed to in writing, software
// distributed under the License is distributed on an "AS IS" BASIS,
// WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
// See the License for the specific language governing permissions and
// limitations under the License.

/// \file
/// Two components for the static composition tests: Talker publishes on
/// "chatter", Listener logs what it hears there.

#include <chrono>
#include <memory>
#include <string>

#include "rclcpp/rclcpp.hpp"
#include "rclcpp_components/register_node_macro.hpp"
#include "std_msgs/msg/string.hpp"

using namespace std::chrono_literals;

namespace rmw_wasm_cpp_node_tests
{

/// Publishes "component says <n>" on "chatter" every 100 ms.
class Talker : public rclcpp::Node
{
public:
  /// Create the component.
  explicit Talker(const rclcpp::NodeOptions & options)
  : Node("component_talker", options)
  {
    publisher_ = create_publisher<std_msgs::msg::String>("chatter", 10);
    timer_ = create_wall_timer(
      100ms, [this]() {
        std_msgs::msg::String message;
        message.data = "component says " + std::to_string(++count_);
        publisher_->publish(message);
      });
  }

private:
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr publisher_;
  rclcpp::TimerBase::SharedPtr timer_;
  size_t count_ = 0;
};

/// Logs "component heard: <data>" for every message on "chatter".
class Listener : public rclcpp::Node
{
public:
  /// Create the component.
  explicit Listener(const rclcpp::NodeOptions & options)
  : Node("component_listener", options)
  {
    subscription_ = create_subscription<std_msgs::msg::String>(
      "chatter", 10, [this](const std_msgs::msg::String & message) {
        RCLCPP_INFO(get_logger(), "component heard: %s", message.data.c_str());
      });
  }

private:
  rclcpp::Subscription<std_msgs::msg::String>::SharedPtr subscription_;
};

}  // namespace rmw_wasm_cpp_node_tests

RCLCPP_COMPONENTS_REGISTER_NODE(rmw_wasm_cpp_node_tests::Talker)
RCLCPP_COMPONENTS_REGISTER_NODE(rmw_wasm_cpp_node_tests::Listener)
