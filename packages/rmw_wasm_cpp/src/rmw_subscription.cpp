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

#include <memory>
#include <string>

#include "rcutils/strdup.h"
#include "rmw/allocators.h"
#include "rmw/error_handling.h"
#include "rmw/impl/cpp/macros.hpp"
#include "rmw/rmw.h"

#include "detail/api_helpers.hpp"
#include "detail/identifier.hpp"
#include "detail/qos.hpp"
#include "detail/rmw_node_data.hpp"
#include "detail/rmw_subscription_data.hpp"
#include "detail/scratch_buffer.hpp"
#include "detail/status.hpp"
#include "detail/type_support.hpp"

using rmw_wasm_cpp::kIdentifier;
using rmw_wasm_cpp::NodeData;
using rmw_wasm_cpp::ScratchBuffer;
using rmw_wasm_cpp::SubscriptionData;

namespace
{

ScratchBuffer & buffer_for(rmw_subscription_allocation_t * allocation)
{
  return allocation != nullptr ?
         rmw_wasm_cpp::buffer_of(allocation->implementation_identifier, allocation->data) :
         ScratchBuffer::for_this_thread();
}

}  // namespace

extern "C"
{

rmw_ret_t rmw_init_subscription_allocation(
  const rosidl_message_type_support_t * type_support,
  const rosidl_runtime_c__Sequence__bound * message_bounds,
  rmw_subscription_allocation_t * allocation)
{
  (void)message_bounds;  // Humble's bounds type carries no sizes; bounded types are sized.
  RMW_CHECK_ARGUMENT_FOR_NULL(type_support, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(allocation, RMW_RET_INVALID_ARGUMENT);
  return rmw_wasm_cpp::init_allocation(
    type_support, &allocation->implementation_identifier, &allocation->data);
}

rmw_ret_t rmw_fini_subscription_allocation(rmw_subscription_allocation_t * allocation)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(allocation, RMW_RET_INVALID_ARGUMENT);
  return rmw_wasm_cpp::fini_allocation(&allocation->implementation_identifier, &allocation->data);
}

rmw_subscription_t * rmw_create_subscription(
  const rmw_node_t * node,
  const rosidl_message_type_support_t * type_support,
  const char * topic_name,
  const rmw_qos_profile_t * qos_policies,
  const rmw_subscription_options_t * subscription_options)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, nullptr);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier, return nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(type_support, nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(topic_name, nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(qos_policies, nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription_options, nullptr);
  if (!rmw_wasm_cpp::check_topic_name(topic_name, *qos_policies)) {
    return nullptr;
  }
  if (!rmw_wasm_cpp::check_network_flow_requirement(
      subscription_options->require_unique_network_flow_endpoints, "subscription", topic_name))
  {
    return nullptr;
  }
  std::string error;
  if (!rmw_wasm_cpp::is_valid_qos(*qos_policies, &error)) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING("subscription on '%s': %s", topic_name, error.c_str());
    return nullptr;
  }
  auto ts = rmw_wasm_cpp::MessageTypeSupport::make(type_support, &error);
  if (ts == nullptr) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING("subscription on '%s': %s", topic_name, error.c_str());
    return nullptr;
  }
  auto node_data = static_cast<NodeData *>(node->data);
  auto data = SubscriptionData::make(
    node_data->node(), ts, topic_name, *qos_policies, *subscription_options);
  if (data == nullptr) {
    return nullptr;
  }
  rmw_subscription_t * subscription = rmw_subscription_allocate();
  char * topic_copy = rcutils_strdup(topic_name, rcutils_get_default_allocator());
  if (subscription == nullptr || topic_copy == nullptr) {
    RMW_SET_ERROR_MSG("cannot allocate an rmw subscription");
    rmw_subscription_free(subscription);
    rcutils_get_default_allocator().deallocate(topic_copy, nullptr);
    data->shutdown();
    return nullptr;
  }
  subscription->implementation_identifier = kIdentifier;
  subscription->data = data.get();
  subscription->topic_name = topic_copy;
  subscription->options = *subscription_options;
  // Content filters are not implemented (rmw_subscription_set_content_filter says why).
  subscription->options.content_filter_options = nullptr;
  subscription->can_loan_messages = false;
  subscription->is_cft_enabled = false;
  node_data->add_subscription(subscription, data);
  return subscription;
}

rmw_ret_t rmw_destroy_subscription(rmw_node_t * node, rmw_subscription_t * subscription)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  static_cast<NodeData *>(node->data)->remove_subscription(subscription);
  rcutils_get_default_allocator().deallocate(
    const_cast<char *>(subscription->topic_name), nullptr);
  rmw_subscription_free(subscription);
  return RMW_RET_OK;
}

rmw_ret_t rmw_subscription_count_matched_publishers(
  const rmw_subscription_t * subscription, size_t * publisher_count)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher_count, RMW_RET_INVALID_ARGUMENT);
  *publisher_count =
    static_cast<SubscriptionData *>(subscription->data)->subscription().matched_publisher_count();
  return RMW_RET_OK;
}

rmw_ret_t rmw_subscription_get_actual_qos(
  const rmw_subscription_t * subscription, rmw_qos_profile_t * qos)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(qos, RMW_RET_INVALID_ARGUMENT);
  *qos = rmw_wasm_cpp::to_rmw_qos(
    static_cast<SubscriptionData *>(subscription->data)->subscription().actual_qos());
  return RMW_RET_OK;
}

rmw_ret_t rmw_take(
  const rmw_subscription_t * subscription, void * ros_message, bool * taken,
  rmw_subscription_allocation_t * allocation)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(ros_message, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(taken, RMW_RET_INVALID_ARGUMENT);
  return static_cast<SubscriptionData *>(subscription->data)->take(
    ros_message, taken, nullptr, buffer_for(allocation));
}

rmw_ret_t rmw_take_with_info(
  const rmw_subscription_t * subscription, void * ros_message, bool * taken,
  rmw_message_info_t * message_info, rmw_subscription_allocation_t * allocation)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(ros_message, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(taken, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(message_info, RMW_RET_INVALID_ARGUMENT);
  return static_cast<SubscriptionData *>(subscription->data)->take(
    ros_message, taken, message_info, buffer_for(allocation));
}

rmw_ret_t rmw_take_sequence(
  const rmw_subscription_t * subscription, size_t count,
  rmw_message_sequence_t * message_sequence,
  rmw_message_info_sequence_t * message_info_sequence,
  size_t * taken, rmw_subscription_allocation_t * allocation)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(message_sequence, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(message_info_sequence, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(taken, RMW_RET_INVALID_ARGUMENT);
  if (count == 0) {
    RMW_SET_ERROR_MSG("rmw_take_sequence: count must be greater than 0");
    return RMW_RET_INVALID_ARGUMENT;
  }
  if (count > message_sequence->capacity || count > message_info_sequence->capacity) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "rmw_take_sequence: count %zu exceeds the sequence capacity (%zu messages, %zu infos)",
      count, message_sequence->capacity, message_info_sequence->capacity);
    return RMW_RET_INVALID_ARGUMENT;
  }
  auto data = static_cast<SubscriptionData *>(subscription->data);
  ScratchBuffer & buffer = buffer_for(allocation);
  *taken = 0;
  rmw_ret_t ret = RMW_RET_OK;
  while (*taken < count) {
    bool one = false;
    ret = data->take(
      message_sequence->data[*taken], &one, &message_info_sequence->data[*taken], buffer);
    if (ret != RMW_RET_OK || !one) {
      break;
    }
    ++*taken;
  }
  message_sequence->size = *taken;
  message_info_sequence->size = *taken;
  return ret;
}

rmw_ret_t rmw_take_serialized_message(
  const rmw_subscription_t * subscription, rmw_serialized_message_t * serialized_message,
  bool * taken, rmw_subscription_allocation_t * allocation)
{
  (void)allocation;  // the bytes go straight into serialized_message
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(serialized_message, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(taken, RMW_RET_INVALID_ARGUMENT);
  return static_cast<SubscriptionData *>(subscription->data)->take_serialized(
    serialized_message, taken, nullptr);
}

rmw_ret_t rmw_take_serialized_message_with_info(
  const rmw_subscription_t * subscription, rmw_serialized_message_t * serialized_message,
  bool * taken, rmw_message_info_t * message_info, rmw_subscription_allocation_t * allocation)
{
  (void)allocation;  // the bytes go straight into serialized_message
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(serialized_message, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(taken, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(message_info, RMW_RET_INVALID_ARGUMENT);
  return static_cast<SubscriptionData *>(subscription->data)->take_serialized(
    serialized_message, taken, message_info);
}

rmw_ret_t rmw_subscription_set_on_new_message_callback(
  rmw_subscription_t * subscription, rmw_event_callback_t callback, const void * user_data)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    subscription, subscription->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  return rmw_wasm_cpp::to_rmw_ret(
    static_cast<SubscriptionData *>(subscription->data)->subscription()
    .set_on_new_message_callback(callback, user_data));
}

}  // extern "C"
