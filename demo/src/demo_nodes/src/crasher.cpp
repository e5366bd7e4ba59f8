// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// A node that crashes on purpose after -p delay:=S seconds (default 2): it
// publishes a heartbeat, then executes an invalid instruction (a wasm trap),
// so that the launcher's crash report and fault isolation can be seen.

#include <chrono>
#include <string>
#include <thread>

#include "demo_nodes/support.hpp"

int main(int argc, char ** argv)
{
  auto args = demo_nodes::parse_arguments(argc, argv, "crasher");
  const std::string & name = args.node_name;
  double delay = demo_nodes::parameter(args, "delay", 2.0);
  auto context = demo_nodes::unwrap(wasm_cpp::Context::make({}), name, "creating the context");
  auto node = demo_nodes::unwrap(
    wasm_cpp::Node::make(context, name, args.node_namespace), name, "creating the node");
  auto publisher = demo_nodes::unwrap(
    wasm_cpp::Publisher::make(
      node, demo_nodes::resolve_name(args, "heartbeat"), "demo_interfaces/msg/Chatter",
      wasm_cpp::QoS{}),
    name, "creating the publisher");
  demo_nodes::log("WARN", name, "I will crash in %.1f s", delay);
  auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(delay);
  for (uint32_t count = 1; std::chrono::steady_clock::now() < end; ++count) {
    demo_nodes::CdrWriter cdr;
    cdr.put_string("alive");
    cdr.put<uint32_t>(count);
    demo_nodes::check(
      publisher->publish(cdr.bytes().data(), cdr.bytes().size()), name, "publishing");
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  demo_nodes::log("ERROR", name, "crashing now");
  __builtin_trap();
}
