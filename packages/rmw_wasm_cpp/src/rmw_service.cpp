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

#include <memory>
#include <string>

#include "rcutils/strdup.h"
#include "rmw/allocators.h"
#include "rmw/error_handling.h"
#include "rmw/impl/cpp/macros.hpp"
#include "rmw/rmw.h"

#include "detail/api_helpers.hpp"
#include "detail/identifier.hpp"
#include "detail/qos.hpp"
#include "detail/rmw_node_data.hpp"
#include "detail/rmw_service_data.hpp"
#include "detail/status.hpp"
#include "detail/type_support.hpp"

using rmw_wasm_cpp::ClientData;
using rmw_wasm_cpp::kIdentifier;
using rmw_wasm_cpp::NodeData;
using rmw_wasm_cpp::ServiceData;

namespace
{

// The checks rmw_create_service and rmw_create_client share; null + rmw error on failure.
std::shared_ptr<rmw_wasm_cpp::ServiceTypeSupport> check_endpoint(
  const rmw_node_t * node, const rosidl_service_type_support_t * type_support,
  const char * service_name, const rmw_qos_profile_t * qos, const char * what)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, nullptr);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier, return nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(type_support, nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(service_name, nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(qos, nullptr);
  if (!rmw_wasm_cpp::check_topic_name(service_name, *qos)) {
    return nullptr;
  }
  std::string error;
  if (!rmw_wasm_cpp::is_valid_qos(*qos, &error)) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING("%s '%s': %s", what, service_name, error.c_str());
    return nullptr;
  }
  auto ts = rmw_wasm_cpp::ServiceTypeSupport::make(type_support, &error);
  if (ts == nullptr) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING("%s '%s': %s", what, service_name, error.c_str());
  }
  return ts;
}

}  // namespace

extern "C"
{

rmw_service_t * rmw_create_service(
  const rmw_node_t * node,
  const rosidl_service_type_support_t * type_support,
  const char * service_name,
  const rmw_qos_profile_t * qos_profile)
{
  auto ts = check_endpoint(node, type_support, service_name, qos_profile, "service");
  if (ts == nullptr) {
    return nullptr;
  }
  auto node_data = static_cast<NodeData *>(node->data);
  auto data = ServiceData::make(node_data->node(), ts, service_name, *qos_profile);
  if (data == nullptr) {
    return nullptr;
  }
  rmw_service_t * service = rmw_service_allocate();
  char * name_copy = rcutils_strdup(service_name, rcutils_get_default_allocator());
  if (service == nullptr || name_copy == nullptr) {
    RMW_SET_ERROR_MSG("cannot allocate an rmw service");
    rmw_service_free(service);
    rcutils_get_default_allocator().deallocate(name_copy, nullptr);
    data->shutdown();
    return nullptr;
  }
  service->implementation_identifier = kIdentifier;
  service->data = data.get();
  service->service_name = name_copy;
  node_data->add_service(service, data);
  return service;
}

rmw_ret_t rmw_destroy_service(rmw_node_t * node, rmw_service_t * service)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(service, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    service, service->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  static_cast<NodeData *>(node->data)->remove_service(service);
  rcutils_get_default_allocator().deallocate(const_cast<char *>(service->service_name), nullptr);
  rmw_service_free(service);
  return RMW_RET_OK;
}

rmw_ret_t rmw_take_request(
  const rmw_service_t * service, rmw_service_info_t * request_header, void * ros_request,
  bool * taken)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(service, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    service, service->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(request_header, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(ros_request, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(taken, RMW_RET_INVALID_ARGUMENT);
  return static_cast<ServiceData *>(service->data)->take_request(
    request_header, ros_request, taken);
}

rmw_ret_t rmw_send_response(
  const rmw_service_t * service, rmw_request_id_t * request_header, void * ros_response)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(service, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    service, service->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(request_header, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(ros_response, RMW_RET_INVALID_ARGUMENT);
  return static_cast<ServiceData *>(service->data)->send_response(*request_header, ros_response);
}

rmw_ret_t rmw_service_request_subscription_get_actual_qos(
  const rmw_service_t * service, rmw_qos_profile_t * qos)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(service, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    service, service->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(qos, RMW_RET_INVALID_ARGUMENT);
  *qos = rmw_wasm_cpp::to_rmw_qos(
    static_cast<ServiceData *>(service->data)->service().actual_qos());
  return RMW_RET_OK;
}

rmw_ret_t rmw_service_response_publisher_get_actual_qos(
  const rmw_service_t * service, rmw_qos_profile_t * qos)
{
  // Requests and responses of a service use one QoS.
  return rmw_service_request_subscription_get_actual_qos(service, qos);
}

rmw_ret_t rmw_service_set_on_new_request_callback(
  rmw_service_t * service, rmw_event_callback_t callback, const void * user_data)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(service, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    service, service->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  return rmw_wasm_cpp::to_rmw_ret(
    static_cast<ServiceData *>(service->data)->service().set_on_new_request_callback(
      callback, user_data));
}

rmw_client_t * rmw_create_client(
  const rmw_node_t * node,
  const rosidl_service_type_support_t * type_support,
  const char * service_name,
  const rmw_qos_profile_t * qos_policies)
{
  auto ts = check_endpoint(node, type_support, service_name, qos_policies, "client of service");
  if (ts == nullptr) {
    return nullptr;
  }
  auto node_data = static_cast<NodeData *>(node->data);
  auto data = ClientData::make(node_data->node(), ts, service_name, *qos_policies);
  if (data == nullptr) {
    return nullptr;
  }
  rmw_client_t * client = rmw_client_allocate();
  char * name_copy = rcutils_strdup(service_name, rcutils_get_default_allocator());
  if (client == nullptr || name_copy == nullptr) {
    RMW_SET_ERROR_MSG("cannot allocate an rmw client");
    rmw_client_free(client);
    rcutils_get_default_allocator().deallocate(name_copy, nullptr);
    data->shutdown();
    return nullptr;
  }
  client->implementation_identifier = kIdentifier;
  client->data = data.get();
  client->service_name = name_copy;
  node_data->add_client(client, data);
  return client;
}

rmw_ret_t rmw_destroy_client(rmw_node_t * node, rmw_client_t * client)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(client, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    client, client->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  static_cast<NodeData *>(node->data)->remove_client(client);
  rcutils_get_default_allocator().deallocate(const_cast<char *>(client->service_name), nullptr);
  rmw_client_free(client);
  return RMW_RET_OK;
}

rmw_ret_t rmw_send_request(
  const rmw_client_t * client, const void * ros_request, int64_t * sequence_id)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(client, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    client, client->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(ros_request, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(sequence_id, RMW_RET_INVALID_ARGUMENT);
  return static_cast<ClientData *>(client->data)->send_request(ros_request, sequence_id);
}

rmw_ret_t rmw_take_response(
  const rmw_client_t * client, rmw_service_info_t * request_header, void * ros_response,
  bool * taken)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(client, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    client, client->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(request_header, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(ros_response, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(taken, RMW_RET_INVALID_ARGUMENT);
  return static_cast<ClientData *>(client->data)->take_response(
    request_header, ros_response, taken);
}

rmw_ret_t rmw_client_request_publisher_get_actual_qos(
  const rmw_client_t * client, rmw_qos_profile_t * qos)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(client, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    client, client->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(qos, RMW_RET_INVALID_ARGUMENT);
  *qos = rmw_wasm_cpp::to_rmw_qos(static_cast<ClientData *>(client->data)->client().actual_qos());
  return RMW_RET_OK;
}

rmw_ret_t rmw_client_response_subscription_get_actual_qos(
  const rmw_client_t * client, rmw_qos_profile_t * qos)
{
  // Requests and responses of a client use one QoS.
  return rmw_client_request_publisher_get_actual_qos(client, qos);
}

rmw_ret_t rmw_client_set_on_new_response_callback(
  rmw_client_t * client, rmw_event_callback_t callback, const void * user_data)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(client, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    client, client->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  return rmw_wasm_cpp::to_rmw_ret(
    static_cast<ClientData *>(client->data)->client().set_on_new_response_callback(
      callback, user_data));
}

rmw_ret_t rmw_service_server_is_available(
  const rmw_node_t * node, const rmw_client_t * client, bool * is_available)
{
  // rmw.h: RMW_RET_ERROR (not INVALID_ARGUMENT) for a null node, client or
  // is_available, as test_rmw_implementation checks
  RMW_CHECK_ARGUMENT_FOR_NULL(node, RMW_RET_ERROR);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(client, RMW_RET_ERROR);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    client, client->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  RMW_CHECK_ARGUMENT_FOR_NULL(is_available, RMW_RET_ERROR);
  *is_available = static_cast<ClientData *>(client->data)->client().server_is_available();
  return RMW_RET_OK;
}

}  // extern "C"
