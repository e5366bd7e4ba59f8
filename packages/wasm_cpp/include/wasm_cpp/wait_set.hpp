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

#ifndef WASM_CPP__WAIT_SET_HPP_
#define WASM_CPP__WAIT_SET_HPP_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "wasm_cpp/context.hpp"
#include "wasm_cpp/status.hpp"
#include "wasm_cpp/types.hpp"

namespace wasm_cpp
{

class Client;
class Event;
class GuardCondition;
class Service;
class Subscription;

/// One thing to wait for, and whether it was ready when the wait returned.
struct WaitItem
{
  /// What `entity` points at.
  enum class Kind : int32_t
  {
    kSubscription = 0,  ///< ready: a message can be taken
    kService = 1,       ///< ready: a request can be taken
    kClient = 2,        ///< ready: a response can be taken
    kGuardCondition = 3,  ///< ready: triggered (consumed by the wait)
    kEvent = 4,         ///< ready: the event status changed since its last take
  };

  Kind kind = Kind::kGuardCondition;
  /// The entity; must stay alive during the wait.
  void * entity = nullptr;
  /// Output of WaitSet::wait().
  bool ready = false;

  /// An item for a subscription.
  static WaitItem of(Subscription * s) {return {Kind::kSubscription, s, false};}
  /// An item for a service server.
  static WaitItem of(Service * s) {return {Kind::kService, s, false};}
  /// An item for a client.
  static WaitItem of(Client * c) {return {Kind::kClient, c, false};}
  /// An item for a guard condition.
  static WaitItem of(GuardCondition * g) {return {Kind::kGuardCondition, g, false};}
  /// An item for an event.
  static WaitItem of(Event * e) {return {Kind::kEvent, e, false};}
};

/// Blocks the calling thread until one of the given items is ready or the timeout passes.
/**
 * The wait reads the process' doorbell, checks every item, and if none is
 * ready sleeps on the doorbell with Atomics.wait (a publish to a matched
 * subscription, a request, a response, a guard condition trigger, a graph
 * change or a peer's death rings it). No polling, no timers, no ASYNCIFY.
 * When the items include deadline or liveliness events, the sleep is cut at
 * the next moment one of them can change.
 *
 * On the main thread of a pthread program, the wait also runs the calls other
 * threads proxy to the main thread (e.g. their printf), so that a thread that
 * logs while main is waiting does not deadlock.
 *
 * Must be called from a worker (every node runs in one), never from a
 * page's main thread. Not to be called concurrently on the same WaitSet.
 */
class WaitSet final
{
public:
  /// Create a wait set.
  static Result<std::shared_ptr<WaitSet>> make(std::shared_ptr<Context> context);

  /// Wait until at least one item is ready or `timeout` passes.
  /**
   * \param[in,out] items the items; `ready` is set for each on return
   * \param[in] count number of items
   * \param[in] timeout negative: forever; zero: check once without blocking
   * \return kOk when at least one item is ready, kTimeout otherwise,
   *   kInvalidArgument for a null entity
   */
  Status wait(WaitItem * items, size_t count, Timeout timeout);

  /// Same as wait(items.data(), items.size(), timeout).
  Status wait(std::vector<WaitItem> & items, Timeout timeout)
  {
    return wait(items.data(), items.size(), timeout);
  }

  ~WaitSet();

private:
  explicit WaitSet(std::shared_ptr<Context> context);

  // Keeps the context alive.
  std::shared_ptr<Context> context_;
  // Scratch array passed to the JS side (kind, handle, pointer, result per item).
  std::vector<int32_t> scratch_;
};

}  // namespace wasm_cpp

#endif  // WASM_CPP__WAIT_SET_HPP_
