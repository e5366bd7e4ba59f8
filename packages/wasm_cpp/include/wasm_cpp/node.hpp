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

#ifndef WASM_CPP__NODE_HPP_
#define WASM_CPP__NODE_HPP_

#include <cstdint>
#include <memory>
#include <string>

#include "wasm_cpp/context.hpp"
#include "wasm_cpp/status.hpp"
#include "wasm_cpp/types.hpp"

namespace wasm_cpp
{

/// A participant in the graph: a named node in one context.
/**
 * Visible in graph queries (name, namespace, enclave) from creation until it
 * is destroyed or its process dies.
 */
class Node final
{
public:
  /// Create a node.
  /**
   * \param[in] context a context that is not shut down
   * \param[in] name a valid ROS node name (e.g. "talker")
   * \param[in] namespace_ an absolute namespace ("/" or "/robot1")
   * \return the node, or kInvalidArgument for a malformed name or namespace,
   *   kBadAlloc when the bus' node table is full
   */
  static Result<std::shared_ptr<Node>> make(
    std::shared_ptr<Context> context,
    const std::string & name,
    const std::string & namespace_);

  /// The node name.
  const std::string & name() const {return name_;}

  /// The node namespace.
  const std::string & namespace_() const {return ns_;}

  /// The fully qualified name, e.g. "/robot1/talker".
  std::string fully_qualified_name() const;

  /// True when another live node in the same domain had the same fully
  /// qualified name when this one was created (ROS warns about this).
  bool name_was_taken() const {return name_was_taken_;}

  /// The node's gid.
  const Gid & gid() const {return gid_;}

  /// The context this node belongs to.
  const std::shared_ptr<Context> & context() const {return context_;}

  /// Internal: the bus handle of this node.
  int32_t handle() const {return handle_;}

  /// Assert liveliness of every MANUAL_BY_NODE publisher of this node
  /// (treated as MANUAL_BY_TOPIC publishers of this node).
  Status assert_liveliness();

  /// Remove the node from the graph. Idempotent; also done by the destructor.
  Status shutdown();

  ~Node();

private:
  Node(
    std::shared_ptr<Context> context, std::string name, std::string namespace_,
    int32_t handle, const Gid & gid, bool name_was_taken);

  // Keeps the context alive.
  std::shared_ptr<Context> context_;
  // Node name and namespace.
  std::string name_;
  std::string ns_;
  // Bus handle, -1 after shutdown().
  int32_t handle_;
  // Node gid.
  Gid gid_;
  // Whether the name was in use at creation.
  bool name_was_taken_;
};

}  // namespace wasm_cpp

#endif  // WASM_CPP__NODE_HPP_
