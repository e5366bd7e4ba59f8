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

#include <string>
#include <vector>

#include "rcutils/allocator.h"
#include "rmw/error_handling.h"
#include "rmw/get_node_info_and_types.h"
#include "rmw/get_service_names_and_types.h"
#include "rmw/get_topic_endpoint_info.h"
#include "rmw/get_topic_names_and_types.h"
#include "rmw/impl/cpp/macros.hpp"
#include "rmw/names_and_types.h"
#include "rmw/rmw.h"
#include "rmw/sanity_checks.h"
#include "rmw/topic_endpoint_info_array.h"
#include "rmw/validate_full_topic_name.h"
#include "rmw/validate_namespace.h"
#include "rmw/validate_node_name.h"

#include "detail/graph.hpp"
#include "detail/identifier.hpp"
#include "detail/rmw_node_data.hpp"
#include "detail/status.hpp"

using rmw_wasm_cpp::kIdentifier;
using rmw_wasm_cpp::NodeData;
using wasm_cpp::EndpointKind;

namespace
{

const wasm_cpp::Context & context_of(const rmw_node_t * node)
{
  return *static_cast<NodeData *>(node->data)->node()->context();
}

// The checks every names-and-types query shares.
rmw_ret_t check_names_and_types_query(
  const rmw_node_t * node, rcutils_allocator_t * allocator, rmw_names_and_types_t * out)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RCUTILS_CHECK_ALLOCATOR_WITH_MSG(
    allocator, "allocator argument is invalid", return RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(out, RMW_RET_INVALID_ARGUMENT);
  return rmw_names_and_types_check_zero(out);
}

// The checks of the *_by_node queries: also a valid node name and namespace.
rmw_ret_t check_by_node_query(
  const rmw_node_t * node, rcutils_allocator_t * allocator, const char * node_name,
  const char * node_namespace, rmw_names_and_types_t * out)
{
  rmw_ret_t ret = check_names_and_types_query(node, allocator, out);
  if (ret != RMW_RET_OK) {
    return ret;
  }
  RMW_CHECK_ARGUMENT_FOR_NULL(node_name, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(node_namespace, RMW_RET_INVALID_ARGUMENT);
  int validation_result = RMW_NODE_NAME_VALID;
  ret = rmw_validate_node_name(node_name, &validation_result, nullptr);
  if (ret != RMW_RET_OK) {
    return ret;
  }
  if (validation_result != RMW_NODE_NAME_VALID) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "invalid node name '%s': %s", node_name,
      rmw_node_name_validation_result_string(validation_result));
    return RMW_RET_INVALID_ARGUMENT;
  }
  validation_result = RMW_NAMESPACE_VALID;
  ret = rmw_validate_namespace(node_namespace, &validation_result, nullptr);
  if (ret != RMW_RET_OK) {
    return ret;
  }
  if (validation_result != RMW_NAMESPACE_VALID) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "invalid node namespace '%s': %s", node_namespace,
      rmw_namespace_validation_result_string(validation_result));
    return RMW_RET_INVALID_ARGUMENT;
  }
  return RMW_RET_OK;
}

rmw_ret_t names_and_types_by_node(
  const rmw_node_t * node, rcutils_allocator_t * allocator, const char * node_name,
  const char * node_namespace, EndpointKind kind, rmw_names_and_types_t * out)
{
  rmw_ret_t ret = check_by_node_query(node, allocator, node_name, node_namespace, out);
  if (ret != RMW_RET_OK) {
    return ret;
  }
  std::vector<wasm_cpp::NameAndTypes> result;
  ret = rmw_wasm_cpp::to_rmw_ret(
    wasm_cpp::graph::get_names_and_types_by_node(
      context_of(node), node_name, node_namespace, kind, &result));
  if (ret != RMW_RET_OK) {
    return ret;
  }
  return rmw_wasm_cpp::to_rmw_names_and_types(result, allocator, out);
}

rmw_ret_t endpoints_info(
  const rmw_node_t * node, rcutils_allocator_t * allocator, const char * topic_name,
  EndpointKind kind, rmw_topic_endpoint_info_array_t * out)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RCUTILS_CHECK_ALLOCATOR_WITH_MSG(
    allocator, "allocator argument is invalid", return RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(topic_name, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(out, RMW_RET_INVALID_ARGUMENT);
  if (rmw_topic_endpoint_info_array_check_zero(out) != RMW_RET_OK) {
    // rmw_get_*_info_by_topic: an array that is not zero initialized is an
    // invalid argument (rmw's check says RMW_RET_ERROR; its message is kept)
    return RMW_RET_INVALID_ARGUMENT;
  }
  std::vector<wasm_cpp::EndpointInfo> endpoints;
  rmw_ret_t ret = rmw_wasm_cpp::to_rmw_ret(
    wasm_cpp::graph::get_endpoints(context_of(node), topic_name, kind, &endpoints));
  if (ret != RMW_RET_OK) {
    return ret;
  }
  return rmw_wasm_cpp::to_rmw_endpoint_info_array(endpoints, allocator, out);
}

rmw_ret_t count_endpoints(
  const rmw_node_t * node, const char * topic_name, EndpointKind kind, size_t * count)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(topic_name, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(count, RMW_RET_INVALID_ARGUMENT);
  int validation_result = RMW_TOPIC_VALID;
  rmw_ret_t ret = rmw_validate_full_topic_name(topic_name, &validation_result, nullptr);
  if (ret != RMW_RET_OK) {
    return ret;
  }
  if (validation_result != RMW_TOPIC_VALID) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "invalid topic name '%s': %s", topic_name,
      rmw_full_topic_name_validation_result_string(validation_result));
    return RMW_RET_INVALID_ARGUMENT;
  }
  return rmw_wasm_cpp::to_rmw_ret(
    wasm_cpp::graph::count_endpoints(context_of(node), topic_name, kind, count));
}

rmw_ret_t get_node_names(
  const rmw_node_t * node, rcutils_string_array_t * node_names,
  rcutils_string_array_t * node_namespaces, rcutils_string_array_t * enclaves)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(node_names, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(node_namespaces, RMW_RET_INVALID_ARGUMENT);
  if (rmw_check_zero_rmw_string_array(node_names) != RMW_RET_OK ||
    rmw_check_zero_rmw_string_array(node_namespaces) != RMW_RET_OK ||
    (enclaves != nullptr && rmw_check_zero_rmw_string_array(enclaves) != RMW_RET_OK))
  {
    return RMW_RET_INVALID_ARGUMENT;
  }
  std::vector<wasm_cpp::NodeInfo> nodes;
  rmw_ret_t ret = rmw_wasm_cpp::to_rmw_ret(wasm_cpp::graph::get_nodes(context_of(node), &nodes));
  if (ret != RMW_RET_OK) {
    return ret;
  }
  std::vector<std::string> names, namespaces, enclave_names;
  for (const auto & info : nodes) {
    names.push_back(info.name);
    namespaces.push_back(info.namespace_);
    enclave_names.push_back(info.enclave);
  }
  rcutils_allocator_t allocator = rcutils_get_default_allocator();
  ret = rmw_wasm_cpp::to_rcutils_string_array(names, &allocator, node_names);
  if (ret == RMW_RET_OK) {
    ret = rmw_wasm_cpp::to_rcutils_string_array(namespaces, &allocator, node_namespaces);
  }
  if (ret == RMW_RET_OK && enclaves != nullptr) {
    ret = rmw_wasm_cpp::to_rcutils_string_array(enclave_names, &allocator, enclaves);
  }
  if (ret != RMW_RET_OK) {
    if (rcutils_string_array_fini(node_names) != RCUTILS_RET_OK ||
      rcutils_string_array_fini(node_namespaces) != RCUTILS_RET_OK)
    {
      rcutils_reset_error();
    }
  }
  return ret;
}

}  // namespace

extern "C"
{

rmw_ret_t rmw_get_node_names(
  const rmw_node_t * node, rcutils_string_array_t * node_names,
  rcutils_string_array_t * node_namespaces)
{
  return get_node_names(node, node_names, node_namespaces, nullptr);
}

rmw_ret_t rmw_get_node_names_with_enclaves(
  const rmw_node_t * node, rcutils_string_array_t * node_names,
  rcutils_string_array_t * node_namespaces, rcutils_string_array_t * enclaves)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(enclaves, RMW_RET_INVALID_ARGUMENT);
  return get_node_names(node, node_names, node_namespaces, enclaves);
}

rmw_ret_t rmw_get_topic_names_and_types(
  const rmw_node_t * node, rcutils_allocator_t * allocator, bool no_demangle,
  rmw_names_and_types_t * topic_names_and_types)
{
  // Topic and type names on the bus are ROS names already: there is nothing to demangle.
  (void)no_demangle;
  rmw_ret_t ret = check_names_and_types_query(node, allocator, topic_names_and_types);
  if (ret != RMW_RET_OK) {
    return ret;
  }
  std::vector<wasm_cpp::NameAndTypes> topics;
  ret = rmw_wasm_cpp::to_rmw_ret(
    wasm_cpp::graph::get_topic_names_and_types(context_of(node), &topics));
  if (ret != RMW_RET_OK) {
    return ret;
  }
  return rmw_wasm_cpp::to_rmw_names_and_types(topics, allocator, topic_names_and_types);
}

rmw_ret_t rmw_get_service_names_and_types(
  const rmw_node_t * node, rcutils_allocator_t * allocator,
  rmw_names_and_types_t * service_names_and_types)
{
  rmw_ret_t ret = check_names_and_types_query(node, allocator, service_names_and_types);
  if (ret != RMW_RET_OK) {
    return ret;
  }
  std::vector<wasm_cpp::NameAndTypes> services;
  ret = rmw_wasm_cpp::to_rmw_ret(
    wasm_cpp::graph::get_service_names_and_types(context_of(node), &services));
  if (ret != RMW_RET_OK) {
    return ret;
  }
  return rmw_wasm_cpp::to_rmw_names_and_types(services, allocator, service_names_and_types);
}

rmw_ret_t rmw_get_subscriber_names_and_types_by_node(
  const rmw_node_t * node, rcutils_allocator_t * allocator, const char * node_name,
  const char * node_namespace, bool no_demangle, rmw_names_and_types_t * topic_names_and_types)
{
  (void)no_demangle;
  return names_and_types_by_node(
    node, allocator, node_name, node_namespace, EndpointKind::kSubscription,
    topic_names_and_types);
}

rmw_ret_t rmw_get_publisher_names_and_types_by_node(
  const rmw_node_t * node, rcutils_allocator_t * allocator, const char * node_name,
  const char * node_namespace, bool no_demangle, rmw_names_and_types_t * topic_names_and_types)
{
  (void)no_demangle;
  return names_and_types_by_node(
    node, allocator, node_name, node_namespace, EndpointKind::kPublisher,
    topic_names_and_types);
}

rmw_ret_t rmw_get_service_names_and_types_by_node(
  const rmw_node_t * node, rcutils_allocator_t * allocator, const char * node_name,
  const char * node_namespace, rmw_names_and_types_t * service_names_and_types)
{
  return names_and_types_by_node(
    node, allocator, node_name, node_namespace, EndpointKind::kService,
    service_names_and_types);
}

rmw_ret_t rmw_get_client_names_and_types_by_node(
  const rmw_node_t * node, rcutils_allocator_t * allocator, const char * node_name,
  const char * node_namespace, rmw_names_and_types_t * service_names_and_types)
{
  return names_and_types_by_node(
    node, allocator, node_name, node_namespace, EndpointKind::kClient,
    service_names_and_types);
}

rmw_ret_t rmw_get_publishers_info_by_topic(
  const rmw_node_t * node, rcutils_allocator_t * allocator, const char * topic_name,
  bool no_mangle, rmw_topic_endpoint_info_array_t * publishers_info)
{
  (void)no_mangle;
  return endpoints_info(node, allocator, topic_name, EndpointKind::kPublisher, publishers_info);
}

rmw_ret_t rmw_get_subscriptions_info_by_topic(
  const rmw_node_t * node, rcutils_allocator_t * allocator, const char * topic_name,
  bool no_mangle, rmw_topic_endpoint_info_array_t * subscriptions_info)
{
  (void)no_mangle;
  return endpoints_info(
    node, allocator, topic_name, EndpointKind::kSubscription, subscriptions_info);
}

rmw_ret_t rmw_count_publishers(const rmw_node_t * node, const char * topic_name, size_t * count)
{
  return count_endpoints(node, topic_name, EndpointKind::kPublisher, count);
}

rmw_ret_t rmw_count_subscribers(const rmw_node_t * node, const char * topic_name, size_t * count)
{
  return count_endpoints(node, topic_name, EndpointKind::kSubscription, count);
}

}  // extern "C"
