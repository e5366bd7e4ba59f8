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

#include "wasm_cpp/subscription.hpp"

#include <memory>
#include <string>
#include <utility>

#include "bus_abi.hpp"
#include "listener.hpp"

namespace wasm_cpp
{

Result<std::shared_ptr<Subscription>> Subscription::make(
  std::shared_ptr<Node> node, const std::string & topic_name, const std::string & type_name,
  const QoS & qos, const SubscriptionOptions & options)
{
  if (!node) {
    return Status(
      Code::kInvalidArgument, "cannot create subscription on '" + topic_name + "': null node");
  }
  detail::EndpointHandle h;
  Status s = detail::create_endpoint(
    detail::kBusSubscription, *node, topic_name, type_name, qos,
    options.ignore_local_publications ? 1 : 0, &h);
  if (!s.ok()) {
    return s;
  }
  return std::shared_ptr<Subscription>(
    new Subscription(std::move(node), topic_name, type_name, h.qos, options, h.handle, h.gid));
}

Subscription::Subscription(
  std::shared_ptr<Node> node, std::string topic_name, std::string type_name,
  const QoS & qos, const SubscriptionOptions & options, int32_t handle, const Gid & gid)
: node_(std::move(node)), topic_name_(std::move(topic_name)), type_name_(std::move(type_name)),
  qos_(qos), options_(options), handle_(handle), gid_(gid)
{
}

Subscription::~Subscription()
{
  shutdown();
}

Status Subscription::take(Message * message, MessageInfo * info, bool * taken)
{
  if (message == nullptr) {
    return Status(Code::kInvalidArgument, "take on '" + topic_name_ + "': null message");
  }
  uint8_t * data = nullptr;
  size_t size = 0;
  Status s = take(detail::reusing_allocator(*message), &data, &size, info, taken);
  if (s.ok() && *taken) {
    detail::adopt(message, data, size);
  }
  return s;
}

Status Subscription::take(
  const Allocator & allocator, uint8_t ** data, size_t * size, MessageInfo * info, bool * taken)
{
  wasm_bus_take_info ti;
  Status s = detail::take(
    handle_, detail::kTakeMessage, allocator, data, size, &ti, taken, "take on", topic_name_);
  if (!s.ok() || !*taken || info == nullptr) {
    return s;
  }
  info->source_timestamp = detail::ms_to_ns(ti.source_ms);
  info->received_timestamp = detail::ms_to_ns(ti.received_ms);
  info->publication_sequence_number =
    (static_cast<uint64_t>(ti.pub_seq_hi) << 32) | ti.pub_seq_lo;
  info->reception_sequence_number =
    (static_cast<uint64_t>(ti.recv_seq_hi) << 32) | ti.recv_seq_lo;
  info->publisher_gid = detail::gid_from_words(ti.gid);
  info->from_same_process = ti.same_process != 0;
  return s;
}

bool Subscription::has_data() const
{
  return handle_ >= 0 && wasm_bus_has_data(handle_, detail::kTakeMessage) == 1;
}

size_t Subscription::matched_publisher_count() const
{
  if (handle_ < 0) {
    return 0;
  }
  int n = wasm_bus_matched_count(handle_);
  return n > 0 ? static_cast<size_t>(n) : 0;
}

Status Subscription::set_on_new_message_callback(EventCallback callback, const void * user_data)
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (handle_ < 0) {
    return Status(Code::kError, "set_on_new_message_callback: subscription was shut down");
  }
  return detail::Listener::instance().set(
    &listener_id_, detail::kListenSubscription, handle_, 0, callback, user_data);
}

Status Subscription::shutdown()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (listener_id_ != 0) {
      detail::Listener::instance().set(&listener_id_, 0, handle_, 0, nullptr, nullptr);
    }
  }
  return detail::destroy_endpoint(&handle_, topic_name_);
}

}  // namespace wasm_cpp
