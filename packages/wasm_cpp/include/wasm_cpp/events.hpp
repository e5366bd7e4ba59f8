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

#ifndef WASM_CPP__EVENTS_HPP_
#define WASM_CPP__EVENTS_HPP_

#include <cstdint>
#include <memory>
#include <mutex>

#include "wasm_cpp/qos.hpp"
#include "wasm_cpp/status.hpp"
#include "wasm_cpp/types.hpp"

namespace wasm_cpp
{

class Publisher;
class Subscription;

/// Event kinds; values equal rmw_event_type_t.
/**
 * Subscription events: kLivelinessChanged, kRequestedDeadlineMissed,
 * kRequestedQosIncompatible, kMessageLost. Publisher events:
 * kLivelinessLost, kOfferedDeadlineMissed, kOfferedQosIncompatible.
 */
enum class EventType : int32_t
{
  kLivelinessChanged = 0,
  kRequestedDeadlineMissed = 1,
  kRequestedQosIncompatible = 2,
  kMessageLost = 3,
  kLivelinessLost = 4,
  kOfferedDeadlineMissed = 5,
  kOfferedQosIncompatible = 6,
  kInvalid = 7,
};

/// The status of one event kind, a superset of every rmw_*_status_t.
/**
 * Which fields are meaningful depends on the kind:
 * - kLivelinessChanged: alive_count, not_alive_count, alive_count_change,
 *   not_alive_count_change (rmw_liveliness_changed_status_t);
 * - kRequestedQosIncompatible / kOfferedQosIncompatible: total_count,
 *   total_count_change, last_policy_kind (rmw_qos_incompatible_event_status_t);
 * - every other kind: total_count and total_count_change.
 *
 * "change" fields count what happened since the previous take of the same
 * event kind on the same entity; taking resets them to zero.
 */
struct EventStatus
{
  int64_t total_count = 0;
  int64_t total_count_change = 0;
  int32_t alive_count = 0;
  int32_t not_alive_count = 0;
  int32_t alive_count_change = 0;
  int32_t not_alive_count_change = 0;
  QosPolicyKind last_policy_kind = QosPolicyKind::kInvalid;
};

/// True when `type` is an event a publisher can have.
bool is_publisher_event(EventType type);

/// True when `type` is an event a subscription can have.
bool is_subscription_event(EventType type);

/// One event kind of one publisher or subscription: the thing an rmw_event_t points at.
/**
 * Deadline and liveliness statuses are computed lazily from timestamps when
 * the event is taken or waited on; a wait that includes such an event uses
 * the next expiry as its timeout, so no timer thread is needed.
 */
class Event final
{
public:
  /// Create an event handle for a publisher; kInvalidArgument for a subscription-only type.
  static Result<std::shared_ptr<Event>> make(std::shared_ptr<Publisher> publisher, EventType type);

  /// Create an event handle for a subscription; kInvalidArgument for a publisher-only type.
  static Result<std::shared_ptr<Event>> make(
    std::shared_ptr<Subscription> subscription, EventType type);

  /// The event kind.
  EventType type() const {return type_;}

  /// Take the current status and reset its "change" fields.
  /**
   * \param[out] status the status; always filled
   * \param[out] taken true when something changed since the previous take
   *   (rmw_take_event may report `taken` as true regardless; rmw adapters choose)
   */
  Status take(EventStatus * status, bool * taken);

  /// True when a take() would report a change (used by wait sets).
  bool has_change() const;

  /// Call `callback(user_data, n)` when the status changes; null clears it.
  /**
   * Needs pthreads (the callback runs on the process' listener thread);
   * returns kUnsupported in a build without them.
   */
  Status set_callback(EventCallback callback, const void * user_data);

  /// Internal: the bus handle of the entity this event belongs to.
  int32_t entity_handle() const {return entity_handle_;}

  ~Event();

private:
  Event(
    std::shared_ptr<Publisher> publisher, std::shared_ptr<Subscription> subscription,
    int32_t entity_handle, EventType type);

  // Keeps the owning entity alive while the event exists; one of the two is set.
  std::shared_ptr<Publisher> publisher_;
  std::shared_ptr<Subscription> subscription_;
  // Bus handle of the owning endpoint.
  int32_t entity_handle_;
  // Which status this event reports.
  EventType type_;
  // Protects callback registration.
  mutable std::mutex mutex_;
  // Listener registration id, 0 when no callback is set.
  int32_t listener_id_ = 0;
};

}  // namespace wasm_cpp

#endif  // WASM_CPP__EVENTS_HPP_
