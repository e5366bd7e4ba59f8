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

#include "detail/rmw_wait_set_data.hpp"

#include <chrono>
#include <memory>
#include <utility>

#include "rmw/error_handling.h"
#include "rmw/time.h"

#include "detail/identifier.hpp"
#include "detail/rmw_event_data.hpp"
#include "detail/rmw_guard_condition_data.hpp"
#include "detail/rmw_service_data.hpp"
#include "detail/rmw_subscription_data.hpp"
#include "detail/status.hpp"

namespace rmw_wasm_cpp
{

WaitSetData::WaitSetData(std::shared_ptr<wasm_cpp::WaitSet> wait_set, size_t max_conditions)
: wait_set_(std::move(wait_set))
{
  items_.reserve(max_conditions);
}

std::unique_ptr<WaitSetData> WaitSetData::make(
  const std::shared_ptr<wasm_cpp::Context> & context, size_t max_conditions)
{
  auto wait_set = wasm_cpp::WaitSet::make(context);
  if (!wait_set.ok()) {
    to_rmw_ret(wait_set.status());
    return nullptr;
  }
  return std::unique_ptr<WaitSetData>(new WaitSetData(wait_set.value(), max_conditions));
}

rmw_ret_t WaitSetData::wait(
  rmw_subscriptions_t * subscriptions, rmw_guard_conditions_t * guard_conditions,
  rmw_services_t * services, rmw_clients_t * clients, rmw_events_t * events,
  const rmw_time_t * wait_timeout)
{
  items_.clear();
  if (subscriptions != nullptr) {
    for (size_t i = 0; i < subscriptions->subscriber_count; ++i) {
      auto data = static_cast<SubscriptionData *>(subscriptions->subscribers[i]);
      items_.push_back(wasm_cpp::WaitItem::of(&data->subscription()));
    }
  }
  if (guard_conditions != nullptr) {
    for (size_t i = 0; i < guard_conditions->guard_condition_count; ++i) {
      auto data = static_cast<GuardConditionData *>(guard_conditions->guard_conditions[i]);
      items_.push_back(wasm_cpp::WaitItem::of(data->guard_condition()));
    }
  }
  if (services != nullptr) {
    for (size_t i = 0; i < services->service_count; ++i) {
      auto data = static_cast<ServiceData *>(services->services[i]);
      items_.push_back(wasm_cpp::WaitItem::of(&data->service()));
    }
  }
  if (clients != nullptr) {
    for (size_t i = 0; i < clients->client_count; ++i) {
      auto data = static_cast<ClientData *>(clients->clients[i]);
      items_.push_back(wasm_cpp::WaitItem::of(&data->client()));
    }
  }
  if (events != nullptr) {
    for (size_t i = 0; i < events->event_count; ++i) {
      auto event = static_cast<rmw_event_t *>(events->events[i]);
      if (event->implementation_identifier != kIdentifier) {
        RMW_SET_ERROR_MSG("rmw_wait: an event was not created by rmw_wasm_cpp");
        return RMW_RET_INCORRECT_RMW_IMPLEMENTATION;
      }
      items_.push_back(wasm_cpp::WaitItem::of(static_cast<EventData *>(event->data)->event()));
    }
  }

  wasm_cpp::Timeout timeout = wasm_cpp::kForever;
  if (wait_timeout != nullptr) {
    const rmw_duration_t ns = rmw_time_total_nsec(*wait_timeout);
    timeout = ns >= INT64_MAX ? wasm_cpp::kForever : wasm_cpp::Timeout(ns);
  }
  const wasm_cpp::Status status = wait_set_->wait(items_, timeout);
  if (!status.ok() && status.code() != wasm_cpp::Code::kTimeout) {
    return to_rmw_ret(status);
  }

  // Clear what is not ready, in the order the items were added.
  size_t k = 0;
  if (subscriptions != nullptr) {
    for (size_t i = 0; i < subscriptions->subscriber_count; ++i, ++k) {
      if (!items_[k].ready) {subscriptions->subscribers[i] = nullptr;}
    }
  }
  if (guard_conditions != nullptr) {
    for (size_t i = 0; i < guard_conditions->guard_condition_count; ++i, ++k) {
      if (!items_[k].ready) {guard_conditions->guard_conditions[i] = nullptr;}
    }
  }
  if (services != nullptr) {
    for (size_t i = 0; i < services->service_count; ++i, ++k) {
      if (!items_[k].ready) {services->services[i] = nullptr;}
    }
  }
  if (clients != nullptr) {
    for (size_t i = 0; i < clients->client_count; ++i, ++k) {
      if (!items_[k].ready) {clients->clients[i] = nullptr;}
    }
  }
  if (events != nullptr) {
    for (size_t i = 0; i < events->event_count; ++i, ++k) {
      if (!items_[k].ready) {events->events[i] = nullptr;}
    }
  }
  return status.ok() ? RMW_RET_OK : RMW_RET_TIMEOUT;
}

}  // namespace rmw_wasm_cpp
