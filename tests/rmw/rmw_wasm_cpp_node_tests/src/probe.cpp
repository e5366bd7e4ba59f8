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
/// Scenarios that exercise rmw_wasm_cpp through rclcpp, one per sub-command:
///
///   probe <scenario> [scenario args...] [--ros-args ...]
///
/// Every scenario reports through the ROS logger (so the host sees the
/// severity) with lines tests/test_rmw_nodes.py looks for.

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "composition_interfaces/srv/load_node.hpp"
#include "composition_interfaces/srv/list_nodes.hpp"
#include "composition_interfaces/srv/unload_node.hpp"
#include "example_interfaces/srv/add_two_ints.hpp"
#include "rclcpp/rclcpp.hpp"
#include "rosgraph_msgs/msg/clock.hpp"
#include "sensor_msgs/msg/image.hpp"
#include "std_msgs/msg/int32.hpp"
#include "std_msgs/msg/string.hpp"

using namespace std::chrono_literals;
using AddTwoInts = example_interfaces::srv::AddTwoInts;

namespace
{

// Publishes "<greeting> <n>" on "chatter"; its parameters come from the command line.
int param_talker(const std::vector<std::string> &)
{
  auto node = std::make_shared<rclcpp::Node>("param_talker");
  const std::string greeting = node->declare_parameter<std::string>("greeting", "hello");
  const int64_t period_ms = node->declare_parameter<int64_t>("period_ms", 100);
  auto publisher = node->create_publisher<std_msgs::msg::String>("chatter", 10);
  RCLCPP_DEBUG(node->get_logger(), "debug line");
  RCLCPP_INFO(node->get_logger(), "info line");
  RCLCPP_WARN(node->get_logger(), "warn line");
  RCLCPP_ERROR(node->get_logger(), "error line");
  RCLCPP_INFO(
    node->get_logger(), "NAME %s TOPIC %s DOMAIN %zu", node->get_fully_qualified_name(),
    publisher->get_topic_name(),
    node->get_node_base_interface()->get_context()->get_domain_id());
  size_t count = 0;
  auto timer = node->create_wall_timer(
    std::chrono::milliseconds(period_ms), [&]() {
      std_msgs::msg::String message;
      message.data = greeting + " " + std::to_string(++count);
      publisher->publish(message);
    });
  rclcpp::spin(node);
  return 0;
}

// Subscribes to "chatter" and logs what it hears.
int listener(const std::vector<std::string> &)
{
  auto node = std::make_shared<rclcpp::Node>("probe_listener");
  auto subscription = node->create_subscription<std_msgs::msg::String>(
    "chatter", 10, [&](const std_msgs::msg::String & message) {
      RCLCPP_INFO(node->get_logger(), "HEARD %s", message.data.c_str());
    });
  rclcpp::spin(node);
  return 0;
}

// Like listener, with a RELIABLE KEEP_ALL subscription: nothing is dropped for a burst
// (the rosbridge reconnection test of tests/test_rosbridge_client.py).
int keep_all_listener(const std::vector<std::string> &)
{
  auto node = std::make_shared<rclcpp::Node>("keep_all_listener");
  auto subscription = node->create_subscription<std_msgs::msg::String>(
    "chatter", rclcpp::QoS(rclcpp::KeepAll()).reliable(),
    [&](const std_msgs::msg::String & message) {
      RCLCPP_INFO(node->get_logger(), "HEARD %s", message.data.c_str());
    });
  rclcpp::spin(node);
  return 0;
}

// Like listener, spun by a MultiThreadedExecutor with 4 threads (for the idle CPU check).
int mt_listener(const std::vector<std::string> &)
{
  auto node = std::make_shared<rclcpp::Node>("mt_listener");
  auto subscription = node->create_subscription<std_msgs::msg::String>(
    "chatter", 10, [&](const std_msgs::msg::String & message) {
      RCLCPP_INFO(node->get_logger(), "HEARD %s", message.data.c_str());
    });
  rclcpp::executors::MultiThreadedExecutor executor(rclcpp::ExecutorOptions(), 4);
  executor.add_node(node);
  RCLCPP_INFO(node->get_logger(), "SPINNING with %zu threads", executor.get_number_of_threads());
  executor.spin();
  return 0;
}

// Reads a parameter of another node through its parameter services.
int param_reader(const std::vector<std::string> & args)
{
  if (args.size() < 2) {
    std::fprintf(stderr, "usage: probe param_reader <node> <parameter>\n");
    return 2;
  }
  auto node = std::make_shared<rclcpp::Node>("param_reader");
  auto client = std::make_shared<rclcpp::AsyncParametersClient>(node, args[0]);
  if (!client->wait_for_service(10s)) {
    RCLCPP_ERROR(node->get_logger(), "NO PARAMETER SERVICE for %s", args[0].c_str());
    return 1;
  }
  auto future = client->get_parameters({args[1]});
  if (rclcpp::spin_until_future_complete(node, future, 10s) !=
    rclcpp::FutureReturnCode::SUCCESS)
  {
    RCLCPP_ERROR(node->get_logger(), "GET PARAMETERS TIMED OUT");
    return 1;
  }
  for (const auto & parameter : future.get()) {
    RCLCPP_INFO(
      node->get_logger(), "PARAM %s=%s", parameter.get_name().c_str(),
      parameter.value_to_string().c_str());
  }
  return 0;
}

// Subscribes to a topic with std_msgs/msg/Int32 (while a String publisher uses it).
int wrong_type(const std::vector<std::string> & args)
{
  const std::string topic = args.empty() ? "topic" : args[0];
  auto node = std::make_shared<rclcpp::Node>("wrong_type");
  size_t received = 0;
  auto subscription = node->create_subscription<std_msgs::msg::Int32>(
    topic, 10, [&](const std_msgs::msg::Int32 &) {++received;});
  rclcpp::executors::SingleThreadedExecutor executor;
  executor.add_node(node);
  executor.spin_until_future_complete(std::promise<void>().get_future(), 1500ms);
  for (const auto & entry : node->get_topic_names_and_types()) {
    if (entry.first == subscription->get_topic_name()) {
      std::string types;
      for (const auto & type : entry.second) {
        types += (types.empty() ? "" : ", ") + type;
      }
      RCLCPP_INFO(node->get_logger(), "TYPES %s: %s", entry.first.c_str(), types.c_str());
    }
  }
  RCLCPP_INFO(
    node->get_logger(), "RECEIVED %zu MATCHED %zu", received, subscription->get_publisher_count());
  return 0;
}

// Calls a service nobody offers: the future stays pending and the wait times out.
int no_server(const std::vector<std::string> &)
{
  auto node = std::make_shared<rclcpp::Node>("no_server");
  auto client = node->create_client<AddTwoInts>("no_such_service");
  RCLCPP_INFO(node->get_logger(), "SERVICE READY %s", client->service_is_ready() ? "yes" : "no");
  auto request = std::make_shared<AddTwoInts::Request>();
  request->a = 1;
  request->b = 2;
  auto future = client->async_send_request(request);
  const auto start = std::chrono::steady_clock::now();
  const auto result = rclcpp::spin_until_future_complete(node, future, 500ms);
  const auto elapsed = std::chrono::duration_cast<std::chrono::milliseconds>(
    std::chrono::steady_clock::now() - start).count();
  RCLCPP_INFO(
    node->get_logger(), "RESULT %s after %lld ms; future pending %s",
    result == rclcpp::FutureReturnCode::TIMEOUT ? "TIMEOUT" : "NOT_TIMEOUT",
    static_cast<long long>(elapsed), future.wait_for(0s) == std::future_status::timeout ? "yes" : "no");
  return 0;
}

// Creates a publisher with an invalid topic name.
int invalid_topic(const std::vector<std::string> &)
{
  auto node = std::make_shared<rclcpp::Node>("invalid_topic");
  try {
    auto publisher = node->create_publisher<std_msgs::msg::String>("bad topic name!", 10);
    RCLCPP_ERROR(node->get_logger(), "CREATED a publisher on an invalid name");
    return 1;
  } catch (const std::exception & e) {
    RCLCPP_INFO(node->get_logger(), "REFUSED %s", e.what());
  }
  return 0;
}

// Publishes a message over the bus maximum, then a normal one.
int oversize(const std::vector<std::string> & args)
{
  const size_t size = args.empty() ? (2u << 20) : std::strtoull(args[0].c_str(), nullptr, 10);
  auto node = std::make_shared<rclcpp::Node>("oversize");
  auto publisher = node->create_publisher<std_msgs::msg::String>("big", 10);
  std_msgs::msg::String message;
  message.data.assign(size, 'x');
  try {
    publisher->publish(message);
    RCLCPP_INFO(node->get_logger(), "PUBLISHED %zu bytes", size);
  } catch (const std::exception & e) {
    RCLCPP_INFO(node->get_logger(), "REFUSED %s", e.what());
  }
  message.data = "small";
  publisher->publish(message);
  RCLCPP_INFO(node->get_logger(), "SMALL PUBLISH OK");
  return 0;
}

// Publishes /clock, starting at the given number of seconds.
int clock_publisher(const std::vector<std::string> & args)
{
  const int32_t start = args.empty() ? 1000 : std::atoi(args[0].c_str());
  auto node = std::make_shared<rclcpp::Node>("clock_publisher");
  auto publisher = node->create_publisher<rosgraph_msgs::msg::Clock>("/clock", 10);
  int64_t ticks = 0;
  auto timer = node->create_wall_timer(
    50ms, [&]() {
      rosgraph_msgs::msg::Clock message;
      message.clock.sec = start + static_cast<int32_t>(ticks / 10);
      message.clock.nanosec = static_cast<uint32_t>((ticks % 10) * 100000000);
      ++ticks;
      publisher->publish(message);
    });
  rclcpp::spin(node);
  return 0;
}

// Reports ROS time once it comes from /clock (run with -p use_sim_time:=true).
int sim_time(const std::vector<std::string> &)
{
  auto node = std::make_shared<rclcpp::Node>("sim_time");
  RCLCPP_INFO(
    node->get_logger(), "USE_SIM_TIME %s",
    node->get_parameter("use_sim_time").as_bool() ? "true" : "false");
  rclcpp::TimerBase::SharedPtr timer;
  timer = node->create_wall_timer(
    100ms, [&]() {
      const rclcpp::Time now = node->now();
      if (now.nanoseconds() > 0) {
        RCLCPP_INFO(node->get_logger(), "SIM_TIME %.1f", now.seconds());
        timer->cancel();
        rclcpp::shutdown();
      }
    });
  rclcpp::spin(node);
  return 0;
}

// An AddTwoInts server on "hold" that never answers (it holds every request).
int hold_server(const std::vector<std::string> &)
{
  auto node = std::make_shared<rclcpp::Node>("hold_server");
  auto service = node->create_service<AddTwoInts>(
    "hold", [&](
      std::shared_ptr<rclcpp::Service<AddTwoInts>>, std::shared_ptr<rmw_request_id_t> id,
      std::shared_ptr<AddTwoInts::Request> request) {
      RCLCPP_INFO(
        node->get_logger(), "HOLDING request %lld (%lld + %lld)",
        static_cast<long long>(id->sequence_number), static_cast<long long>(request->a),
        static_cast<long long>(request->b));
    });
  rclcpp::spin(node);
  return 0;
}

// An AddTwoInts server on "hold" that answers.
int add_server(const std::vector<std::string> &)
{
  auto node = std::make_shared<rclcpp::Node>("add_server");
  auto service = node->create_service<AddTwoInts>(
    "hold", [&](
      const std::shared_ptr<AddTwoInts::Request> request,
      std::shared_ptr<AddTwoInts::Response> response) {
      response->sum = request->a + request->b;
      RCLCPP_INFO(node->get_logger(), "ANSWERED %lld", static_cast<long long>(response->sum));
    });
  rclcpp::spin(node);
  return 0;
}

// Sends 2 + 3 to "hold"; when the server disappears with the request, re-sends it
// to the next server. A timer drives it: the executor sleeps in between.
int caller(const std::vector<std::string> &)
{
  auto node = std::make_shared<rclcpp::Node>("caller");
  auto client = node->create_client<AddTwoInts>("hold");
  auto request = std::make_shared<AddTwoInts::Request>();
  request->a = 2;
  request->b = 3;
  std::shared_ptr<rclcpp::Client<AddTwoInts>::FutureAndRequestId> pending;
  bool server_was_seen = false;
  bool lost_reported = false;
  rclcpp::TimerBase::SharedPtr timer;
  timer = node->create_wall_timer(
    100ms, [&]() {
      const bool ready = client->service_is_ready();
      if (pending && pending->future.wait_for(0s) == std::future_status::ready) {
        RCLCPP_INFO(
          node->get_logger(), "RESULT %lld",
          static_cast<long long>(pending->future.get()->sum));
        timer->cancel();
        rclcpp::shutdown();
        return;
      }
      if (pending && !ready && server_was_seen && !lost_reported) {
        const size_t pruned = client->prune_pending_requests();
        RCLCPP_WARN(
          node->get_logger(), "SERVER GONE with the request; pruned %zu pending", pruned);
        lost_reported = true;
        pending.reset();
      }
      if (!pending && ready) {
        server_was_seen = true;
        lost_reported = false;
        pending = std::make_shared<rclcpp::Client<AddTwoInts>::FutureAndRequestId>(
          client->async_send_request(request));
        RCLCPP_INFO(node->get_logger(), "SENT request %lld",
          static_cast<long long>(pending->request_id));
      }
    });
  rclcpp::spin(node);
  return 0;
}

// Asks a component container to load a component.
int load_component(const std::vector<std::string> & args)
{
  if (args.size() < 3) {
    std::fprintf(stderr, "usage: probe load_component <container> <package> <class>\n");
    return 2;
  }
  using LoadNode = composition_interfaces::srv::LoadNode;
  auto node = std::make_shared<rclcpp::Node>("component_loader");
  auto client = node->create_client<LoadNode>(args[0] + "/_container/load_node");
  if (!client->wait_for_service(10s)) {
    RCLCPP_ERROR(node->get_logger(), "NO CONTAINER %s", args[0].c_str());
    return 1;
  }
  auto request = std::make_shared<LoadNode::Request>();
  request->package_name = args[1];
  request->plugin_name = args[2];
  auto future = client->async_send_request(request);
  if (rclcpp::spin_until_future_complete(node, future, 10s) !=
    rclcpp::FutureReturnCode::SUCCESS)
  {
    RCLCPP_ERROR(node->get_logger(), "LOAD TIMED OUT");
    return 1;
  }
  auto response = future.get();
  if (response->success) {
    RCLCPP_INFO(
      node->get_logger(), "LOADED %s id %llu", response->full_node_name.c_str(),
      static_cast<unsigned long long>(response->unique_id));
  } else {
    RCLCPP_INFO(node->get_logger(), "LOAD FAILED %s", response->error_message.c_str());
  }
  return 0;
}

// Lists the nodes of a component container: "LISTED <name> id <id>" each.
int list_components(const std::vector<std::string> & args)
{
  if (args.empty()) {
    std::fprintf(stderr, "usage: probe list_components <container>\n");
    return 2;
  }
  using ListNodes = composition_interfaces::srv::ListNodes;
  auto node = std::make_shared<rclcpp::Node>("component_lister");
  auto client = node->create_client<ListNodes>(args[0] + "/_container/list_nodes");
  if (!client->wait_for_service(10s)) {
    RCLCPP_ERROR(node->get_logger(), "NO CONTAINER %s", args[0].c_str());
    return 1;
  }
  auto future = client->async_send_request(std::make_shared<ListNodes::Request>());
  if (rclcpp::spin_until_future_complete(node, future, 10s) !=
    rclcpp::FutureReturnCode::SUCCESS)
  {
    RCLCPP_ERROR(node->get_logger(), "LIST TIMED OUT");
    return 1;
  }
  auto response = future.get();
  for (size_t i = 0; i < response->full_node_names.size(); ++i) {
    RCLCPP_INFO(
      node->get_logger(), "LISTED %s id %llu", response->full_node_names[i].c_str(),
      static_cast<unsigned long long>(response->unique_ids[i]));
  }
  RCLCPP_INFO(node->get_logger(), "LISTED %zu nodes", response->full_node_names.size());
  return 0;
}

// Asks a component container to unload the node of an id.
int unload_component(const std::vector<std::string> & args)
{
  if (args.size() < 2) {
    std::fprintf(stderr, "usage: probe unload_component <container> <id>\n");
    return 2;
  }
  using UnloadNode = composition_interfaces::srv::UnloadNode;
  auto node = std::make_shared<rclcpp::Node>("component_unloader");
  auto client = node->create_client<UnloadNode>(args[0] + "/_container/unload_node");
  if (!client->wait_for_service(10s)) {
    RCLCPP_ERROR(node->get_logger(), "NO CONTAINER %s", args[0].c_str());
    return 1;
  }
  auto request = std::make_shared<UnloadNode::Request>();
  request->unique_id = std::stoull(args[1]);
  auto future = client->async_send_request(request);
  if (rclcpp::spin_until_future_complete(node, future, 10s) !=
    rclcpp::FutureReturnCode::SUCCESS)
  {
    RCLCPP_ERROR(node->get_logger(), "UNLOAD TIMED OUT");
    return 1;
  }
  auto response = future.get();
  RCLCPP_INFO(
    node->get_logger(), "%s %s", response->success ? "UNLOADED" : "UNLOAD FAILED",
    response->success ? args[1].c_str() : response->error_message.c_str());
  return 0;
}


// ---------------------------------------------------------------- bench/rclcpp

// A message of the bench: a 32-character std_msgs/String or a 1 MiB sensor_msgs/Image.
template<typename T>
T bench_message();

template<>
std_msgs::msg::String bench_message<std_msgs::msg::String>()
{
  std_msgs::msg::String message;
  message.data.assign(32, 'x');
  return message;
}

template<>
sensor_msgs::msg::Image bench_message<sensor_msgs::msg::Image>()
{
  sensor_msgs::msg::Image message;
  message.header.frame_id = "camera";
  message.width = 512;
  message.height = 512;
  message.encoding = "rgba8";
  message.step = 4 * 512;
  message.data.assign(4 * 512 * 512, 0x5a);
  return message;
}

// Write and read the sequence number a bench message carries.
void stamp(std_msgs::msg::String & message, uint32_t n)
{
  std::memcpy(&message.data[0], &n, sizeof(n));
}
uint32_t stamp_of(const std_msgs::msg::String & message)
{
  uint32_t n = 0;
  std::memcpy(&n, message.data.data(), sizeof(n));
  return n;
}
void stamp(sensor_msgs::msg::Image & message, uint32_t n) {message.header.stamp.nanosec = n;}
uint32_t stamp_of(const sensor_msgs::msg::Image & message) {return message.header.stamp.nanosec;}

// Echo every message of bench/ping on bench/pong.
template<typename T>
int bench_pong()
{
  auto node = std::make_shared<rclcpp::Node>("bench_pong");
  auto publisher = node->create_publisher<T>("bench/pong", rclcpp::QoS(10));
  auto subscription = node->create_subscription<T>(
    "bench/ping", rclcpp::QoS(10), [&](const T & message) {publisher->publish(message);});
  RCLCPP_INFO(node->get_logger(), "READY");
  rclcpp::spin(node);
  return 0;
}

// Send `count` messages to bench_pong, one at a time; report the one-way latency (RTT / 2).
template<typename T>
int bench_ping(const std::vector<std::string> & args)
{
  const long count = args.size() > 0 ? std::atol(args[0].c_str()) : 1000;  // NOLINT
  const long warmup = args.size() > 1 ? std::atol(args[1].c_str()) : 100;  // NOLINT
  auto node = std::make_shared<rclcpp::Node>("bench_ping");
  auto publisher = node->create_publisher<T>("bench/ping", rclcpp::QoS(10));
  uint32_t expected = 0;
  bool answered = false;
  auto subscription = node->create_subscription<T>(
    "bench/pong", rclcpp::QoS(10), [&](const T & message) {
      answered = stamp_of(message) == expected;
    });
  rclcpp::executors::SingleThreadedExecutor executor;
  executor.add_node(node);
  while (rclcpp::ok() &&
    (publisher->get_subscription_count() == 0 || subscription->get_publisher_count() == 0))
  {
    executor.spin_once(100ms);  // woken by the graph change
  }
  T message = bench_message<T>();
  std::vector<double> one_way;
  for (long i = 0; i < warmup + count && rclcpp::ok(); ++i) {  // NOLINT
    expected = static_cast<uint32_t>(i);
    answered = false;
    stamp(message, expected);
    const auto t0 = std::chrono::steady_clock::now();
    publisher->publish(message);
    while (!answered && rclcpp::ok()) {
      executor.spin_once(5s);
    }
    const double us = std::chrono::duration<double, std::micro>(
      std::chrono::steady_clock::now() - t0).count();
    if (i >= warmup) {
      one_way.push_back(us / 2);
    }
  }
  std::sort(one_way.begin(), one_way.end());
  auto pct = [&](double p) {
      return one_way[std::min(one_way.size() - 1, static_cast<size_t>(p * one_way.size()))];
    };
  std::printf(
    "RESULT count=%zu p50_us=%.2f p99_us=%.2f min_us=%.2f max_us=%.2f\n",
    one_way.size(), pct(0.5), pct(0.99), one_way.front(), one_way.back());
  return 0;
}

// Publish `count` strings as fast as a RELIABLE KEEP_ALL subscription takes them.
int bench_flood(const std::vector<std::string> & args)
{
  const uint32_t count = args.empty() ? 100000 : static_cast<uint32_t>(std::atol(args[0].c_str()));
  auto node = std::make_shared<rclcpp::Node>("bench_flood");
  auto publisher = node->create_publisher<std_msgs::msg::String>(
    "bench/flood", rclcpp::QoS(rclcpp::KeepAll()).reliable());
  rclcpp::executors::SingleThreadedExecutor executor;
  executor.add_node(node);
  while (rclcpp::ok() && publisher->get_subscription_count() == 0) {
    executor.spin_once(100ms);
  }
  auto message = bench_message<std_msgs::msg::String>();
  const auto t0 = std::chrono::steady_clock::now();
  for (uint32_t i = 0; i < count; ++i) {
    stamp(message, i);
    publisher->publish(message);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("RESULT published=%u publish_per_s=%.0f\n", count, count / s);
  return 0;
}

// Take `count` strings from bench_flood; report the rate, losses and disorder.
int bench_sink(const std::vector<std::string> & args)
{
  const uint32_t count = args.empty() ? 100000 : static_cast<uint32_t>(std::atol(args[0].c_str()));
  auto node = std::make_shared<rclcpp::Node>("bench_sink");
  uint32_t received = 0;
  uint32_t disorder = 0;
  uint32_t last = 0;
  std::chrono::steady_clock::time_point first;
  auto subscription = node->create_subscription<std_msgs::msg::String>(
    "bench/flood", rclcpp::QoS(rclcpp::KeepAll()).reliable(),
    [&](const std_msgs::msg::String & message) {
      const uint32_t n = stamp_of(message);
      if (received == 0) {
        first = std::chrono::steady_clock::now();
      } else if (n != last + 1) {
        ++disorder;
      }
      last = n;
      if (++received == count) {
        const double s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - first).count();
        std::printf(
          "RESULT received=%u lost=%u disorder=%u msgs_per_s=%.0f\n", received,
          count - received, disorder, (count - 1) / s);
        rclcpp::shutdown();
      }
    });
  RCLCPP_INFO(node->get_logger(), "READY");
  rclcpp::spin(node);
  return 0;
}

// Publish one message on /bench/hello as soon as the node exists (node start time).
int bench_hello(const std::vector<std::string> &)
{
  auto node = std::make_shared<rclcpp::Node>("bench_hello");
  auto publisher = node->create_publisher<std_msgs::msg::String>("/bench/hello", 10);
  std_msgs::msg::String message;
  message.data = "hello";
  publisher->publish(message);
  return 0;
}

}  // namespace

int main(int argc, char ** argv)
{
  const std::vector<std::string> args = rclcpp::init_and_remove_ros_arguments(argc, argv);
  const std::vector<std::string> rest(args.size() > 2 ? args.begin() + 2 : args.end(), args.end());
  const std::string scenario = args.size() > 1 ? args[1] : "";
  const struct
  {
    const char * name;
    std::function<int(const std::vector<std::string> &)> run;
  } scenarios[] = {
    {"param_talker", param_talker}, {"listener", listener}, {"mt_listener", mt_listener},
    {"keep_all_listener", keep_all_listener},
    {"param_reader", param_reader},
    {"wrong_type", wrong_type}, {"no_server", no_server}, {"invalid_topic", invalid_topic},
    {"oversize", oversize}, {"clock", clock_publisher}, {"sim_time", sim_time},
    {"hold_server", hold_server}, {"add_server", add_server}, {"caller", caller},
    {"load_component", load_component}, {"list_components", list_components},
    {"unload_component", unload_component},
    {"bench_pong_string", [](const std::vector<std::string> &) {
        return bench_pong<std_msgs::msg::String>();
      }},
    {"bench_pong_image", [](const std::vector<std::string> &) {
        return bench_pong<sensor_msgs::msg::Image>();
      }},
    {"bench_ping_string", bench_ping<std_msgs::msg::String>},
    {"bench_ping_image", bench_ping<sensor_msgs::msg::Image>},
    {"bench_flood", bench_flood}, {"bench_sink", bench_sink}, {"bench_hello", bench_hello},
  };
  for (const auto & s : scenarios) {
    if (scenario == s.name) {
      const int code = s.run(rest);
      if (rclcpp::ok()) {
        rclcpp::shutdown();
      }
      return code;
    }
  }
  std::string names;
  for (const auto & s : scenarios) {
    names += std::string(names.empty() ? "" : ", ") + s.name;
  }
  std::fprintf(stderr, "probe: unknown scenario '%s'; one of: %s\n", scenario.c_str(), names.c_str());
  rclcpp::shutdown();
  return 2;
}
