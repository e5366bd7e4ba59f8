// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Publishes demo_interfaces/msg/Chatter "Hello World: N" on /chatter every
// 1/rate seconds (-p rate:=HZ, default 1), keeping the last -p depth:=N
// messages for its subscribers (QoS history depth, default 10). The first
// goes out as soon as a subscriber has matched, and at the latest one period
// after the start (when a ROS talker's timer first fires): a listener started
// with the talker hears message 1, as a volatile subscriber that joined
// before the first publish does natively, and without waiting a period.

#include <chrono>
#include <string>
#include <thread>

#include "demo_nodes/support.hpp"

int main(int argc, char ** argv)
{
  auto args = demo_nodes::parse_arguments(argc, argv, "talker");
  const std::string & name = args.node_name;
  double rate = demo_nodes::parameter(args, "rate", 1.0);
  std::string text = demo_nodes::parameter(args, "message", std::string("Hello World"));
  auto context = demo_nodes::unwrap(wasm_cpp::Context::make({}), name, "creating the context");
  auto node = demo_nodes::unwrap(
    wasm_cpp::Node::make(context, name, args.node_namespace), name, "creating the node");
  std::string topic = demo_nodes::resolve_name(args, "chatter");
  wasm_cpp::QoS qos;
  double depth = demo_nodes::parameter(args, "depth", 10.0);
  qos.depth = depth >= 1 ? static_cast<size_t>(depth) : 1;
  auto publisher = demo_nodes::unwrap(
    wasm_cpp::Publisher::make(node, topic, "demo_interfaces/msg/Chatter", qos),
    name, "creating the publisher");
  auto period = std::chrono::duration<double>(1.0 / (rate > 0 ? rate : 1.0));
  auto first = std::chrono::steady_clock::now() +
    std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
  while (publisher->matched_subscription_count() == 0 &&
    std::chrono::steady_clock::now() < first)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  for (uint32_t count = 1;; ++count) {
    demo_nodes::CdrWriter cdr;
    std::string data = text + ": " + std::to_string(count);
    cdr.put_string(data);
    cdr.put<uint32_t>(count);
    demo_nodes::check(
      publisher->publish(cdr.bytes().data(), cdr.bytes().size()), name, "publishing");
    demo_nodes::log("INFO", name, "Publishing: '%s'", data.c_str());
    std::this_thread::sleep_for(period);
  }
}
