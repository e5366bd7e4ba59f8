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

#include <cstring>
#include <memory>
#include <string>

#include "rcutils/strdup.h"
#include "rmw/allocators.h"
#include "rmw/error_handling.h"
#include "rmw/impl/cpp/macros.hpp"
#include "rmw/rmw.h"
#include "rmw/time.h"

#include "detail/api_helpers.hpp"
#include "detail/identifier.hpp"
#include "detail/qos.hpp"
#include "detail/rmw_node_data.hpp"
#include "detail/rmw_publisher_data.hpp"
#include "detail/scratch_buffer.hpp"
#include "detail/status.hpp"
#include "detail/type_support.hpp"

using rmw_wasm_cpp::kIdentifier;
using rmw_wasm_cpp::NodeData;
using rmw_wasm_cpp::PublisherData;
using rmw_wasm_cpp::ScratchBuffer;

extern "C"
{

rmw_ret_t rmw_init_publisher_allocation(
  const rosidl_message_type_support_t * type_support,
  const rosidl_runtime_c__Sequence__bound * message_bounds,
  rmw_publisher_allocation_t * allocation)
{
  (void)message_bounds;  // Humble's bounds type carries no sizes; bounded types are sized.
  RMW_CHECK_ARGUMENT_FOR_NULL(type_support, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(allocation, RMW_RET_INVALID_ARGUMENT);
  return rmw_wasm_cpp::init_allocation(
    type_support, &allocation->implementation_identifier, &allocation->data);
}

rmw_ret_t rmw_fini_publisher_allocation(rmw_publisher_allocation_t * allocation)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(allocation, RMW_RET_INVALID_ARGUMENT);
  return rmw_wasm_cpp::fini_allocation(&allocation->implementation_identifier, &allocation->data);
}

rmw_publisher_t * rmw_create_publisher(
  const rmw_node_t * node,
  const rosidl_message_type_support_t * type_support,
  const char * topic_name,
  const rmw_qos_profile_t * qos_profile,
  const rmw_publisher_options_t * publisher_options)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, nullptr);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier, return nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(type_support, nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(topic_name, nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(qos_profile, nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher_options, nullptr);
  if (!rmw_wasm_cpp::check_topic_name(topic_name, *qos_profile)) {
    return nullptr;
  }
  if (!rmw_wasm_cpp::check_network_flow_requirement(
      publisher_options->require_unique_network_flow_endpoints, "publisher", topic_name))
  {
    return nullptr;
  }
  std::string error;
  if (!rmw_wasm_cpp::is_valid_qos(*qos_profile, &error)) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING("publisher on '%s': %s", topic_name, error.c_str());
    return nullptr;
  }
  auto ts = rmw_wasm_cpp::MessageTypeSupport::make(type_support, &error);
  if (ts == nullptr) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING("publisher on '%s': %s", topic_name, error.c_str());
    return nullptr;
  }
  auto node_data = static_cast<NodeData *>(node->data);
  auto data = PublisherData::make(node_data->node(), ts, topic_name, *qos_profile);
  if (data == nullptr) {
    return nullptr;
  }
  rmw_publisher_t * publisher = rmw_publisher_allocate();
  char * topic_copy = rcutils_strdup(topic_name, rcutils_get_default_allocator());
  if (publisher == nullptr || topic_copy == nullptr) {
    RMW_SET_ERROR_MSG("cannot allocate an rmw publisher");
    rmw_publisher_free(publisher);
    rcutils_get_default_allocator().deallocate(topic_copy, nullptr);
    data->shutdown();
    return nullptr;
  }
  publisher->implementation_identifier = kIdentifier;
  publisher->data = data.get();
  publisher->topic_name = topic_copy;
  publisher->options = *publisher_options;
  publisher->can_loan_messages = false;
  node_data->add_publisher(publisher, data);
  return publisher;
}

rmw_ret_t rmw_destroy_publisher(rmw_node_t * node, rmw_publisher_t * publisher)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  static_cast<NodeData *>(node->data)->remove_publisher(publisher);
  rcutils_get_default_allocator().deallocate(const_cast<char *>(publisher->topic_name), nullptr);
  rmw_publisher_free(publisher);
  return RMW_RET_OK;
}

rmw_ret_t rmw_publish(
  const rmw_publisher_t * publisher, const void * ros_message,
  rmw_publisher_allocation_t * allocation)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(ros_message, RMW_RET_INVALID_ARGUMENT);
  ScratchBuffer & buffer = allocation != nullptr ?
    rmw_wasm_cpp::buffer_of(allocation->implementation_identifier, allocation->data) :
    ScratchBuffer::for_this_thread();
  return static_cast<PublisherData *>(publisher->data)->publish(ros_message, buffer);
}

rmw_ret_t rmw_publish_serialized_message(
  const rmw_publisher_t * publisher,
  const rmw_serialized_message_t * serialized_message,
  rmw_publisher_allocation_t * allocation)
{
  (void)allocation;  // the bytes are already serialized: nothing to allocate
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(serialized_message, RMW_RET_INVALID_ARGUMENT);
  return static_cast<PublisherData *>(publisher->data)->publish_serialized(*serialized_message);
}

rmw_ret_t rmw_publisher_count_matched_subscriptions(
  const rmw_publisher_t * publisher, size_t * subscription_count)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(subscription_count, RMW_RET_INVALID_ARGUMENT);
  *subscription_count =
    static_cast<PublisherData *>(publisher->data)->publisher().matched_subscription_count();
  return RMW_RET_OK;
}

rmw_ret_t rmw_publisher_get_actual_qos(const rmw_publisher_t * publisher, rmw_qos_profile_t * qos)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(qos, RMW_RET_INVALID_ARGUMENT);
  *qos = rmw_wasm_cpp::to_rmw_qos(
    static_cast<PublisherData *>(publisher->data)->publisher().actual_qos());
  return RMW_RET_OK;
}

rmw_ret_t rmw_publisher_assert_liveliness(const rmw_publisher_t * publisher)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  return rmw_wasm_cpp::to_rmw_ret(
    static_cast<PublisherData *>(publisher->data)->publisher().assert_liveliness());
}

rmw_ret_t rmw_publisher_wait_for_all_acked(
  const rmw_publisher_t * publisher, rmw_time_t wait_timeout)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  const rmw_duration_t ns = rmw_time_total_nsec(wait_timeout);
  const wasm_cpp::Timeout timeout = ns >= INT64_MAX ? wasm_cpp::kForever : wasm_cpp::Timeout(ns);
  return rmw_wasm_cpp::to_rmw_ret(
    static_cast<PublisherData *>(publisher->data)->publisher().wait_for_all_acked(timeout));
}

rmw_ret_t rmw_get_gid_for_publisher(const rmw_publisher_t * publisher, rmw_gid_t * gid)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(publisher, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    publisher, publisher->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(gid, RMW_RET_INVALID_ARGUMENT);
  const wasm_cpp::Gid & core = static_cast<PublisherData *>(publisher->data)->publisher().gid();
  gid->implementation_identifier = kIdentifier;
  std::memset(gid->data, 0, sizeof(gid->data));
  static_assert(wasm_cpp::kGidSize <= RMW_GID_STORAGE_SIZE, "a gid fits rmw_gid_t");
  std::memcpy(gid->data, core.data.data(), wasm_cpp::kGidSize);
  return RMW_RET_OK;
}

rmw_ret_t rmw_compare_gids_equal(const rmw_gid_t * gid1, const rmw_gid_t * gid2, bool * result)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(gid1, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    gid1, gid1->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(gid2, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    gid2, gid2->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(result, RMW_RET_INVALID_ARGUMENT);
  *result = std::memcmp(gid1->data, gid2->data, RMW_GID_STORAGE_SIZE) == 0;
  return RMW_RET_OK;
}

}  // extern "C"
