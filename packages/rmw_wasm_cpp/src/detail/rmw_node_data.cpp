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

#include "detail/rmw_node_data.hpp"

#include <memory>
#include <string>
#include <utility>

#include "detail/identifier.hpp"
#include "detail/logging_macros.hpp"
#include "detail/rmw_publisher_data.hpp"
#include "detail/rmw_service_data.hpp"
#include "detail/rmw_subscription_data.hpp"
#include "detail/status.hpp"

namespace rmw_wasm_cpp
{

NodeData::NodeData(
  std::shared_ptr<wasm_cpp::Node> node, std::shared_ptr<wasm_cpp::GuardCondition> graph_guard)
: node_(std::move(node)), graph_guard_(GuardConditionData::make(std::move(graph_guard)))
{
  graph_guard_handle_.implementation_identifier = kIdentifier;
  graph_guard_handle_.data = graph_guard_.get();
  graph_guard_handle_.context = nullptr;
}

std::shared_ptr<NodeData> NodeData::make(
  const std::shared_ptr<wasm_cpp::Context> & context,
  const char * name, const char * namespace_)
{
  auto graph_guard = wasm_cpp::GuardCondition::make_graph(context);
  if (!graph_guard.ok()) {
    to_rmw_ret(graph_guard.status());
    return nullptr;
  }
  auto node = wasm_cpp::Node::make(context, name, namespace_);
  if (!node.ok()) {
    to_rmw_ret(node.status());
    return nullptr;
  }
  if (node.value()->name_was_taken()) {
    RMW_WASM_LOG_WARN(
      "a node named '%s' already exists in domain %zu; node names should be unique "
      "(tools such as 'ros2 node list' cannot tell the two apart)",
      node.value()->fully_qualified_name().c_str(), context->domain_id());
  }
  return std::shared_ptr<NodeData>(new NodeData(node.value(), graph_guard.value()));
}

void NodeData::add_publisher(
  const rmw_publisher_t * handle, std::shared_ptr<PublisherData> publisher)
{
  std::lock_guard<std::mutex> lock(mutex_);
  publishers_[handle] = std::move(publisher);
}

void NodeData::remove_publisher(const rmw_publisher_t * handle)
{
  std::shared_ptr<PublisherData> publisher;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = publishers_.find(handle);
    if (it == publishers_.end()) {
      return;
    }
    publisher = std::move(it->second);
    publishers_.erase(it);
  }
  publisher->shutdown();
}

void NodeData::add_subscription(
  const rmw_subscription_t * handle, std::shared_ptr<SubscriptionData> subscription)
{
  std::lock_guard<std::mutex> lock(mutex_);
  subscriptions_[handle] = std::move(subscription);
}

void NodeData::remove_subscription(const rmw_subscription_t * handle)
{
  std::shared_ptr<SubscriptionData> subscription;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = subscriptions_.find(handle);
    if (it == subscriptions_.end()) {
      return;
    }
    subscription = std::move(it->second);
    subscriptions_.erase(it);
  }
  subscription->shutdown();
}

void NodeData::add_service(const rmw_service_t * handle, std::shared_ptr<ServiceData> service)
{
  std::lock_guard<std::mutex> lock(mutex_);
  services_[handle] = std::move(service);
}

void NodeData::remove_service(const rmw_service_t * handle)
{
  std::shared_ptr<ServiceData> service;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = services_.find(handle);
    if (it == services_.end()) {
      return;
    }
    service = std::move(it->second);
    services_.erase(it);
  }
  service->shutdown();
}

void NodeData::add_client(const rmw_client_t * handle, std::shared_ptr<ClientData> client)
{
  std::lock_guard<std::mutex> lock(mutex_);
  clients_[handle] = std::move(client);
}

void NodeData::remove_client(const rmw_client_t * handle)
{
  std::shared_ptr<ClientData> client;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = clients_.find(handle);
    if (it == clients_.end()) {
      return;
    }
    client = std::move(it->second);
    clients_.erase(it);
  }
  client->shutdown();
}

void NodeData::shutdown()
{
  std::unordered_map<const rmw_publisher_t *, std::shared_ptr<PublisherData>> publishers;
  std::unordered_map<const rmw_subscription_t *, std::shared_ptr<SubscriptionData>> subscriptions;
  std::unordered_map<const rmw_service_t *, std::shared_ptr<ServiceData>> services;
  std::unordered_map<const rmw_client_t *, std::shared_ptr<ClientData>> clients;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    publishers.swap(publishers_);
    subscriptions.swap(subscriptions_);
    services.swap(services_);
    clients.swap(clients_);
  }
  for (auto & entry : publishers) {entry.second->shutdown();}
  for (auto & entry : subscriptions) {entry.second->shutdown();}
  for (auto & entry : services) {entry.second->shutdown();}
  for (auto & entry : clients) {entry.second->shutdown();}
  node_->shutdown();
}

NodeData::~NodeData()
{
  shutdown();
}

}  // namespace rmw_wasm_cpp
