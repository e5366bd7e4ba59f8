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

#include "detail/rmw_event_data.hpp"

#include <memory>
#include <utility>

#include "rmw/error_handling.h"
#include "rmw/events_statuses/events_statuses.h"

#include "detail/status.hpp"

namespace rmw_wasm_cpp
{

wasm_cpp::EventType to_wasm_event_type(rmw_event_type_t type)
{
  switch (type) {
    case RMW_EVENT_LIVELINESS_CHANGED: return wasm_cpp::EventType::kLivelinessChanged;
    case RMW_EVENT_REQUESTED_DEADLINE_MISSED: return wasm_cpp::EventType::kRequestedDeadlineMissed;
    case RMW_EVENT_REQUESTED_QOS_INCOMPATIBLE:
      return wasm_cpp::EventType::kRequestedQosIncompatible;
    case RMW_EVENT_MESSAGE_LOST: return wasm_cpp::EventType::kMessageLost;
    case RMW_EVENT_LIVELINESS_LOST: return wasm_cpp::EventType::kLivelinessLost;
    case RMW_EVENT_OFFERED_DEADLINE_MISSED: return wasm_cpp::EventType::kOfferedDeadlineMissed;
    case RMW_EVENT_OFFERED_QOS_INCOMPATIBLE: return wasm_cpp::EventType::kOfferedQosIncompatible;
    default: return wasm_cpp::EventType::kInvalid;
  }
}

EventData::EventData(std::shared_ptr<wasm_cpp::Event> event)
: event_(std::move(event))
{
}

std::shared_ptr<EventData> EventData::make(std::shared_ptr<wasm_cpp::Event> event)
{
  return std::shared_ptr<EventData>(new EventData(std::move(event)));
}

rmw_ret_t EventData::take(void * event_info, bool * taken)
{
  wasm_cpp::EventStatus status;
  bool changed = false;
  const rmw_ret_t ret = to_rmw_ret(event_->take(&status, &changed));
  if (ret != RMW_RET_OK) {
    *taken = false;
    return ret;
  }
  switch (event_->type()) {
    case wasm_cpp::EventType::kLivelinessChanged:
      {
        auto info = static_cast<rmw_liveliness_changed_status_t *>(event_info);
        info->alive_count = status.alive_count;
        info->not_alive_count = status.not_alive_count;
        info->alive_count_change = status.alive_count_change;
        info->not_alive_count_change = status.not_alive_count_change;
      }
      break;
    case wasm_cpp::EventType::kRequestedDeadlineMissed:
      {
        auto info = static_cast<rmw_requested_deadline_missed_status_t *>(event_info);
        info->total_count = static_cast<int32_t>(status.total_count);
        info->total_count_change = static_cast<int32_t>(status.total_count_change);
      }
      break;
    case wasm_cpp::EventType::kOfferedDeadlineMissed:
      {
        auto info = static_cast<rmw_offered_deadline_missed_status_t *>(event_info);
        info->total_count = static_cast<int32_t>(status.total_count);
        info->total_count_change = static_cast<int32_t>(status.total_count_change);
      }
      break;
    case wasm_cpp::EventType::kLivelinessLost:
      {
        auto info = static_cast<rmw_liveliness_lost_status_t *>(event_info);
        info->total_count = static_cast<int32_t>(status.total_count);
        info->total_count_change = static_cast<int32_t>(status.total_count_change);
      }
      break;
    case wasm_cpp::EventType::kMessageLost:
      {
        auto info = static_cast<rmw_message_lost_status_t *>(event_info);
        info->total_count = static_cast<size_t>(status.total_count);
        info->total_count_change = static_cast<size_t>(status.total_count_change);
      }
      break;
    case wasm_cpp::EventType::kRequestedQosIncompatible:
    case wasm_cpp::EventType::kOfferedQosIncompatible:
      {
        auto info = static_cast<rmw_qos_incompatible_event_status_t *>(event_info);
        info->total_count = static_cast<int32_t>(status.total_count);
        info->total_count_change = static_cast<int32_t>(status.total_count_change);
        // DDS has no policy of its own for the lease duration (it is part of
        // LIVELINESS), and rcl's test_events expects what the DDS middlewares
        // report; rmw_qos_profile_check_compatible still names the duration
        auto kind = static_cast<rmw_qos_policy_kind_t>(status.last_policy_kind);
        info->last_policy_kind =
          kind == RMW_QOS_POLICY_LIVELINESS_LEASE_DURATION ? RMW_QOS_POLICY_LIVELINESS : kind;
      }
      break;
    default:
      RMW_SET_ERROR_MSG("rmw_take_event: the event has an invalid type");
      *taken = false;
      return RMW_RET_ERROR;
  }
  // Like the DDS implementations: a successful take always yields the current status.
  *taken = true;
  return RMW_RET_OK;
}

rmw_ret_t EventData::set_callback(rmw_event_callback_t callback, const void * user_data)
{
  return to_rmw_ret(event_->set_callback(callback, user_data));
}

}  // namespace rmw_wasm_cpp
