// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Publishes demo_interfaces/msg/Chatter "Hello World: N" on /chatter, first
// at once, then every 1/rate seconds (-p rate:=HZ, default 1), keeping the
// last -p depth:=N messages for its subscribers (QoS history depth, default 10).

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
