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

#ifndef DETAIL__RMW_SUBSCRIPTION_DATA_HPP_
#define DETAIL__RMW_SUBSCRIPTION_DATA_HPP_

#include <memory>

#include "rmw/event.h"
#include "rmw/serialized_message.h"
#include "rmw/types.h"
#include "wasm_cpp/node.hpp"
#include "wasm_cpp/subscription.hpp"

#include "detail/rmw_event_data.hpp"
#include "detail/scratch_buffer.hpp"
#include "detail/type_support.hpp"

namespace rmw_wasm_cpp
{

/// The data behind an rmw_subscription_t: the core subscription and the message type support.
class SubscriptionData final
{
public:
  /// Create the subscription on the bus; on failure returns null with the rmw error set.
  /**
   * Logs a warning when the topic already has endpoints of another type
   * (they will not match this one).
   */
  static std::shared_ptr<SubscriptionData> make(
    const std::shared_ptr<wasm_cpp::Node> & node,
    std::shared_ptr<MessageTypeSupport> type_support,
    const char * topic_name,
    const rmw_qos_profile_t & qos,
    const rmw_subscription_options_t & options);

  /// Take the next message into `ros_message`, copying its bytes through `buffer`.
  /**
   * A message that does not deserialize is dropped: RMW_RET_ERROR with the
   * reason, and `*taken` false; the next take goes on with the next message.
   */
  rmw_ret_t take(
    void * ros_message, bool * taken, rmw_message_info_t * message_info,
    ScratchBuffer & buffer);

  /// Take the next message as CDR bytes into `message` (resized as needed).
  rmw_ret_t take_serialized(
    rmw_serialized_message_t * message, bool * taken, rmw_message_info_t * message_info);

  /// The core subscription.
  wasm_cpp::Subscription & subscription() const {return *subscription_;}

  /// The message type support.
  const MessageTypeSupport & type_support() const {return *type_support_;}

  /// The event handle of kind `type`, created on first use; null (rmw error set) when the
  /// kind is not a subscription event.
  EventData * event(rmw_event_type_t type);

  /// Remove the subscription from the graph. Idempotent.
  void shutdown();

private:
  SubscriptionData(
    std::shared_ptr<wasm_cpp::Subscription> subscription,
    std::shared_ptr<MessageTypeSupport> type_support);

  // The core subscription.
  std::shared_ptr<wasm_cpp::Subscription> subscription_;
  // How messages are deserialized.
  std::shared_ptr<MessageTypeSupport> type_support_;
  // Event handles by rmw event type.
  EventTable events_;
};

/// Copy the core's message info into an rmw_message_info_t.
void to_rmw_message_info(const wasm_cpp::MessageInfo & info, rmw_message_info_t * out);

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__RMW_SUBSCRIPTION_DATA_HPP_
