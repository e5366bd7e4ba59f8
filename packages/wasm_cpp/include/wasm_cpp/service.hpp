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

#ifndef WASM_CPP__SERVICE_HPP_
#define WASM_CPP__SERVICE_HPP_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "wasm_cpp/node.hpp"
#include "wasm_cpp/qos.hpp"
#include "wasm_cpp/status.hpp"
#include "wasm_cpp/types.hpp"

namespace wasm_cpp
{

/// A service server: takes requests (with their request ids) and sends responses.
/**
 * Requests come from the request rings of the matched clients; a response
 * goes into this server's response ring, addressed to the one client whose
 * gid is in the request id, so concurrent requests of many clients each get
 * their own response. Requests and responses are never dropped: a sender
 * blocks (up to its timeout) rather than overwrite one that was not taken.
 * Thread-safe.
 */
class Service final
{
public:
  /// Create a service server.
  /**
   * \param[in] node the owning node
   * \param[in] service_name fully qualified service name (e.g. "/add_two_ints")
   * \param[in] type_name the service type (e.g. "example_interfaces/srv/AddTwoInts")
   * \param[in] qos the QoS (services_default_qos() is typical)
   */
  static Result<std::shared_ptr<Service>> make(
    std::shared_ptr<Node> node,
    const std::string & service_name,
    const std::string & type_name,
    const QoS & qos);

  /// Take the next request.
  /**
   * \param[out] message the request bytes (set only when taken)
   * \param[out] info timestamps and the request id to answer with (when taken)
   * \param[out] taken false when no request was waiting
   */
  Status take_request(Message * message, ServiceInfo * info, bool * taken);

  /// Take the next request into memory from `allocator` (see Subscription::take).
  Status take_request(
    const Allocator & allocator, uint8_t ** data, size_t * size,
    ServiceInfo * info, bool * taken);

  /// Send the response to the request `request_id`.
  /**
   * When the client no longer exists the response is dropped and kOk is
   * returned (as with DDS). Blocks at most the context's publish timeout
   * when the response ring is full of responses not yet taken.
   */
  Status send_response(const RequestId & request_id, const void * data, size_t size);

  /// True when a take_request() would find a request now.
  bool has_request() const;

  /// The QoS in use (SYSTEM_DEFAULT resolved); same for requests and responses.
  const QoS & actual_qos() const {return qos_;}

  /// Call `callback(user_data, n)` for each batch of n new requests; null clears it.
  Status set_on_new_request_callback(EventCallback callback, const void * user_data);

  /// The server's gid.
  const Gid & gid() const {return gid_;}

  /// The service name.
  const std::string & service_name() const {return service_name_;}

  /// The type name.
  const std::string & type_name() const {return type_name_;}

  /// The owning node.
  const std::shared_ptr<Node> & node() const {return node_;}

  /// Internal: the bus handle of this server.
  int32_t handle() const {return handle_;}

  /// Remove the server from the graph. Idempotent; also done by the destructor.
  Status shutdown();

  ~Service();

private:
  Service(
    std::shared_ptr<Node> node, std::string service_name, std::string type_name,
    const QoS & qos, int32_t handle, const Gid & gid);

  // Keeps the node alive.
  std::shared_ptr<Node> node_;
  // Service and type names.
  std::string service_name_;
  std::string type_name_;
  // Resolved QoS.
  QoS qos_;
  // Bus handle, -1 after shutdown().
  int32_t handle_;
  // Server gid.
  Gid gid_;
  // Protects listener_id_.
  mutable std::mutex mutex_;
  // Listener registration id, 0 when no callback is set.
  int32_t listener_id_ = 0;
};

/// A service client: sends requests and takes the responses addressed to it.
class Client final
{
public:
  /// Create a service client (arguments as Service::make).
  static Result<std::shared_ptr<Client>> make(
    std::shared_ptr<Node> node,
    const std::string & service_name,
    const std::string & type_name,
    const QoS & qos);

  /// Send a request to every matched server.
  /**
   * \param[out] sequence_number the request's sequence number (1, 2, ...);
   *   the response's ServiceInfo::request_id carries it back
   * \return kOk, also when no server is matched yet (as with DDS, a server
   *   that appears later does not see requests sent before it matched,
   *   unless both sides use TRANSIENT_LOCAL); kTimeout when a server left
   *   earlier requests untaken for the whole publish timeout.
   */
  Status send_request(const void * data, size_t size, int64_t * sequence_number);

  /// Take the next response addressed to this client.
  Status take_response(Message * message, ServiceInfo * info, bool * taken);

  /// Take the next response into memory from `allocator` (see Subscription::take).
  Status take_response(
    const Allocator & allocator, uint8_t ** data, size_t * size,
    ServiceInfo * info, bool * taken);

  /// True when a take_response() would find a response now.
  bool has_response() const;

  /// True when at least one matched server is alive.
  bool server_is_available() const;

  /// The QoS in use (SYSTEM_DEFAULT resolved).
  const QoS & actual_qos() const {return qos_;}

  /// Call `callback(user_data, n)` for each batch of n new responses; null clears it.
  Status set_on_new_response_callback(EventCallback callback, const void * user_data);

  /// The client's gid (the writer_guid of its request ids).
  const Gid & gid() const {return gid_;}

  /// The service name.
  const std::string & service_name() const {return service_name_;}

  /// The type name.
  const std::string & type_name() const {return type_name_;}

  /// The owning node.
  const std::shared_ptr<Node> & node() const {return node_;}

  /// Internal: the bus handle of this client.
  int32_t handle() const {return handle_;}

  /// Remove the client from the graph. Idempotent; also done by the destructor.
  Status shutdown();

  ~Client();

private:
  Client(
    std::shared_ptr<Node> node, std::string service_name, std::string type_name,
    const QoS & qos, int32_t handle, const Gid & gid);

  // Keeps the node alive.
  std::shared_ptr<Node> node_;
  // Service and type names.
  std::string service_name_;
  std::string type_name_;
  // Resolved QoS.
  QoS qos_;
  // Bus handle, -1 after shutdown().
  int32_t handle_;
  // Client gid.
  Gid gid_;
  // Protects listener_id_.
  mutable std::mutex mutex_;
  // Listener registration id, 0 when no callback is set.
  int32_t listener_id_ = 0;
};

}  // namespace wasm_cpp

#endif  // WASM_CPP__SERVICE_HPP_
