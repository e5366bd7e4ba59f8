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

#ifndef WASM_CPP__GUARD_CONDITION_HPP_
#define WASM_CPP__GUARD_CONDITION_HPP_

#include <cstdint>
#include <memory>

#include "wasm_cpp/context.hpp"
#include "wasm_cpp/status.hpp"

namespace wasm_cpp
{

/// A condition a wait set can wait on, triggered by trigger() from any thread.
/**
 * Like rmw guard conditions: a trigger makes the next wait that includes the
 * condition return with it ready, and that wait consumes the trigger.
 *
 * A graph guard condition (make_graph()) is, in addition, triggered by every
 * change of the bus graph (nodes or endpoints appearing or leaving, in any
 * domain); rmw_node_get_graph_guard_condition returns one per node.
 */
class GuardCondition final
{
public:
  /// Create a plain guard condition.
  static Result<std::shared_ptr<GuardCondition>> make(std::shared_ptr<Context> context);

  /// Create a graph guard condition.
  static Result<std::shared_ptr<GuardCondition>> make_graph(std::shared_ptr<Context> context);

  /// Trigger the condition and wake the waits of this process. Thread-safe.
  Status trigger();

  /// True for a graph guard condition.
  bool is_graph() const {return state_[0] == 1;}

  /// Internal: the shared state words read by the wait (kind, triggered, seen graph version).
  int32_t * state() {return state_;}

  ~GuardCondition();

private:
  GuardCondition(std::shared_ptr<Context> context, bool graph);

  // Keeps the context alive.
  std::shared_ptr<Context> context_;
  // [0] kind (0 plain, 1 graph), [1] triggered flag, [2] last graph version seen,
  // [3] reserved. Accessed with atomics from C++ and JS.
  alignas(16) int32_t state_[4];
};

}  // namespace wasm_cpp

#endif  // WASM_CPP__GUARD_CONDITION_HPP_
