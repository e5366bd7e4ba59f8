// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// corpus_probe joint_states NAME=POSITION...   publish sensor_msgs/JointState at 20 Hz
// corpus_probe tf                              print each transform of /tf and /tf_static
// corpus_probe diagnostics                     publish a DiagnosticArray at 2 Hz and print
//                                              each status of /diagnostics_agg

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "diagnostic_msgs/msg/diagnostic_array.hpp"
#include "rclcpp/rclcpp.hpp"
#include "sensor_msgs/msg/joint_state.hpp"
#include "tf2_msgs/msg/tf_message.hpp"

using namespace std::chrono_literals;

namespace
{

void print_transforms(const tf2_msgs::msg::TFMessage & message, const char * topic,
  std::map<std::string, std::string> & seen)
{
  for (const auto & t : message.transforms) {
    char line[512];
    std::snprintf(line, sizeof(line), "TF %s %s->%s %.3f %.3f %.3f %.3f %.3f %.3f %.3f", topic,
      t.header.frame_id.c_str(), t.child_frame_id.c_str(), t.transform.translation.x,
      t.transform.translation.y, t.transform.translation.z, t.transform.rotation.x,
      t.transform.rotation.y, t.transform.rotation.z, t.transform.rotation.w);
    const std::string key = std::string(topic) + t.child_frame_id;
    if (seen[key] != line) {
      seen[key] = line;
      std::printf("%s\n", line);
      std::fflush(stdout);
    }
  }
}

}  // namespace

int main(int argc, char ** argv)
{
  auto args = rclcpp::init_and_remove_ros_arguments(argc, argv);
  const std::string mode = args.size() > 1 ? args[1] : "";
  auto node = std::make_shared<rclcpp::Node>("corpus_probe_" + (mode.empty() ? "x" : mode));
  rclcpp::TimerBase::SharedPtr timer;
  rclcpp::PublisherBase::SharedPtr publisher;
  std::vector<rclcpp::SubscriptionBase::SharedPtr> subscriptions;
  std::map<std::string, std::string> seen;
  if (mode == "joint_states") {
    auto pub = node->create_publisher<sensor_msgs::msg::JointState>("joint_states", 10);
    auto state = std::make_shared<sensor_msgs::msg::JointState>();
    for (size_t i = 2; i < args.size(); ++i) {
      const auto eq = args[i].find('=');
      state->name.push_back(args[i].substr(0, eq));
      state->position.push_back(std::stod(args[i].substr(eq + 1)));
    }
    publisher = pub;
    timer = node->create_wall_timer(50ms, [node, pub, state]() {
      state->header.stamp = node->now();
      pub->publish(*state);
    });
  } else if (mode == "tf") {
    subscriptions.push_back(node->create_subscription<tf2_msgs::msg::TFMessage>(
      "/tf", 100, [&seen](const tf2_msgs::msg::TFMessage & m) {print_transforms(m, "/tf", seen);}));
    subscriptions.push_back(node->create_subscription<tf2_msgs::msg::TFMessage>(
      "/tf_static", rclcpp::QoS(100).transient_local(),
      [&seen](const tf2_msgs::msg::TFMessage & m) {print_transforms(m, "/tf_static", seen);}));
  } else if (mode == "diagnostics") {
    auto pub = node->create_publisher<diagnostic_msgs::msg::DiagnosticArray>("/diagnostics", 10);
    publisher = pub;
    timer = node->create_wall_timer(500ms, [node, pub]() {
      diagnostic_msgs::msg::DiagnosticArray array;
      array.header.stamp = node->now();
      diagnostic_msgs::msg::DiagnosticStatus imu;
      imu.name = "imu";
      imu.hardware_id = "imu0";
      imu.level = diagnostic_msgs::msg::DiagnosticStatus::OK;
      imu.message = "imu fine";
      diagnostic_msgs::msg::DiagnosticStatus motor;
      motor.name = "motor_left";
      motor.hardware_id = "motor0";
      motor.level = diagnostic_msgs::msg::DiagnosticStatus::WARN;
      motor.message = "motor hot";
      array.status = {imu, motor};
      pub->publish(array);
    });
    subscriptions.push_back(node->create_subscription<diagnostic_msgs::msg::DiagnosticArray>(
      "/diagnostics_agg", 10, [&seen](const diagnostic_msgs::msg::DiagnosticArray & m) {
        for (const auto & s : m.status) {
          char line[512];
          std::snprintf(line, sizeof(line), "AGG %s level=%d %s", s.name.c_str(),
            static_cast<int>(s.level), s.message.c_str());
          if (seen[s.name] != line) {
            seen[s.name] = line;
            std::printf("%s\n", line);
            std::fflush(stdout);
          }
        }
      }));
  } else {
    std::fprintf(stderr, "usage: corpus_probe joint_states NAME=POS... | tf | diagnostics\n");
    return 2;
  }
  rclcpp::spin(node);
  rclcpp::shutdown();
  return 0;
}
