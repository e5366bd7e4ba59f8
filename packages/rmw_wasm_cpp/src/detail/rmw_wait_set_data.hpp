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

#ifndef DETAIL__RMW_WAIT_SET_DATA_HPP_
#define DETAIL__RMW_WAIT_SET_DATA_HPP_

#include <memory>
#include <vector>

#include "rmw/types.h"
#include "wasm_cpp/wait_set.hpp"

namespace rmw_wasm_cpp
{

/// The data behind an rmw_wait_set_t: the core wait set and a reusable item list.
class WaitSetData final
{
public:
  /// Create a wait set for up to `max_conditions` entities (0: no limit); null + rmw error
  /// on failure.
  static std::unique_ptr<WaitSetData> make(
    const std::shared_ptr<wasm_cpp::Context> & context, size_t max_conditions);

  /// Block until one of the given entities is ready or the timeout passes (null: forever).
  /**
   * Entities that are not ready are set to null in their arrays, as rmw_wait
   * specifies. Sleeps on the process' doorbell (Atomics.wait) in the core;
   * never polls.
   * \return RMW_RET_OK when something is ready, RMW_RET_TIMEOUT otherwise
   */
  rmw_ret_t wait(
    rmw_subscriptions_t * subscriptions, rmw_guard_conditions_t * guard_conditions,
    rmw_services_t * services, rmw_clients_t * clients, rmw_events_t * events,
    const rmw_time_t * wait_timeout);

private:
  WaitSetData(std::shared_ptr<wasm_cpp::WaitSet> wait_set, size_t max_conditions);

  // The core wait set.
  std::shared_ptr<wasm_cpp::WaitSet> wait_set_;
  // Items of the current wait (reused; rmw_wait is not called concurrently on one wait set).
  std::vector<wasm_cpp::WaitItem> items_;
};

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__RMW_WAIT_SET_DATA_HPP_
