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

#include "wasm_cpp/wait_set.hpp"

#include <chrono>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#ifdef __EMSCRIPTEN_PTHREADS__
#include <emscripten/threading.h>
#endif

#include "bus_abi.hpp"
#include "wasm_cpp/events.hpp"
#include "wasm_cpp/guard_condition.hpp"
#include "wasm_cpp/service.hpp"
#include "wasm_cpp/subscription.hpp"

namespace wasm_cpp
{

Result<std::shared_ptr<WaitSet>> WaitSet::make(std::shared_ptr<Context> context)
{
  if (!context) {
    return Status(Code::kInvalidArgument, "cannot create wait set: null context");
  }
  return std::shared_ptr<WaitSet>(new WaitSet(std::move(context)));
}

WaitSet::WaitSet(std::shared_ptr<Context> context)
: context_(std::move(context))
{
}

WaitSet::~WaitSet() = default;

Status WaitSet::wait(WaitItem * items, size_t count, Timeout timeout)
{
  if (items == nullptr && count != 0) {
    return Status(Code::kInvalidArgument, "wait: null items");
  }
  scratch_.assign(count * 4, 0);
  for (size_t i = 0; i < count; ++i) {
    WaitItem & it = items[i];
    it.ready = false;
    if (it.entity == nullptr) {
      return Status(Code::kInvalidArgument, "wait: item " + std::to_string(i) + " has no entity");
    }
    int32_t * w = &scratch_[i * 4];
    w[0] = static_cast<int32_t>(it.kind);
    switch (it.kind) {
      case WaitItem::Kind::kSubscription:
        w[1] = static_cast<Subscription *>(it.entity)->handle();
        break;
      case WaitItem::Kind::kService:
        w[1] = static_cast<Service *>(it.entity)->handle();
        break;
      case WaitItem::Kind::kClient:
        w[1] = static_cast<Client *>(it.entity)->handle();
        break;
      case WaitItem::Kind::kGuardCondition:
        w[1] = static_cast<int32_t>(
          reinterpret_cast<uintptr_t>(static_cast<GuardCondition *>(it.entity)->state()));
        break;
      case WaitItem::Kind::kEvent: {
        auto * e = static_cast<Event *>(it.entity);
        w[1] = e->entity_handle();
        w[2] = static_cast<int32_t>(e->type());
        break;
      }
      default:
        return Status(
          Code::kInvalidArgument, "wait: item " + std::to_string(i) + " has an unknown kind");
    }
    if (it.kind != WaitItem::Kind::kGuardCondition && w[1] < 0) {
      return Status(
        Code::kInvalidArgument, "wait: item " + std::to_string(i) + " was shut down");
    }
  }

  using Clock = std::chrono::steady_clock;
  const bool forever = timeout.count() < 0;
  const Clock::time_point deadline = forever ? Clock::time_point::max() : Clock::now() + timeout;
  int r = 0;
  for (;;) {
    double ms = -1.0;
    if (!forever) {
      auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(deadline - Clock::now());
      ms = left.count() > 0 ? static_cast<double>(left.count()) / 1e6 : 0.0;
    }
    r = wasm_bus_wait(scratch_.data(), static_cast<int>(count), ms);
    if (r != -1) {
      break;
    }
    // Woken on the main thread of a pthread program: run what other threads
    // proxied to us (their printf, ...), then wait again.
#ifdef __EMSCRIPTEN_PTHREADS__
    if (emscripten_is_main_runtime_thread()) {
      emscripten_main_thread_process_queued_calls();
    }
#endif
  }
  if (r <= -100) {
    return detail::bus_status(-100 - r, "wait");
  }
  for (size_t i = 0; i < count; ++i) {
    items[i].ready = scratch_[i * 4 + 3] != 0;
  }
  if (r == 0) {
    return Status(Code::kTimeout, "wait timed out");
  }
  return Status::Ok();
}

}  // namespace wasm_cpp
