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

#include "rmw/event.h"
#include "rmw/event_callback_type.h"
#include "rmw/ret_types.h"
#include "wasm_cpp/events.hpp"

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

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__RMW_EVENT_DATA_HPP_
