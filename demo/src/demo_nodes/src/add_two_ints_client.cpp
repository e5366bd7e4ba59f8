// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Calls /add_two_ints every second with a = N, b = 2N and logs the sum; waits
// for the server first (woken by graph changes, not by polling).

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "demo_nodes/support.hpp"

int main(int argc, char ** argv)
{
  auto args = demo_nodes::parse_arguments(argc, argv, "add_two_ints_client");
  const std::string & name = args.node_name;
  double period = demo_nodes::parameter(args, "period", 1.0);
  auto context = demo_nodes::unwrap(wasm_cpp::Context::make({}), name, "creating the context");
  auto node = demo_nodes::unwrap(
    wasm_cpp::Node::make(context, name, args.node_namespace), name, "creating the node");
  std::string service_name = demo_nodes::resolve_name(args, "add_two_ints");
  auto client = demo_nodes::unwrap(
    wasm_cpp::Client::make(node, service_name, "demo_interfaces/srv/AddTwoInts", wasm_cpp::QoS{}),
    name, "creating the client");
  auto graph = demo_nodes::unwrap(
    wasm_cpp::GuardCondition::make_graph(context), name, "creating the graph guard condition");
  auto wait_set = demo_nodes::unwrap(wasm_cpp::WaitSet::make(context), name, "creating a wait set");
  std::vector<wasm_cpp::WaitItem> graph_items{wasm_cpp::WaitItem::of(graph.get())};
  while (!client->server_is_available()) {
    demo_nodes::log("INFO", name, "service %s not available, waiting again...",
      service_name.c_str());
    // a second without a graph change is no failure: look again (a server may take long to start)
    wasm_cpp::Status waited = wait_set->wait(graph_items, std::chrono::seconds(1));
    if (waited.code() != wasm_cpp::Code::kTimeout) {
      demo_nodes::check(waited, name, "waiting");
    }
  }
  std::vector<wasm_cpp::WaitItem> response_items{wasm_cpp::WaitItem::of(client.get())};
  for (int64_t n = 1;; ++n) {
    demo_nodes::CdrWriter request;
    request.put<int64_t>(n);
    request.put<int64_t>(2 * n);
    int64_t sequence = 0;
    demo_nodes::check(
      client->send_request(request.bytes().data(), request.bytes().size(), &sequence),
      name, "sending the request");
    bool answered = false;
    auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (!answered && std::chrono::steady_clock::now() < deadline) {
      response_items[0].ready = false;
      wasm_cpp::Status status = wait_set->wait(response_items, std::chrono::seconds(5));
      if (status.code() == wasm_cpp::Code::kTimeout) {break;}
      demo_nodes::check(status, name, "waiting for the response");
      wasm_cpp::Message response;
      wasm_cpp::ServiceInfo info;
      bool taken = false;
      demo_nodes::check(client->take_response(&response, &info, &taken), name, "taking");
      if (taken && info.request_id.sequence_number == sequence) {
        demo_nodes::CdrReader cdr(response.data.get(), response.size);
        demo_nodes::log("INFO", name, "Result of add_two_ints: for %lld + %lld = %lld",
          static_cast<long long>(n), static_cast<long long>(2 * n),
          static_cast<long long>(cdr.get<int64_t>()));
        answered = true;
      }
    }
    if (!answered) {
      demo_nodes::log("WARN", name, "no response to request %lld within 5 s",
        static_cast<long long>(sequence));
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(period));
  }
}
