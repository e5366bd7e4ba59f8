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

#include "detail/rmw_subscription_data.hpp"

#include <cstring>
#include <memory>
#include <string>
#include <utility>

#include "rcutils/types/uint8_array.h"
#include "rmw/error_handling.h"

#include "detail/graph.hpp"
#include "detail/identifier.hpp"
#include "detail/qos.hpp"
#include "detail/status.hpp"

namespace rmw_wasm_cpp
{

void to_rmw_message_info(const wasm_cpp::MessageInfo & info, rmw_message_info_t * out)
{
  out->source_timestamp = info.source_timestamp;
  out->received_timestamp = info.received_timestamp;
  out->publication_sequence_number = info.publication_sequence_number;
  out->reception_sequence_number = info.reception_sequence_number;
  out->publisher_gid.implementation_identifier = kIdentifier;
  std::memset(out->publisher_gid.data, 0, sizeof(out->publisher_gid.data));
  std::memcpy(out->publisher_gid.data, info.publisher_gid.data.data(), wasm_cpp::kGidSize);
  // "intra process" means rclcpp's intra-process manager, which never uses the rmw.
  out->from_intra_process = false;
}

SubscriptionData::SubscriptionData(
  std::shared_ptr<wasm_cpp::Subscription> subscription,
  std::shared_ptr<MessageTypeSupport> type_support)
: subscription_(std::move(subscription)), type_support_(std::move(type_support))
{
}

std::shared_ptr<SubscriptionData> SubscriptionData::make(
  const std::shared_ptr<wasm_cpp::Node> & node,
  std::shared_ptr<MessageTypeSupport> type_support,
  const char * topic_name,
  const rmw_qos_profile_t & qos,
  const rmw_subscription_options_t & options)
{
  warn_if_topic_type_differs(
    *node->context(), topic_name, type_support->type_name(), "subscription");
  wasm_cpp::SubscriptionOptions core_options;
  core_options.ignore_local_publications = options.ignore_local_publications;
  auto subscription = wasm_cpp::Subscription::make(
    node, topic_name, type_support->type_name(), to_wasm_qos(qos), core_options);
  if (!subscription.ok()) {
    to_rmw_ret(subscription.status());
    return nullptr;
  }
  return std::shared_ptr<SubscriptionData>(
    new SubscriptionData(subscription.value(), std::move(type_support)));
}

rmw_ret_t SubscriptionData::take(
  void * ros_message, bool * taken, rmw_message_info_t * message_info, ScratchBuffer & buffer)
{
  *taken = false;
  uint8_t * data = nullptr;
  size_t size = 0;
  wasm_cpp::MessageInfo info;
  bool got = false;
  const rmw_ret_t ret = to_rmw_ret(
    subscription_->take(buffer.allocator(), &data, &size, &info, &got));
  if (ret != RMW_RET_OK || !got) {
    return ret;
  }
  std::string error;
  if (!type_support_->deserialize(data, size, ros_message, &error)) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "dropped a malformed message on '%s' (publication %llu): %s",
      subscription_->topic_name().c_str(),
      static_cast<unsigned long long>(info.publication_sequence_number), error.c_str());
    return RMW_RET_ERROR;
  }
  if (message_info != nullptr) {
    to_rmw_message_info(info, message_info);
  }
  *taken = true;
  return RMW_RET_OK;
}

rmw_ret_t SubscriptionData::take_serialized(
  rmw_serialized_message_t * message, bool * taken, rmw_message_info_t * message_info)
{
  *taken = false;
  // Copy the message from the bus straight into the caller's serialized message.
  struct Target
  {
    rmw_serialized_message_t * message;
    bool failed;
  } target{message, false};
  wasm_cpp::Allocator allocator;
  allocator.allocate = [](size_t size, void * state) -> void * {
      auto t = static_cast<Target *>(state);
      if (t->message->buffer_capacity < size &&
        rcutils_uint8_array_resize(t->message, size) != RCUTILS_RET_OK)
      {
        t->failed = true;
        return nullptr;
      }
      return t->message->buffer;
    };
  allocator.deallocate = [](void *, void *) {};
  allocator.state = &target;
  allocator.buffer = message->buffer;
  allocator.capacity = message->buffer_capacity;  // take() ignores it when there is no buffer
  uint8_t * data = nullptr;
  size_t size = 0;
  wasm_cpp::MessageInfo info;
  bool got = false;
  const rmw_ret_t ret = to_rmw_ret(subscription_->take(allocator, &data, &size, &info, &got));
  if (target.failed) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "cannot take from '%s': no memory for a serialized message of %zu bytes",
      subscription_->topic_name().c_str(), size);
    return RMW_RET_BAD_ALLOC;
  }
  if (ret != RMW_RET_OK || !got) {
    return ret;
  }
  message->buffer_length = size;
  if (message_info != nullptr) {
    to_rmw_message_info(info, message_info);
  }
  *taken = true;
  return RMW_RET_OK;
}

EventData * SubscriptionData::event(rmw_event_type_t type)
{
  return events_.get(subscription_, type, wasm_cpp::is_subscription_event, "subscription");
}

void SubscriptionData::shutdown()
{
  events_.clear();
  subscription_->shutdown();
}

}  // namespace rmw_wasm_cpp
