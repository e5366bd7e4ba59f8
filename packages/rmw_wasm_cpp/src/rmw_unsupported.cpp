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

/// \file
/// The only rmw functions rmw_wasm_cpp does not implement, each with the reason in its error:
///
/// - message loans: a loaned message lives in middleware memory the user writes into. The
///   bus shares memory between workers as one SharedArrayBuffer, but a node's C++ code can
///   only address its own wasm heap, so there is nothing to lend: a publish copies the
///   serialized bytes into the bus once, and a take copies them out once.
///   (rmw_publisher_t::can_loan_messages is false, so rclcpp never asks.)
/// - network flow endpoints: nodes talk through shared memory, there are no sockets,
///   ports or addresses to report.
/// - content filters: the core delivers every message of a topic to every matched
///   subscription; rclcpp falls back to no filtering (is_cft_enabled is false).

#include "rmw/error_handling.h"
#include "rmw/get_network_flow_endpoints.h"
#include "rmw/impl/cpp/macros.hpp"
#include "rmw/rmw.h"

#include "detail/identifier.hpp"

using rmw_wasm_cpp::kIdentifier;

namespace
{

constexpr const char kNoLoans[] =
  "rmw_wasm_cpp does not loan messages: node code can only address its own wasm heap, so "
  "messages are copied once into the shared bus instead (can_loan_messages is false)";
constexpr const char kNoNetworkFlows[] =
  "rmw_wasm_cpp has no network flow endpoints: nodes exchange messages through shared "
  "memory, with no sockets, ports or addresses";
constexpr const char kNoContentFilter[] =
  "rmw_wasm_cpp does not filter content: every matched subscription receives every message "
  "of its topic (filter in the callback instead)";

}  // namespace

extern "C"
{

rmw_ret_t rmw_borrow_loaned_message(
  const rmw_publisher_t * publisher, const rosidl_message_type_support_t * type_support,
  void ** ros_message)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  (void)type_support;
  (void)ros_message;
  RMW_SET_ERROR_MSG(kNoLoans);
  return RMW_RET_UNSUPPORTED;
}

rmw_ret_t rmw_return_loaned_message_from_publisher(
  const rmw_publisher_t * publisher, void * loaned_message)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  (void)loaned_message;
  RMW_SET_ERROR_MSG(kNoLoans);
  return RMW_RET_UNSUPPORTED;
}

rmw_ret_t rmw_publish_loaned_message(
  const rmw_publisher_t * publisher, void * ros_message, rmw_publisher_allocation_t * allocation)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  (void)ros_message;
  (void)allocation;
  RMW_SET_ERROR_MSG(kNoLoans);
  return RMW_RET_UNSUPPORTED;
}

rmw_ret_t rmw_take_loaned_message(
  const rmw_subscription_t * subscription, void ** loaned_message, bool * taken,
  rmw_subscription_allocation_t * allocation)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  (void)loaned_message;
  (void)taken;
  (void)allocation;
  RMW_SET_ERROR_MSG(kNoLoans);
  return RMW_RET_UNSUPPORTED;
}

rmw_ret_t rmw_take_loaned_message_with_info(
  const rmw_subscription_t * subscription, void ** loaned_message, bool * taken,
  rmw_message_info_t * message_info, rmw_subscription_allocation_t * allocation)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  (void)loaned_message;
  (void)taken;
  (void)message_info;
  (void)allocation;
  RMW_SET_ERROR_MSG(kNoLoans);
  return RMW_RET_UNSUPPORTED;
}

rmw_ret_t rmw_return_loaned_message_from_subscription(
  const rmw_subscription_t * subscription, void * loaned_message)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  (void)loaned_message;
  RMW_SET_ERROR_MSG(kNoLoans);
  return RMW_RET_UNSUPPORTED;
}

rmw_ret_t rmw_publisher_get_network_flow_endpoints(
  const rmw_publisher_t * publisher, rcutils_allocator_t * allocator,
  rmw_network_flow_endpoint_array_t * network_flow_endpoint_array)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  // Leave a valid empty array, so that the caller's cleanup (rcl finalizes it) succeeds.
  if (network_flow_endpoint_array != nullptr && network_flow_endpoint_array->size == 0) {
    network_flow_endpoint_array->allocator = allocator;
  }
  RMW_SET_ERROR_MSG(kNoNetworkFlows);
  return RMW_RET_UNSUPPORTED;
}

rmw_ret_t rmw_subscription_get_network_flow_endpoints(
  const rmw_subscription_t * subscription, rcutils_allocator_t * allocator,
  rmw_network_flow_endpoint_array_t * network_flow_endpoint_array)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  // Leave a valid empty array, so that the caller's cleanup (rcl finalizes it) succeeds.
  if (network_flow_endpoint_array != nullptr && network_flow_endpoint_array->size == 0) {
    network_flow_endpoint_array->allocator = allocator;
  }
  RMW_SET_ERROR_MSG(kNoNetworkFlows);
  return RMW_RET_UNSUPPORTED;
}

rmw_ret_t rmw_subscription_set_content_filter(
  rmw_subscription_t * subscription, const rmw_subscription_content_filter_options_t * options)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  (void)options;
  RMW_SET_ERROR_MSG(kNoContentFilter);
  return RMW_RET_UNSUPPORTED;
}

rmw_ret_t rmw_subscription_get_content_filter(
  const rmw_subscription_t * subscription, rcutils_allocator_t * allocator,
  rmw_subscription_content_filter_options_t * options)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  (void)allocator;
  (void)options;
  RMW_SET_ERROR_MSG(kNoContentFilter);
  return RMW_RET_UNSUPPORTED;
}

}  // extern "C"
