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

#include "bus_abi.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

namespace wasm_cpp
{
namespace detail
{

static_assert(sizeof(wasm_bus_take_info) == 72, "wasm_bus_take_info layout is shared with JS");

std::string last_error()
{
  char buf[512];
  int n = wasm_bus_last_error(buf, sizeof(buf));
  if (n < static_cast<int>(sizeof(buf))) {
    return std::string(buf, static_cast<size_t>(n));
  }
  std::string s(static_cast<size_t>(n) + 1, '\0');
  wasm_bus_last_error(&s[0], n + 1);
  s.resize(static_cast<size_t>(n));
  return s;
}

Status bus_status(int code, const char * what)
{
  if (code == 0) {
    return Status::Ok();
  }
  std::string msg = last_error();
  if (msg.empty()) {
    msg = std::string(what) + " failed (bus code " + std::to_string(code) + ")";
  }
  Code c = Code::kError;
  switch (code) {
    case static_cast<int>(Code::kTimeout): c = Code::kTimeout; break;
    case static_cast<int>(Code::kUnsupported): c = Code::kUnsupported; break;
    case static_cast<int>(Code::kBadAlloc): c = Code::kBadAlloc; break;
    case static_cast<int>(Code::kInvalidArgument): c = Code::kInvalidArgument; break;
    case static_cast<int>(Code::kNodeNameNonExistent): c = Code::kNodeNameNonExistent; break;
    default: c = Code::kError; break;
  }
  return Status(c, msg);
}

static void put_duration(int32_t * lo, DurationNs d)
{
  uint64_t u = static_cast<uint64_t>(d < 0 ? kDurationInfinite : d);
  lo[0] = static_cast<int32_t>(static_cast<uint32_t>(u & 0xffffffffu));
  lo[1] = static_cast<int32_t>(static_cast<uint32_t>(u >> 32));
}

static DurationNs get_duration(const int32_t * lo)
{
  uint64_t u = static_cast<uint64_t>(static_cast<uint32_t>(lo[0])) |
    (static_cast<uint64_t>(static_cast<uint32_t>(lo[1])) << 32);
  return static_cast<DurationNs>(u);
}

void qos_to_wire(const QoS & qos, int32_t * w)
{
  w[0] = static_cast<int32_t>(qos.history);
  w[1] = qos.depth > 0x7fffffffu ? 0x7fffffff : static_cast<int32_t>(qos.depth);
  w[2] = static_cast<int32_t>(qos.reliability);
  w[3] = static_cast<int32_t>(qos.durability);
  w[4] = static_cast<int32_t>(qos.liveliness);
  w[5] = qos.avoid_ros_namespace_conventions ? 1 : 0;
  put_duration(&w[6], qos.deadline);
  put_duration(&w[8], qos.lifespan);
  put_duration(&w[10], qos.liveliness_lease_duration);
}

QoS qos_from_wire(const int32_t * w)
{
  QoS q;
  q.history = static_cast<History>(w[0]);
  q.depth = static_cast<size_t>(w[1]);
  q.reliability = static_cast<Reliability>(w[2]);
  q.durability = static_cast<Durability>(w[3]);
  q.liveliness = static_cast<Liveliness>(w[4]);
  q.avoid_ros_namespace_conventions = (w[5] & 1) != 0;
  q.deadline = get_duration(&w[6]);
  q.lifespan = get_duration(&w[8]);
  q.liveliness_lease_duration = get_duration(&w[10]);
  return q;
}

double timeout_ms(Timeout timeout)
{
  if (timeout.count() < 0) {
    return -1.0;
  }
  return static_cast<double>(timeout.count()) / 1e6;
}

Gid gid_from_words(const int32_t * words) noexcept
{
  Gid g;
  std::memcpy(g.data.data(), words, kGidSize);
  return g;
}

void gid_to_words(const Gid & gid, int32_t * words) noexcept
{
  std::memcpy(words, gid.data.data(), kGidSize);
}

int64_t ms_to_ns(double ms) noexcept
{
  return static_cast<int64_t>(std::llround(ms * 1e6));
}

static void * malloc_allocate(size_t size, void *)
{
  return std::malloc(size);
}

static void malloc_deallocate(void * pointer, void *)
{
  std::free(pointer);
}

const Allocator & malloc_allocator()
{
  static const Allocator a{&malloc_allocate, &malloc_deallocate, nullptr};
  return a;
}

Allocator reusing_allocator(const Message & message)
{
  Allocator a = malloc_allocator();
  a.buffer = message.data.get();
  a.capacity = message.capacity;  // take() ignores it when there is no buffer
  return a;
}

void adopt(Message * message, uint8_t * data, size_t size)
{
  if (data != message->data.get()) {
    message->data.reset(data);
    // A new buffer from malloc_allocate(): exactly the message (1 byte when empty).
    message->capacity = size > 0 ? size : 1;
  }
  message->size = size;
}

Status take(
  int ep, int mode, const Allocator & allocator, uint8_t ** data, size_t * size,
  wasm_bus_take_info * info, bool * taken, const char * what, const std::string & name)
{
  if (data == nullptr || size == nullptr || taken == nullptr || info == nullptr) {
    return Status(Code::kInvalidArgument, std::string(what) + " '" + name + "': null output argument");
  }
  if (allocator.allocate == nullptr || allocator.deallocate == nullptr) {
    return Status(
      Code::kInvalidArgument, std::string(what) + " '" + name + "': allocator without functions");
  }
  *taken = false;
  if (ep < 0) {
    return Status(
      Code::kInvalidArgument, std::string(what) + " '" + name + "': the entity was shut down");
  }
  info->data = static_cast<int32_t>(reinterpret_cast<uintptr_t>(allocator.buffer));
  info->capacity = allocator.buffer == nullptr ? 0 : static_cast<int32_t>(
    std::min<size_t>(allocator.capacity, static_cast<size_t>(INT32_MAX)));
  int r = wasm_bus_take(ep, mode, allocator.allocate, allocator.deallocate, allocator.state, info);
  if (r < 0) {
    return bus_status(-r, (std::string(what) + " '" + name + "'").c_str());
  }
  if (r == 0) {
    return Status::Ok();
  }
  *taken = true;
  *data = reinterpret_cast<uint8_t *>(static_cast<uintptr_t>(info->data));
  *size = static_cast<size_t>(info->length);
  return Status::Ok();
}

Status create_endpoint(
  int kind, const Node & node, const std::string & name, const std::string & type,
  const QoS & qos, int flags, EndpointHandle * out)
{
  static const char * const kinds[] = {"", "publisher", "subscription", "service", "client"};
  const std::string what = std::string("creating ") + kinds[kind] + " on '" + name + "'";
  if (node.handle() < 0) {
    return Status(Code::kError, what + " failed: node '" + node.name() + "' was shut down");
  }
  if (node.context()->is_shut_down()) {
    return Status(Code::kError, what + " failed: the context has been shut down");
  }
  int32_t words[kQosWords];
  qos_to_wire(qos, words);
  int32_t result[5] = {};
  size_t keep_all = node.context()->options().keep_all_depth;
  int rc = wasm_bus_endpoint_create(
    kind, node.handle(), name.c_str(), type.c_str(), words, flags,
    static_cast<int>(keep_all), result);
  if (rc != 0) {
    return bus_status(rc, what.c_str());
  }
  out->handle = result[0];
  out->gid = gid_from_words(&result[1]);
  out->qos = qos_from_wire(words);
  return Status::Ok();
}

Status destroy_endpoint(int32_t * handle, const std::string & name)
{
  if (*handle < 0) {
    return Status::Ok();
  }
  int rc = wasm_bus_endpoint_destroy(*handle);
  *handle = -1;
  return bus_status(rc, ("destroying endpoint '" + name + "'").c_str());
}

}  // namespace detail
}  // namespace wasm_cpp
