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

#ifndef LISTENER_HPP_
#define LISTENER_HPP_

#include <cstdint>
#include <map>
#include <mutex>
#include <vector>

#include "wasm_cpp/status.hpp"
#include "wasm_cpp/types.hpp"

namespace wasm_cpp
{
namespace detail
{

/// What a listener registration watches (values equal WaitItem::Kind).
enum ListenKind : int
{
  kListenSubscription = 0,
  kListenService = 1,
  kListenClient = 2,
  kListenEvent = 4,
};

/// The process' listener thread: calls the "new data" callbacks.
/**
 * Started on the first registration. It sleeps on the process doorbell
 * (like a wait set), counts what arrived since it last looked (without
 * taking anything) and calls each callback with that number. A callback is
 * never running when set() returns after clearing it.
 */
class Listener final
{
public:
  /// The process-wide instance.
  static Listener & instance();

  /// Register, replace (same *id) or, with a null callback, remove a callback.
  /**
   * \param[in,out] id registration id, 0 when none; updated
   * \return kUnsupported without pthreads
   */
  Status set(
    int32_t * id, int kind, int handle, int aux, EventCallback callback, const void * user_data);

private:
  Listener();
  void run();

  struct Entry
  {
    int kind;
    int handle;
    int aux;
    EventCallback callback;
    const void * user_data;
  };

  // Protects entries_, forget_ and started_.
  std::mutex mutex_;
  // Held while callbacks run, so that removal waits for a running callback.
  std::recursive_mutex call_mutex_;
  // Registrations by id.
  std::map<int32_t, Entry> entries_;
  // Endpoints whose listener marks the thread must drop.
  std::vector<int> forget_;
  // Next registration id.
  int32_t next_id_ = 1;
  // Whether the thread runs.
  bool started_ = false;
  // Guard-condition words the thread also waits on: [kind, triggered, seen, 0].
  alignas(16) int32_t wake_[4] = {0, 0, 0, 0};
};

}  // namespace detail
}  // namespace wasm_cpp

#endif  // LISTENER_HPP_
