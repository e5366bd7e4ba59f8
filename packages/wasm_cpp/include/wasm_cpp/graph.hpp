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

#ifndef WASM_CPP__GRAPH_HPP_
#define WASM_CPP__GRAPH_HPP_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "wasm_cpp/context.hpp"
#include "wasm_cpp/qos.hpp"
#include "wasm_cpp/status.hpp"
#include "wasm_cpp/types.hpp"

namespace wasm_cpp
{

/// A node as graph queries report it.
struct NodeInfo
{
  std::string name;
  std::string namespace_;
  std::string enclave;
  Gid gid;
};

/// The kinds of endpoints.
enum class EndpointKind : int32_t
{
  kPublisher = 1,
  kSubscription = 2,
  kService = 3,
  kClient = 4,
};

/// An endpoint as graph queries report it (rmw_topic_endpoint_info_t plus the name).
struct EndpointInfo
{
  EndpointKind kind = EndpointKind::kPublisher;
  /// Topic or service name.
  std::string name;
  std::string type_name;
  std::string node_name;
  std::string node_namespace;
  Gid gid;
  /// The endpoint's actual QoS.
  QoS qos;
};

/// A name with every type it is used with (rmw_names_and_types_t entry).
struct NameAndTypes
{
  std::string name;
  /// Sorted, without duplicates.
  std::vector<std::string> types;
};

/// Read-only queries of the bus graph, limited to the context's domain.
/**
 * Every query reads a consistent snapshot of the registry. Results are
 * sorted by name. Topic queries list publishers and subscriptions only;
 * service queries list servers and clients only.
 */
namespace graph
{

/// Every live node (rmw_get_node_names_with_enclaves).
Status get_nodes(const Context & context, std::vector<NodeInfo> * nodes);

/// Topics with at least one publisher or subscription, with their types.
Status get_topic_names_and_types(const Context & context, std::vector<NameAndTypes> * topics);

/// Services with at least one server or client, with their types.
Status get_service_names_and_types(
  const Context & context, std::vector<NameAndTypes> * services);

/// The endpoints of one kind on one topic or service name.
Status get_endpoints(
  const Context & context, const std::string & name, EndpointKind kind,
  std::vector<EndpointInfo> * endpoints);

/// How many endpoints of one kind use `name` (rmw_count_publishers / rmw_count_subscribers).
Status count_endpoints(
  const Context & context, const std::string & name, EndpointKind kind, size_t * count);

/// Names and types of one kind of endpoint of one node.
/**
 * \return kNodeNameNonExistent when no live node has this name and namespace
 *   (what rmw_get_*_names_and_types_by_node must report).
 */
Status get_names_and_types_by_node(
  const Context & context, const std::string & node_name, const std::string & node_namespace,
  EndpointKind kind, std::vector<NameAndTypes> * names_and_types);

/// The graph version: a counter bumped by every change of the bus graph.
uint32_t version();

}  // namespace graph

}  // namespace wasm_cpp

#endif  // WASM_CPP__GRAPH_HPP_
