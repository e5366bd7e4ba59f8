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

#ifndef WASM_CPP__PUBLISHER_HPP_
#define WASM_CPP__PUBLISHER_HPP_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "wasm_cpp/node.hpp"
#include "wasm_cpp/qos.hpp"
#include "wasm_cpp/status.hpp"
#include "wasm_cpp/types.hpp"

namespace wasm_cpp
{

/// Options of a publisher beyond its QoS.
struct PublisherOptions
{
  /// How long publish() may block on a full KEEP_ALL reader; negative: the context's default.
  Timeout publish_timeout = Timeout(-1);
};

/// Publishes opaque byte messages (serialized by the caller) on a topic.
/**
 * Each publisher owns a ring of message slots on the bus (its history: depth
 * slots for KEEP_LAST, ContextOptions::keep_all_depth for KEEP_ALL). A
 * publish copies the bytes once into the ring and wakes the processes of the
 * matched subscriptions. It never waits for KEEP_LAST readers; it blocks (up
 * to the publish timeout) only before overwriting a message that a RELIABLE
 * KEEP_ALL subscription has not taken yet. Thread-safe.
 */
class Publisher final
{
public:
  /// Create a publisher.
  /**
   * \param[in] node the owning node
   * \param[in] topic_name fully qualified topic name (e.g. "/chatter")
   * \param[in] type_name the message type (e.g. "std_msgs/msg/String"); only
   *   endpoints with equal type names match
   * \param[in] qos the QoS; SYSTEM_DEFAULT values are resolved (resolve_qos)
   * \return the publisher, or kInvalidArgument (bad name/type/QoS),
   *   kBadAlloc (bus tables or memory exhausted)
   */
  static Result<std::shared_ptr<Publisher>> make(
    std::shared_ptr<Node> node,
    const std::string & topic_name,
    const std::string & type_name,
    const QoS & qos,
    const PublisherOptions & options = PublisherOptions());

  /// Publish `size` bytes, blocking at most the publisher's publish timeout.
  /**
   * \return kOk; kBadAlloc when `size` exceeds the bus maximum or bus memory
   *   is exhausted; kTimeout when a RELIABLE KEEP_ALL subscription stayed full
   *   for the whole timeout (the message is then not published);
   *   kInvalidArgument for a null `data` with a non-zero size.
   */
  Status publish(const void * data, size_t size);

  /// Publish `size` bytes, blocking at most `timeout` (negative: forever).
  Status publish(const void * data, size_t size, Timeout timeout);

  /// Number of subscriptions currently matched (same domain, topic, type; compatible QoS).
  size_t matched_subscription_count() const;

  /// The QoS in use (SYSTEM_DEFAULT resolved).
  const QoS & actual_qos() const {return qos_;}

  /// Assert liveliness (for MANUAL_BY_TOPIC); publishing asserts it too.
  Status assert_liveliness();

  /// Block until every RELIABLE matched subscription has taken every message
  /// published so far (or can no longer take it), or `timeout` passes.
  /**
   * On this bus a message is delivered the moment it is published (readers
   * read the publisher's ring), so "acknowledged" is defined as "taken": this
   * is what a publisher about to exit needs to know, since its ring goes away
   * with it. Returns kTimeout when the timeout passes first.
   */
  Status wait_for_all_acked(Timeout timeout);

  /// The publisher's gid.
  const Gid & gid() const {return gid_;}

  /// The topic name.
  const std::string & topic_name() const {return topic_name_;}

  /// The type name.
  const std::string & type_name() const {return type_name_;}

  /// The owning node.
  const std::shared_ptr<Node> & node() const {return node_;}

  /// Internal: the bus handle of this publisher.
  int32_t handle() const {return handle_;}

  /// Remove the publisher from the graph. Idempotent; also done by the destructor.
  Status shutdown();

  ~Publisher();

private:
  Publisher(
    std::shared_ptr<Node> node, std::string topic_name, std::string type_name,
    const QoS & qos, Timeout publish_timeout, int32_t handle, const Gid & gid);

  // Keeps the node alive.
  std::shared_ptr<Node> node_;
  // Topic and type names.
  std::string topic_name_;
  std::string type_name_;
  // Resolved QoS.
  QoS qos_;
  // Default blocking bound of publish().
  Timeout publish_timeout_;
  // Bus handle, -1 after shutdown().
  int32_t handle_;
  // Publisher gid.
  Gid gid_;
};

}  // namespace wasm_cpp

#endif  // WASM_CPP__PUBLISHER_HPP_
