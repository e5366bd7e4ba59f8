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

#ifndef DETAIL__RMW_EVENT_DATA_HPP_
#define DETAIL__RMW_EVENT_DATA_HPP_

#include <memory>
#include <mutex>
#include <unordered_map>

#include "rmw/event.h"
#include "rmw/error_handling.h"
#include "rmw/event_callback_type.h"
#include "rmw/ret_types.h"
#include "wasm_cpp/events.hpp"

#include "detail/status.hpp"

namespace rmw_wasm_cpp
{

/// The data behind an rmw_event_t: one event kind of one publisher or subscription.
/**
 * Owned by its publisher or subscription (rmw_event_fini frees nothing), so
 * it lives as long as the entity does.
 */
class EventData final
{
public:
  /// Wrap a core event.
  static std::shared_ptr<EventData> make(std::shared_ptr<wasm_cpp::Event> event);

  /// The core event.
  wasm_cpp::Event * event() const {return event_.get();}

  /// Take the status into `event_info` (the rmw_*_status_t of the event's kind).
  rmw_ret_t take(void * event_info, bool * taken);

  /// Call `callback` when the status changes (null clears it).
  rmw_ret_t set_callback(rmw_event_callback_t callback, const void * user_data);

private:
  explicit EventData(std::shared_ptr<wasm_cpp::Event> event);

  // The core event (keeps its entity alive).
  std::shared_ptr<wasm_cpp::Event> event_;
};

/// The core event kind of an rmw event type (kInvalid for RMW_EVENT_INVALID and unknown values).
wasm_cpp::EventType to_wasm_event_type(rmw_event_type_t type);

/// The event handles of one publisher or subscription, each made on first use.
class EventTable final
{
public:
  /// The handle of kind `type` on `entity` (a wasm_cpp::Publisher or Subscription);
  /// null (rmw error set) when `is_own_kind` says the kind is not the entity's.
  template<typename Entity>
  EventData * get(
    const std::shared_ptr<Entity> & entity, rmw_event_type_t type,
    bool (* is_own_kind)(wasm_cpp::EventType), const char * role)
  {
    const wasm_cpp::EventType kind = to_wasm_event_type(type);
    if (!is_own_kind(kind)) {
      RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
        "event type %d is not a %s event", static_cast<int>(type), role);
      return nullptr;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = events_.find(static_cast<int>(type));
    if (it != events_.end()) {
      return it->second.get();
    }
    auto event = wasm_cpp::Event::make(entity, kind);
    if (!event.ok()) {
      to_rmw_ret(event.status());
      return nullptr;
    }
    auto data = EventData::make(event.value());
    events_[static_cast<int>(type)] = data;
    return data.get();
  }

  /// Drop every handle (the entity shuts down).
  void clear()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    events_.clear();
  }

private:
  // Protects events_.
  std::mutex mutex_;
  // Event handles by rmw event type.
  std::unordered_map<int, std::shared_ptr<EventData>> events_;
};

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__RMW_EVENT_DATA_HPP_
