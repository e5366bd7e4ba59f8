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

#ifndef DETAIL__RMW_NODE_DATA_HPP_
#define DETAIL__RMW_NODE_DATA_HPP_

#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>

#include "rmw/types.h"
#include "wasm_cpp/context.hpp"
#include "wasm_cpp/guard_condition.hpp"
#include "wasm_cpp/node.hpp"

#include "detail/rmw_guard_condition_data.hpp"

namespace rmw_wasm_cpp
{

class ClientData;
class PublisherData;
class ServiceData;
class SubscriptionData;

/// The data behind an rmw_node_t: the core node, its graph guard condition and its entities.
class NodeData final
{
public:
  /// Create the node on the bus; on failure returns null with the rmw error set.
  /**
   * When another live node of the domain already has this fully qualified
   * name, a warning is logged (as ROS tools warn), and the node is created.
   */
  static std::shared_ptr<NodeData> make(
    const std::shared_ptr<wasm_cpp::Context> & context,
    const char * name, const char * namespace_);

  /// The core node.
  const std::shared_ptr<wasm_cpp::Node> & node() const {return node_;}

  /// The guard condition triggered by every graph change, as an rmw handle owned by the node.
  const rmw_guard_condition_t * graph_guard_condition() const {return &graph_guard_handle_;}

  /// Keep `publisher` alive until remove_publisher(handle).
  void add_publisher(const rmw_publisher_t * handle, std::shared_ptr<PublisherData> publisher);
  /// Forget a publisher (shutting it down).
  void remove_publisher(const rmw_publisher_t * handle);

  /// Keep `subscription` alive until remove_subscription(handle).
  void add_subscription(
    const rmw_subscription_t * handle, std::shared_ptr<SubscriptionData> subscription);
  /// Forget a subscription (shutting it down).
  void remove_subscription(const rmw_subscription_t * handle);

  /// Keep `service` alive until remove_service(handle).
  void add_service(const rmw_service_t * handle, std::shared_ptr<ServiceData> service);
  /// Forget a service server (shutting it down).
  void remove_service(const rmw_service_t * handle);

  /// Keep `client` alive until remove_client(handle).
  void add_client(const rmw_client_t * handle, std::shared_ptr<ClientData> client);
  /// Forget a client (shutting it down).
  void remove_client(const rmw_client_t * handle);

  /// Remove the node and every entity of it from the graph. Idempotent.
  void shutdown();

  ~NodeData();

private:
  NodeData(
    std::shared_ptr<wasm_cpp::Node> node, std::shared_ptr<wasm_cpp::GuardCondition> graph_guard);

  // Protects the entity maps.
  mutable std::mutex mutex_;
  // The core node.
  std::shared_ptr<wasm_cpp::Node> node_;
  // Triggered by graph changes.
  std::unique_ptr<GuardConditionData> graph_guard_;
  // rmw handle of graph_guard_ (its data points at graph_guard_).
  rmw_guard_condition_t graph_guard_handle_;
  // Entities by their rmw handle.
  std::unordered_map<const rmw_publisher_t *, std::shared_ptr<PublisherData>> publishers_;
  std::unordered_map<const rmw_subscription_t *, std::shared_ptr<SubscriptionData>>
  subscriptions_;
  std::unordered_map<const rmw_service_t *, std::shared_ptr<ServiceData>> services_;
  std::unordered_map<const rmw_client_t *, std::shared_ptr<ClientData>> clients_;
};

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__RMW_NODE_DATA_HPP_
