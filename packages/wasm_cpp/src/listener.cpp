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

#include "listener.hpp"

#include <cstdio>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bus_abi.hpp"

namespace wasm_cpp
{
namespace detail
{

Listener & Listener::instance()
{
  // Never destroyed: the thread may outlive static destruction at exit.
  static Listener * listener = new Listener();
  return *listener;
}

Listener::Listener() = default;

Status Listener::set(
  int32_t * id, int kind, int handle, int aux, EventCallback callback, const void * user_data)
{
#ifndef __EMSCRIPTEN_PTHREADS__
  (void)id;
  (void)kind;
  (void)handle;
  (void)aux;
  (void)user_data;
  if (callback == nullptr) {
    return Status::Ok();
  }
  return Status(
    Code::kUnsupported,
    "new-data callbacks need a listener thread: build with pthreads (colcon build --wasm "
    "without --wasm-no-pthread)");
#else
  std::lock_guard<std::recursive_mutex> calls(call_mutex_);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (*id != 0) {
      entries_.erase(*id);
      forget_.push_back(handle);
      *id = 0;
    }
    if (callback != nullptr) {
      *id = next_id_++;
      entries_[*id] = Entry{kind, handle, aux, callback, user_data};
    }
    if (!started_ && callback != nullptr) {
      started_ = true;
      std::thread([this]() {run();}).detach();
    }
  }
  __atomic_store_n(&wake_[1], 1, __ATOMIC_SEQ_CST);
  wasm_bus_ring_self();
  return Status::Ok();
#endif
}

void Listener::run()
{
  std::vector<int32_t> items;
  std::vector<std::pair<int32_t, Entry>> active;
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (int ep : forget_) {
        wasm_bus_listen_forget(ep);
      }
      forget_.clear();
      active.assign(entries_.begin(), entries_.end());
    }
    // Item 0 is the wake-up guard (registration changes), then one per entry.
    items.assign((active.size() + 1) * 4, 0);
    items[0] = 3;
    items[1] = static_cast<int32_t>(reinterpret_cast<uintptr_t>(wake_));
    for (size_t i = 0; i < active.size(); ++i) {
      items[(i + 1) * 4] = active[i].second.kind;
      items[(i + 1) * 4 + 1] = active[i].second.handle;
      items[(i + 1) * 4 + 2] = active[i].second.aux;
    }
    int n = wasm_bus_listen(items.data(), static_cast<int>(active.size() + 1), -1.0);
    if (n <= -100) {
      std::fprintf(
        stderr, "[ERROR] [wasm_cpp]: listener thread: %s\n", last_error().c_str());
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto & kv : active) {
        entries_.erase(kv.first);
      }
      continue;
    }
    if (n <= 0) {
      continue;
    }
    std::lock_guard<std::recursive_mutex> calls(call_mutex_);
    for (size_t i = 0; i < active.size(); ++i) {
      int32_t count = items[(i + 1) * 4 + 3];
      if (count <= 0) {
        continue;
      }
      Entry e;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = entries_.find(active[i].first);
        if (it == entries_.end()) {
          continue;  // removed meanwhile
        }
        e = it->second;
      }
      e.callback(e.user_data, static_cast<size_t>(count));
    }
  }
}

}  // namespace detail
}  // namespace wasm_cpp
