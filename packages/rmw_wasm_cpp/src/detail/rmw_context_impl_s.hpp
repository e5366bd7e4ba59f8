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

#ifndef DETAIL__RMW_CONTEXT_IMPL_S_HPP_
#define DETAIL__RMW_CONTEXT_IMPL_S_HPP_

#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>

#include "rmw/init.h"
#include "rmw/types.h"
#include "wasm_cpp/context.hpp"

namespace rmw_wasm_cpp
{
class NodeData;
}  // namespace rmw_wasm_cpp

/// The implementation behind an rmw_context_t: one wasm_cpp::Context and the nodes created in it.
struct rmw_context_impl_s final
{
public:
  /// Attach to the bus in the options' domain; on failure returns null with the rmw error set.
  static std::unique_ptr<rmw_context_impl_s> make(const rmw_init_options_t & options);

  /// The core context.
  const std::shared_ptr<wasm_cpp::Context> & context() const {return context_;}

  /// Create a node of this context and keep it until destroy_node().
  /**
   * \return the node's data, or null with the rmw error set
   */
  std::shared_ptr<rmw_wasm_cpp::NodeData> create_node(
    const rmw_node_t * handle, const char * name, const char * namespace_);

  /// Forget a node (its entities go with it).
  void destroy_node(const rmw_node_t * handle);

  /// Shut the context down: creating entities fails from now on. Idempotent.
  rmw_ret_t shutdown();

  /// True after shutdown().
  bool is_shutdown() const;

private:
  explicit rmw_context_impl_s(std::shared_ptr<wasm_cpp::Context> context);

  // Protects nodes_.
  mutable std::mutex mutex_;
  // The attachment to the bus.
  std::shared_ptr<wasm_cpp::Context> context_;
  // Live nodes by their rmw handle.
  std::unordered_map<const rmw_node_t *, std::shared_ptr<rmw_wasm_cpp::NodeData>> nodes_;
};

#endif  // DETAIL__RMW_CONTEXT_IMPL_S_HPP_
