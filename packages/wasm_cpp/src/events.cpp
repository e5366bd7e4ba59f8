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

#include "wasm_cpp/events.hpp"

#include <memory>
#include <string>
#include <utility>

#include "bus_abi.hpp"
#include "listener.hpp"
#include "wasm_cpp/publisher.hpp"
#include "wasm_cpp/subscription.hpp"

namespace wasm_cpp
{

bool is_publisher_event(EventType type)
{
  return type == EventType::kLivelinessLost || type == EventType::kOfferedDeadlineMissed ||
         type == EventType::kOfferedQosIncompatible;
}

bool is_subscription_event(EventType type)
{
  return type == EventType::kLivelinessChanged ||
         type == EventType::kRequestedDeadlineMissed ||
         type == EventType::kRequestedQosIncompatible || type == EventType::kMessageLost;
}

Result<std::shared_ptr<Event>> Event::make(std::shared_ptr<Publisher> publisher, EventType type)
{
  if (!publisher) {
    return Status(Code::kInvalidArgument, "cannot create event: null publisher");
  }
  if (!is_publisher_event(type)) {
    return Status(
      Code::kInvalidArgument, "cannot create event of type " +
      std::to_string(static_cast<int>(type)) + " for publisher on '" + publisher->topic_name() +
      "': not a publisher event");
  }
  int32_t handle = publisher->handle();
  return std::shared_ptr<Event>(new Event(std::move(publisher), nullptr, handle, type));
}

Result<std::shared_ptr<Event>> Event::make(
  std::shared_ptr<Subscription> subscription, EventType type)
{
  if (!subscription) {
    return Status(Code::kInvalidArgument, "cannot create event: null subscription");
  }
  if (!is_subscription_event(type)) {
    return Status(
      Code::kInvalidArgument, "cannot create event of type " +
      std::to_string(static_cast<int>(type)) + " for subscription on '" +
      subscription->topic_name() + "': not a subscription event");
  }
  int32_t handle = subscription->handle();
  return std::shared_ptr<Event>(new Event(nullptr, std::move(subscription), handle, type));
}

Event::Event(
  std::shared_ptr<Publisher> publisher, std::shared_ptr<Subscription> subscription,
  int32_t entity_handle, EventType type)
: publisher_(std::move(publisher)), subscription_(std::move(subscription)),
  entity_handle_(entity_handle), type_(type)
{
}

Event::~Event()
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (listener_id_ != 0) {
    detail::Listener::instance().set(&listener_id_, 0, entity_handle_, 0, nullptr, nullptr);
  }
}

Status Event::take(EventStatus * status, bool * taken)
{
  if (status == nullptr || taken == nullptr) {
    return Status(Code::kInvalidArgument, "take_event: null output argument");
  }
  int32_t s[8] = {};
  int rc = wasm_bus_event_status(entity_handle_, static_cast<int>(type_), 1, s);
  if (rc != 0) {
    return detail::bus_status(rc, "take_event");
  }
  *taken = s[0] != 0;
  status->total_count = s[1];
  status->total_count_change = s[2];
  status->alive_count = s[3];
  status->not_alive_count = s[4];
  status->alive_count_change = s[5];
  status->not_alive_count_change = s[6];
  status->last_policy_kind =
    s[7] != 0 ? static_cast<QosPolicyKind>(s[7]) : QosPolicyKind::kInvalid;
  return Status::Ok();
}

bool Event::has_change() const
{
  int32_t s[8] = {};
  return wasm_bus_event_status(entity_handle_, static_cast<int>(type_), 0, s) == 0 && s[0] != 0;
}

Status Event::set_callback(EventCallback callback, const void * user_data)
{
  std::lock_guard<std::mutex> lock(mutex_);
  return detail::Listener::instance().set(
    &listener_id_, detail::kListenEvent, entity_handle_, static_cast<int>(type_), callback,
    user_data);
}

}  // namespace wasm_cpp
