// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Publishes demo_interfaces/msg/Sample on /wave: a sine and a cosine of
// frequency -p frequency:=HZ (default 0.5), rate:=HZ samples per second
// (default 20). A numeric topic to plot.

#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "demo_nodes/support.hpp"

int main(int argc, char ** argv)
{
  auto args = demo_nodes::parse_arguments(argc, argv, "oscillator");
  const std::string & name = args.node_name;
  double rate = demo_nodes::parameter(args, "rate", 20.0);
  double frequency = demo_nodes::parameter(args, "frequency", 0.5);
  auto context = demo_nodes::unwrap(wasm_cpp::Context::make({}), name, "creating the context");
  auto node = demo_nodes::unwrap(
    wasm_cpp::Node::make(context, name, args.node_namespace), name, "creating the node");
  std::string topic = demo_nodes::resolve_name(args, "wave");
  auto publisher = demo_nodes::unwrap(
    wasm_cpp::Publisher::make(node, topic, "demo_interfaces/msg/Sample", wasm_cpp::QoS{}),
    name, "creating the publisher");
  demo_nodes::log("INFO", name, "Publishing a %.2f Hz wave on %s at %.1f samples/s",
    frequency, topic.c_str(), rate);
  auto start = std::chrono::steady_clock::now();
  auto period = std::chrono::duration<double>(1.0 / (rate > 0 ? rate : 20.0));
  for (int32_t step = 0;; ++step) {
    double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double phase = 2.0 * M_PI * frequency * t;
    demo_nodes::CdrWriter cdr;
    cdr.put<double>(t);
    cdr.put<double>(std::sin(phase));
    cdr.put<double>(std::cos(phase));
    cdr.put<int32_t>(step);
    demo_nodes::check(
      publisher->publish(cdr.bytes().data(), cdr.bytes().size()), name, "publishing");
    std::this_thread::sleep_until(start + (step + 1) * period);
  }
}
