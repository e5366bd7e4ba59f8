// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The robot demo's moving parts: joint states that swing the arm (for
// robot_state_publisher), a laser-like point cloud of a square room seen
// from laser_frame, and markers (a label, the gripper's trail, a target).
//   -p rate:=HZ   joint states per second (default 30)
//   -p room:=M    the room's side in metres (default 4)

#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "rclcpp/rclcpp.hpp"
#include "sensor_msgs/msg/joint_state.hpp"
#include "sensor_msgs/msg/point_cloud2.hpp"
#include "sensor_msgs/msg/point_field.hpp"
#include "visualization_msgs/msg/marker_array.hpp"

using namespace std::chrono_literals;

class ArmMotion : public rclcpp::Node
{
public:
  ArmMotion()
  : Node("arm_motion"), start_(now())
  {
    double rate = declare_parameter("rate", 30.0);
    room_ = declare_parameter("room", 4.0);
    joints_ = create_publisher<sensor_msgs::msg::JointState>("joint_states", 10);
    cloud_ = create_publisher<sensor_msgs::msg::PointCloud2>("scan_cloud", rclcpp::SensorDataQoS());
    markers_ = create_publisher<visualization_msgs::msg::MarkerArray>("markers", 10);
    joint_timer_ = create_wall_timer(
      std::chrono::duration<double>(1.0 / (rate > 0 ? rate : 30.0)), [this] {publish_joints();});
    cloud_timer_ = create_wall_timer(100ms, [this] {publish_cloud();});
    marker_timer_ = create_wall_timer(200ms, [this] {publish_markers();});
    RCLCPP_INFO(get_logger(), "Moving demo_arm: joint states at %.0f Hz, a %.1f m room on "
      "/scan_cloud, markers on /markers", rate, room_);
  }

private:
  double seconds() {return (now() - start_).seconds();}

  void publish_joints()
  {
    double t = seconds();
    sensor_msgs::msg::JointState msg;
    msg.header.stamp = now();
    msg.name = {"shoulder_pan", "shoulder_lift", "elbow"};
    pan_ = 1.2 * std::sin(0.5 * t);
    lift_ = -0.6 + 0.4 * std::sin(0.9 * t);
    elbow_ = 1.0 + 0.7 * std::sin(1.3 * t);
    msg.position = {pan_, lift_, elbow_};
    joints_->publish(msg);
  }

  void publish_cloud()
  {
    // one scan line every 0.5 degrees, at three heights, of a square room
    // centred on the base; intensity falls with range
    const int beams = 720;
    const double heights[] = {-0.05, 0.0, 0.05};
    sensor_msgs::msg::PointCloud2 cloud;
    cloud.header.stamp = now();
    cloud.header.frame_id = "laser_frame";
    cloud.height = 1;
    cloud.width = beams * 3;
    const char * names[] = {"x", "y", "z", "intensity"};
    for (uint32_t i = 0; i < 4; ++i) {
      sensor_msgs::msg::PointField field;
      field.name = names[i];
      field.offset = 4 * i;
      field.datatype = sensor_msgs::msg::PointField::FLOAT32;
      field.count = 1;
      cloud.fields.push_back(field);
    }
    cloud.point_step = 16;
    cloud.row_step = cloud.point_step * cloud.width;
    cloud.is_dense = true;
    cloud.data.resize(cloud.row_step);
    float * out = reinterpret_cast<float *>(cloud.data.data());
    double half = room_ / 2;
    double spin = 0.2 * seconds();
    for (int b = 0; b < beams; ++b) {
      double a = 2 * M_PI * b / beams + spin;
      double c = std::cos(a);
      double s = std::sin(a);
      // the laser sits 0.2 m ahead of the base's centre
      double tx = std::abs(c) > 1e-9 ? ((c > 0 ? half : -half) - 0.2) / c : 1e9;
      double ty = std::abs(s) > 1e-9 ? (s > 0 ? half : -half) / s : 1e9;
      double r = std::min(tx, ty);
      for (int k = 0; k < 3; ++k) {
        float * p = out + 4 * (b * 3 + k);
        p[0] = static_cast<float>(r * c);
        p[1] = static_cast<float>(r * s);
        p[2] = static_cast<float>(heights[k]);
        p[3] = static_cast<float>(100.0 / (1.0 + r));
      }
    }
    cloud_->publish(cloud);
  }

  void publish_markers()
  {
    visualization_msgs::msg::MarkerArray array;
    auto base = [this](int id, int type) {
        visualization_msgs::msg::Marker m;
        m.header.frame_id = "base_link";
        m.header.stamp = now();
        m.ns = "demo_arm";
        m.id = id;
        m.type = type;
        m.action = visualization_msgs::msg::Marker::ADD;
        m.pose.orientation.w = 1.0;
        return m;
      };
    auto label = base(0, visualization_msgs::msg::Marker::TEXT_VIEW_FACING);
    label.pose.position.z = 1.1;
    label.scale.z = 0.12;
    label.color.r = label.color.g = label.color.b = label.color.a = 1.0;
    label.text = "demo_arm";
    array.markers.push_back(label);
    // the gripper's position from the joint angles (the URDF's chain)
    double reach = 0.5 * std::cos(lift_) + 0.54 * std::cos(lift_ + elbow_);
    double height = 0.22 - 0.5 * std::sin(lift_) - 0.54 * std::sin(lift_ + elbow_);
    geometry_msgs::msg::Point tip;
    tip.x = reach * std::cos(pan_);
    tip.y = reach * std::sin(pan_);
    tip.z = height;
    trail_.push_back(tip);
    if (trail_.size() > 40) {trail_.pop_front();}
    auto trail = base(1, visualization_msgs::msg::Marker::LINE_STRIP);
    trail.scale.x = 0.01;
    trail.color.g = 0.9;
    trail.color.b = 0.4;
    trail.color.a = 1.0;
    trail.points.assign(trail_.begin(), trail_.end());
    array.markers.push_back(trail);
    auto target = base(2, visualization_msgs::msg::Marker::SPHERE);
    target.pose.position = tip;
    target.scale.x = target.scale.y = target.scale.z = 0.06;
    target.color.r = 0.2;
    target.color.g = 1.0;
    target.color.b = 0.5;
    target.color.a = 0.8;
    target.lifetime = rclcpp::Duration::from_seconds(0.5);
    array.markers.push_back(target);
    markers_->publish(array);
  }

  rclcpp::Time start_;
  double room_;
  double pan_ = 0.0;
  double lift_ = 0.0;
  double elbow_ = 0.0;
  std::deque<geometry_msgs::msg::Point> trail_;
  rclcpp::Publisher<sensor_msgs::msg::JointState>::SharedPtr joints_;
  rclcpp::Publisher<sensor_msgs::msg::PointCloud2>::SharedPtr cloud_;
  rclcpp::Publisher<visualization_msgs::msg::MarkerArray>::SharedPtr markers_;
  rclcpp::TimerBase::SharedPtr joint_timer_;
  rclcpp::TimerBase::SharedPtr cloud_timer_;
  rclcpp::TimerBase::SharedPtr marker_timer_;
};

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<ArmMotion>());
  rclcpp::shutdown();
  return 0;
}
