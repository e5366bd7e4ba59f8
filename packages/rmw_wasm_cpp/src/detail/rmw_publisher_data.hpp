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

#ifndef DETAIL__RMW_PUBLISHER_DATA_HPP_
#define DETAIL__RMW_PUBLISHER_DATA_HPP_

#include <memory>

#include "rmw/event.h"
#include "rmw/serialized_message.h"
#include "rmw/types.h"
#include "wasm_cpp/node.hpp"
#include "wasm_cpp/publisher.hpp"

#include "detail/rmw_event_data.hpp"
#include "detail/scratch_buffer.hpp"
#include "detail/type_support.hpp"

namespace rmw_wasm_cpp
{

/// The data behind an rmw_publisher_t: the core publisher and the message type support.
class PublisherData final
{
public:
  /// Create the publisher on the bus; on failure returns null with the rmw error set.
  /**
   * Logs a warning when the topic already has endpoints of another type
   * (they will not match this one).
   */
  static std::shared_ptr<PublisherData> make(
    const std::shared_ptr<wasm_cpp::Node> & node,
    std::shared_ptr<MessageTypeSupport> type_support,
    const char * topic_name,
    const rmw_qos_profile_t & qos);

  /// Serialize `ros_message` (into `buffer`) and publish it.
  rmw_ret_t publish(const void * ros_message, ScratchBuffer & buffer);

  /// Publish an already serialized message (checked to carry a CDR header).
  rmw_ret_t publish_serialized(const rmw_serialized_message_t & message);

  /// The core publisher.
  wasm_cpp::Publisher & publisher() const {return *publisher_;}

  /// The message type support.
  const MessageTypeSupport & type_support() const {return *type_support_;}

  /// The event handle of kind `type`, created on first use; null (rmw error set) when the
  /// kind is not a publisher event.
  EventData * event(rmw_event_type_t type);

  /// Remove the publisher from the graph. Idempotent.
  void shutdown();

private:
  PublisherData(
    std::shared_ptr<wasm_cpp::Publisher> publisher,
    std::shared_ptr<MessageTypeSupport> type_support);

  // Check the size against the bus maximum and publish.
  rmw_ret_t send(const uint8_t * data, size_t size);

  // The core publisher.
  std::shared_ptr<wasm_cpp::Publisher> publisher_;
  // How messages are serialized.
  std::shared_ptr<MessageTypeSupport> type_support_;
  // Event handles by rmw event type.
  EventTable events_;
};

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__RMW_PUBLISHER_DATA_HPP_
