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

#ifndef BUS_ABI_HPP_
#define BUS_ABI_HPP_

// The C functions of wasm_js' Emscripten library (library_wasm_bus.js).
// They return wasm_cpp::Code values unless said otherwise; the message of the
// last failure of the calling thread comes from wasm_bus_last_error().

#include <cstddef>
#include <cstdint>
#include <string>

#include "wasm_cpp/node.hpp"
#include "wasm_cpp/qos.hpp"
#include "wasm_cpp/status.hpp"
#include "wasm_cpp/types.hpp"

extern "C" {

/// What wasm_bus_take() reports about a message (layout shared with JS).
struct wasm_bus_take_info
{
  double source_ms;
  double received_ms;
  uint32_t pub_seq_lo;
  uint32_t pub_seq_hi;
  uint32_t recv_seq_lo;
  uint32_t recv_seq_hi;
  int32_t gid[4];
  uint32_t req_seq_lo;
  uint32_t req_seq_hi;
  int32_t same_process;
  /// In: the caller's buffer (0: none) and its capacity; out: where the message is, its length.
  int32_t length;
  int32_t data;
  int32_t capacity;
};

// The wasm_js library catches every JS exception and returns an error code,
// so no call unwinds: noexcept spares Emscripten's exception wrappers
// (invoke_*, a JS round trip) around each call from code with cleanups.
int wasm_bus_attached(void) noexcept;
int wasm_bus_last_error(char * buf, int cap) noexcept;
int wasm_bus_process_id(void) noexcept;
int wasm_bus_max_message(void) noexcept;
int wasm_bus_context_create(void) noexcept;
int wasm_bus_node_create(
  int domain, int context, const char * name, const char * ns, const char * enclave,
  int32_t * out) noexcept;
int wasm_bus_node_destroy(int node) noexcept;
int wasm_bus_endpoint_create(
  int kind, int node, const char * name, const char * type, int32_t * qos, int flags,
  int keep_all_depth, int32_t * out) noexcept;
int wasm_bus_endpoint_destroy(int ep) noexcept;
int wasm_bus_publish(int ep, const void * data, int len, double timeout_ms, uint32_t * seq) noexcept;
int wasm_bus_send_response(
  int ep, const int32_t * gid, uint32_t seq_lo, uint32_t seq_hi, const void * data, int len,
  double timeout_ms) noexcept;
int wasm_bus_take(
  int ep, int mode, void * (*allocate)(size_t, void *), void (* deallocate)(void *, void *),
  void * state, wasm_bus_take_info * info) noexcept;
int wasm_bus_has_data(int ep, int mode) noexcept;
int wasm_bus_matched_count(int ep) noexcept;
int wasm_bus_assert_liveliness(int ep) noexcept;
int wasm_bus_wait_for_acked(int ep, double timeout_ms) noexcept;
int wasm_bus_wait(int32_t * items, int count, double timeout_ms) noexcept;
int wasm_bus_listen(int32_t * items, int count, double timeout_ms) noexcept;
void wasm_bus_listen_forget(int ep) noexcept;
int wasm_bus_event_status(int ep, int type, int take, int32_t * status) noexcept;
void wasm_bus_ring_self(void) noexcept;
int wasm_bus_graph_version(void) noexcept;
int wasm_bus_graph(int domain, uint8_t ** out, int * out_len) noexcept;

}  // extern "C"

namespace wasm_cpp
{
namespace detail
{

/// Endpoint kinds as the bus numbers them.
enum BusKind : int
{
  kBusPublisher = 1,
  kBusSubscription = 2,
  kBusService = 3,
  kBusClient = 4,
};

/// Take modes as the bus numbers them.
enum BusTakeMode : int
{
  kTakeMessage = 0,
  kTakeRequest = 1,
  kTakeResponse = 2,
};

/// Number of int32 words of a wire QoS.
constexpr size_t kQosWords = 12;

/// The message of the calling thread's last bus failure.
std::string last_error();

/// A Status for bus code `code`, prefixed with `what` when the bus gave no message.
Status bus_status(int code, const char * what);

/// Encode a QoS into wire words.
void qos_to_wire(const QoS & qos, int32_t * words);

/// Decode wire words into a QoS.
QoS qos_from_wire(const int32_t * words);

/// A timeout in milliseconds for the bus: -1 for forever.
double timeout_ms(Timeout timeout);

/// A gid from four little-endian words.
Gid gid_from_words(const int32_t * words) noexcept;

/// Four words from a gid.
void gid_to_words(const Gid & gid, int32_t * words) noexcept;

/// Nanoseconds since the epoch from bus milliseconds.
int64_t ms_to_ns(double ms) noexcept;

/// Take one message of endpoint `ep` with `allocator`; fills `info`.
/**
 * `what` and `name` ("take on", "/chatter") only build the message of a failure.
 * \return kOk with *taken set; or the failure
 */
Status take(
  int ep, int mode, const Allocator & allocator, uint8_t ** data, size_t * size,
  wasm_bus_take_info * info, bool * taken, const char * what, const std::string & name);

/// The Allocator that uses std::malloc / std::free.
const Allocator & malloc_allocator();

/// A malloc Allocator that fills `message`'s buffer when the next message fits.
Allocator reusing_allocator(const Message & message);

/// Make `message` hold what take() returned with reusing_allocator(message).
void adopt(Message * message, uint8_t * data, size_t size);

/// What create_endpoint() returns.
struct EndpointHandle
{
  int32_t handle = -1;
  Gid gid;
  QoS qos;
};

/// Create an endpoint of `kind` on `node` (checks the node and context first).
Status create_endpoint(
  int kind, const Node & node, const std::string & name, const std::string & type,
  const QoS & qos, int flags, EndpointHandle * out);

/// Destroy an endpoint handle (if >= 0) and set it to -1.
Status destroy_endpoint(int32_t * handle, const std::string & name);

}  // namespace detail
}  // namespace wasm_cpp

#endif  // BUS_ABI_HPP_
