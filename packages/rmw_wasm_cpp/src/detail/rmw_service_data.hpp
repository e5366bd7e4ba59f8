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

#ifndef DETAIL__RMW_SERVICE_DATA_HPP_
#define DETAIL__RMW_SERVICE_DATA_HPP_

#include <memory>

#include "rmw/types.h"
#include "wasm_cpp/node.hpp"
#include "wasm_cpp/service.hpp"

#include "detail/type_support.hpp"

namespace rmw_wasm_cpp
{

/// The data behind an rmw_service_t: the core service server and the service type support.
class ServiceData final
{
public:
  /// Create the server on the bus; on failure returns null with the rmw error set.
  static std::shared_ptr<ServiceData> make(
    const std::shared_ptr<wasm_cpp::Node> & node,
    std::shared_ptr<ServiceTypeSupport> type_support,
    const char * service_name,
    const rmw_qos_profile_t & qos);

  /// Take the next request into `ros_request`; `*request_header` gets its id and timestamps.
  rmw_ret_t take_request(
    rmw_service_info_t * request_header, void * ros_request, bool * taken);

  /// Send `ros_response` to the client that sent the request `request_id`.
  rmw_ret_t send_response(const rmw_request_id_t & request_id, const void * ros_response);

  /// The core server.
  wasm_cpp::Service & service() const {return *service_;}

  /// Remove the server from the graph. Idempotent.
  void shutdown();

private:
  ServiceData(
    std::shared_ptr<wasm_cpp::Service> service, std::shared_ptr<ServiceTypeSupport> type_support);

  // The core server.
  std::shared_ptr<wasm_cpp::Service> service_;
  // How requests and responses are serialized.
  std::shared_ptr<ServiceTypeSupport> type_support_;
};

/// The data behind an rmw_client_t: the core client and the service type support.
class ClientData final
{
public:
  /// Create the client on the bus; on failure returns null with the rmw error set.
  static std::shared_ptr<ClientData> make(
    const std::shared_ptr<wasm_cpp::Node> & node,
    std::shared_ptr<ServiceTypeSupport> type_support,
    const char * service_name,
    const rmw_qos_profile_t & qos);

  /// Send `ros_request`; `*sequence_id` gets its sequence number.
  rmw_ret_t send_request(const void * ros_request, int64_t * sequence_id);

  /// Take the next response addressed to this client.
  rmw_ret_t take_response(
    rmw_service_info_t * request_header, void * ros_response, bool * taken);

  /// The core client.
  wasm_cpp::Client & client() const {return *client_;}

  /// Remove the client from the graph. Idempotent.
  void shutdown();

private:
  ClientData(
    std::shared_ptr<wasm_cpp::Client> client, std::shared_ptr<ServiceTypeSupport> type_support);

  // The core client.
  std::shared_ptr<wasm_cpp::Client> client_;
  // How requests and responses are serialized.
  std::shared_ptr<ServiceTypeSupport> type_support_;
};

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__RMW_SERVICE_DATA_HPP_
