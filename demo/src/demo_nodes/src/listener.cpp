// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Subscribes to /chatter (demo_interfaces/msg/Chatter) and logs each message.

#include <stdexcept>
#include <string>
#include <vector>

#include "demo_nodes/support.hpp"

int main(int argc, char ** argv)
{
  auto args = demo_nodes::parse_arguments(argc, argv, "listener");
  const std::string & name = args.node_name;
  auto context = demo_nodes::unwrap(wasm_cpp::Context::make({}), name, "creating the context");
  auto node = demo_nodes::unwrap(
    wasm_cpp::Node::make(context, name, args.node_namespace), name, "creating the node");
  std::string topic = demo_nodes::resolve_name(args, "chatter");
  auto subscription = demo_nodes::unwrap(
    wasm_cpp::Subscription::make(node, topic, "demo_interfaces/msg/Chatter", wasm_cpp::QoS{}),
    name, "creating the subscription");
  auto wait_set = demo_nodes::unwrap(wasm_cpp::WaitSet::make(context), name, "creating a wait set");
  std::vector<wasm_cpp::WaitItem> items{wasm_cpp::WaitItem::of(subscription.get())};
  for (;;) {
    demo_nodes::check(wait_set->wait(items, wasm_cpp::kForever), name, "waiting");
    for (;;) {
      wasm_cpp::Message message;
      bool taken = false;
      demo_nodes::check(subscription->take(&message, nullptr, &taken), name, "taking");
      if (!taken) {break;}
      try {
        demo_nodes::CdrReader cdr(message.data.get(), message.size);
        std::string data = cdr.get_string();
        demo_nodes::log("INFO", name, "I heard: [%s]", data.c_str());
      } catch (const std::runtime_error & e) {
        demo_nodes::log("ERROR", name, "cannot decode a message of %zu bytes: %s",
          message.size, e.what());
      }
    }
  }
}
