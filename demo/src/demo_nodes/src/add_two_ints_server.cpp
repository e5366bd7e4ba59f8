// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Serves /add_two_ints (demo_interfaces/srv/AddTwoInts): sum = a + b.

#include <stdexcept>
#include <string>
#include <vector>

#include "demo_nodes/support.hpp"

int main(int argc, char ** argv)
{
  auto args = demo_nodes::parse_arguments(argc, argv, "add_two_ints_server");
  const std::string & name = args.node_name;
  auto context = demo_nodes::unwrap(wasm_cpp::Context::make({}), name, "creating the context");
  auto node = demo_nodes::unwrap(
    wasm_cpp::Node::make(context, name, args.node_namespace), name, "creating the node");
  std::string service_name = demo_nodes::resolve_name(args, "add_two_ints");
  auto service = demo_nodes::unwrap(
    wasm_cpp::Service::make(node, service_name, "demo_interfaces/srv/AddTwoInts", wasm_cpp::QoS{}),
    name, "creating the service");
  auto wait_set = demo_nodes::unwrap(wasm_cpp::WaitSet::make(context), name, "creating a wait set");
  std::vector<wasm_cpp::WaitItem> items{wasm_cpp::WaitItem::of(service.get())};
  demo_nodes::log("INFO", name, "Ready to add two ints on %s", service_name.c_str());
  for (;;) {
    demo_nodes::check(wait_set->wait(items, wasm_cpp::kForever), name, "waiting");
    for (;;) {
      wasm_cpp::Message request;
      wasm_cpp::ServiceInfo info;
      bool taken = false;
      demo_nodes::check(service->take_request(&request, &info, &taken), name, "taking a request");
      if (!taken) {break;}
      try {
        demo_nodes::CdrReader cdr(request.data.get(), request.size);
        int64_t a = cdr.get<int64_t>();
        int64_t b = cdr.get<int64_t>();
        demo_nodes::log("INFO", name, "Incoming request: a: %lld b: %lld",
          static_cast<long long>(a), static_cast<long long>(b));
        demo_nodes::CdrWriter response;
        response.put<int64_t>(a + b);
        demo_nodes::check(
          service->send_response(info.request_id, response.bytes().data(), response.bytes().size()),
          name, "sending the response");
      } catch (const std::runtime_error & e) {
        demo_nodes::log("ERROR", name, "cannot decode a request of %zu bytes: %s",
          request.size, e.what());
      }
    }
  }
}
