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

#ifndef WASM_CPP__SUBSCRIPTION_HPP_
#define WASM_CPP__SUBSCRIPTION_HPP_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "wasm_cpp/node.hpp"
#include "wasm_cpp/qos.hpp"
#include "wasm_cpp/status.hpp"
#include "wasm_cpp/types.hpp"

namespace wasm_cpp
{

/// Options of a subscription beyond its QoS.
struct SubscriptionOptions
{
  /// Do not receive messages from publishers of the same context.
  bool ignore_local_publications = false;
};

/// Receives the messages of the matched publishers of a topic.
/**
 * Messages are read straight out of each matched publisher's ring: take()
 * copies a message once, from the bus into a buffer owned by the caller.
 * Several threads of one process may take from one subscription
 * concurrently; each message is taken exactly once.
 *
 * Delivery follows the QoS: KEEP_LAST(n) keeps the newest n messages of each
 * publisher, KEEP_ALL + RELIABLE never loses one (the publisher blocks
 * instead), TRANSIENT_LOCAL late joiners receive the publishers' retained
 * history, expired messages (lifespan) are skipped, and messages a
 * BEST_EFFORT subscription missed are counted as lost (kMessageLost event).
 * Among several publishers, the message with the oldest source timestamp is
 * taken first.
 */
class Subscription final
{
public:
  /// Create a subscription.
  /**
   * \param[in] node the owning node
   * \param[in] topic_name fully qualified topic name
   * \param[in] type_name the message type; only equal type names match
   * \param[in] qos the QoS; SYSTEM_DEFAULT values are resolved (resolve_qos)
   * \param[in] options see SubscriptionOptions
   */
  static Result<std::shared_ptr<Subscription>> make(
    std::shared_ptr<Node> node,
    const std::string & topic_name,
    const std::string & type_name,
    const QoS & qos,
    const SubscriptionOptions & options = SubscriptionOptions());

  /// Take the next message into a new malloc'd buffer owned by `message`.
  /**
   * \param[out] message the bytes (set only when taken)
   * \param[out] info message info (set only when taken); may be null
   * \param[out] taken false when no message was available
   */
  Status take(Message * message, MessageInfo * info, bool * taken);

  /// Take the next message into memory obtained from `allocator`.
  /**
   * The bytes are copied once, from the bus into
   * `allocator.allocate(size)`; on success `*data`/`*size` describe them
   * and the caller owns `*data` (release with `allocator.deallocate`).
   */
  Status take(
    const Allocator & allocator, uint8_t ** data, size_t * size,
    MessageInfo * info, bool * taken);

  /// True when a take() would find a message now.
  bool has_data() const;

  /// Number of publishers currently matched.
  size_t matched_publisher_count() const;

  /// The QoS in use (SYSTEM_DEFAULT resolved).
  const QoS & actual_qos() const {return qos_;}

  /// The options this subscription was created with.
  const SubscriptionOptions & options() const {return options_;}

  /// Call `callback(user_data, n)` for each batch of n new messages; null clears it.
  /**
   * Messages that arrived before the callback was set are reported at once.
   * The callback runs on the process' listener thread (needs pthreads;
   * kUnsupported otherwise). Same contract as
   * rmw_subscription_set_on_new_message_callback.
   */
  Status set_on_new_message_callback(EventCallback callback, const void * user_data);

  /// The subscription's gid.
  const Gid & gid() const {return gid_;}

  /// The topic name.
  const std::string & topic_name() const {return topic_name_;}

  /// The type name.
  const std::string & type_name() const {return type_name_;}

  /// The owning node.
  const std::shared_ptr<Node> & node() const {return node_;}

  /// Internal: the bus handle of this subscription.
  int32_t handle() const {return handle_;}

  /// Remove the subscription from the graph. Idempotent; also done by the destructor.
  Status shutdown();

  ~Subscription();

private:
  Subscription(
    std::shared_ptr<Node> node, std::string topic_name, std::string type_name,
    const QoS & qos, const SubscriptionOptions & options, int32_t handle, const Gid & gid);

  // Keeps the node alive.
  std::shared_ptr<Node> node_;
  // Topic and type names.
  std::string topic_name_;
  std::string type_name_;
  // Resolved QoS.
  QoS qos_;
  // Creation options.
  SubscriptionOptions options_;
  // Bus handle, -1 after shutdown().
  int32_t handle_;
  // Subscription gid.
  Gid gid_;
  // Protects listener_id_.
  mutable std::mutex mutex_;
  // Listener registration id, 0 when no callback is set.
  int32_t listener_id_ = 0;
};

}  // namespace wasm_cpp

#endif  // WASM_CPP__SUBSCRIPTION_HPP_
