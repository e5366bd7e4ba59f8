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

#ifndef WASM_CPP__TYPES_HPP_
#define WASM_CPP__TYPES_HPP_

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>

namespace wasm_cpp
{

/// Size of a gid in bytes; fits rmw_gid_t (24 bytes) and rmw_request_id_t::writer_guid (16 bytes).
constexpr size_t kGidSize = 16;

/// The globally unique id of an endpoint (publisher, subscription, service, client) or node.
/**
 * Unique on one bus for its whole lifetime (serials are never reused while
 * the bus lives). Layout (four little-endian 32-bit words): bus id, process
 * id, entity kind << 24 | registry index, serial. Compare with ==.
 */
struct Gid
{
  std::array<uint8_t, kGidSize> data{};

  bool operator==(const Gid & other) const {return data == other.data;}
  bool operator!=(const Gid & other) const {return data != other.data;}
};

/// Identifies one service request: the client's gid and the request's sequence number.
/**
 * Same meaning as rmw_request_id_t: `writer_guid` is the client's gid and
 * `sequence_number` is the number the client got from send_request().
 */
struct RequestId
{
  Gid writer_guid;
  int64_t sequence_number = 0;
};

/// Information delivered with each message (rmw_message_info_t without the implementation id).
struct MessageInfo
{
  /// When the publisher published it, nanoseconds since the Unix epoch.
  int64_t source_timestamp = 0;
  /// When it reached this subscription's history, nanoseconds since the Unix epoch.
  /**
   * On the bus a message reaches every matched subscription the moment its
   * publisher commits it to shared memory, so this equals source_timestamp
   * (as a DDS reception timestamp, it is not the time of the take).
   */
  int64_t received_timestamp = 0;
  /// The publisher's sequence number for the message, starting at 1.
  uint64_t publication_sequence_number = 0;
  /// This subscription's count of taken messages, starting at 1.
  uint64_t reception_sequence_number = 0;
  /// The publishing endpoint.
  Gid publisher_gid;
  /// True when publisher and subscription live in the same bus process.
  bool from_same_process = false;
};

/// Information delivered with each request or response (rmw_service_info_t).
struct ServiceInfo
{
  /// When the request/response was sent, nanoseconds since the Unix epoch.
  int64_t source_timestamp = 0;
  /// When it reached the server's (or client's) queue: equal to source_timestamp on the bus.
  int64_t received_timestamp = 0;
  /// The request this message is or answers.
  RequestId request_id;
};

/// Deleter for buffers obtained with std::malloc.
struct FreeDeleter
{
  void operator()(uint8_t * p) const {std::free(p);}
};

/// A message taken from the bus: bytes in a malloc'd buffer owned by the caller.
/**
 * The bytes were copied once, from the bus straight into this buffer.
 * Taking into the same Message again reuses the buffer when the next message
 * fits (`capacity` bytes), so steady traffic allocates nothing; `data` is
 * null only before the first take.
 */
struct Message
{
  std::unique_ptr<uint8_t[], FreeDeleter> data;
  size_t size = 0;
  /// Bytes `data` can hold.
  size_t capacity = 0;
};

/// An allocator in rcutils_allocator_t's shape, so that take() can write into caller memory.
/**
 * `allocate(size, state)` must return `size` writable bytes or null;
 * `deallocate(pointer, state)` releases what `allocate` returned.
 * `buffer` (optional) is memory of `capacity` bytes that take() fills without
 * calling either function when the message fits: a reused scratch buffer
 * spares an allocation and a call per message.
 */
struct Allocator
{
  void * (*allocate)(size_t size, void * state) = nullptr;
  void (* deallocate)(void * pointer, void * state) = nullptr;
  void * state = nullptr;
  uint8_t * buffer = nullptr;
  size_t capacity = 0;
};

/// A timeout: a negative value means "wait forever", zero means "do not block".
using Timeout = std::chrono::nanoseconds;

/// Wait forever.
constexpr Timeout kForever = Timeout(-1);

/// Callback type of the "new data" notifications, equal to rmw_event_callback_t.
/**
 * Called with the number of new events (messages, requests, responses or
 * status changes) since the last call. Called from the process' listener
 * thread (a pthread wasm_cpp starts when the first callback is set), never
 * while a wasm_cpp lock is held.
 */
using EventCallback = void (*)(const void * user_data, size_t number_of_events);

}  // namespace wasm_cpp

#endif  // WASM_CPP__TYPES_HPP_
