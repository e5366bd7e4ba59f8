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

#include "detail/rmw_service_data.hpp"

#include <cstring>
#include <memory>
#include <string>
#include <utility>

#include "rmw/error_handling.h"

#include "detail/qos.hpp"
#include "detail/scratch_buffer.hpp"
#include "detail/status.hpp"

namespace rmw_wasm_cpp
{

namespace
{

void to_rmw_service_info(const wasm_cpp::ServiceInfo & info, rmw_service_info_t * out)
{
  out->source_timestamp = info.source_timestamp;
  out->received_timestamp = info.received_timestamp;
  static_assert(
    sizeof(out->request_id.writer_guid) == wasm_cpp::kGidSize,
    "a gid fills rmw_request_id_t::writer_guid");
  std::memcpy(
    out->request_id.writer_guid, info.request_id.writer_guid.data.data(), wasm_cpp::kGidSize);
  out->request_id.sequence_number = info.request_id.sequence_number;
}

// Serialize into the thread's buffer; null (rmw error set) when the message cannot be.
uint8_t * serialize(
  const MessageTypeSupport & type_support, const void * ros_message, size_t * size,
  const std::string & where)
{
  std::string error;
  if (!type_support.serialized_size(ros_message, size, &error)) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING("%s: %s", where.c_str(), error.c_str());
    return nullptr;
  }
  uint8_t * data = ScratchBuffer::for_this_thread().reserve(*size);
  if (data == nullptr) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "%s: out of memory for a %zu-byte message", where.c_str(), *size);
    return nullptr;
  }
  type_support.write(ros_message, data);
  return data;
}

// Take one request or response with `take` (a wasm_cpp take of that kind) and
// decode it into `ros_message`; `kind` and `service_name` name it in the error.
template<typename Take>
rmw_ret_t take_and_deserialize(
  Take take, const MessageTypeSupport & type_support, const char * kind,
  const std::string & service_name, rmw_service_info_t * header, void * ros_message,
  bool * taken)
{
  *taken = false;
  ScratchBuffer & buffer = ScratchBuffer::for_this_thread();
  uint8_t * data = nullptr;
  size_t size = 0;
  wasm_cpp::ServiceInfo info;
  bool got = false;
  const rmw_ret_t ret = to_rmw_ret(take(buffer.allocator(), &data, &size, &info, &got));
  if (ret != RMW_RET_OK || !got) {
    return ret;
  }
  std::string error;
  if (!type_support.deserialize(data, size, ros_message, &error)) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "dropped a malformed %s on service '%s' (request %lld): %s", kind,
      service_name.c_str(), static_cast<long long>(info.request_id.sequence_number),
      error.c_str());
    return RMW_RET_ERROR;
  }
  to_rmw_service_info(info, header);
  *taken = true;
  return RMW_RET_OK;
}

}  // namespace

ServiceData::ServiceData(
  std::shared_ptr<wasm_cpp::Service> service, std::shared_ptr<ServiceTypeSupport> type_support)
: service_(std::move(service)), type_support_(std::move(type_support))
{
}

std::shared_ptr<ServiceData> ServiceData::make(
  const std::shared_ptr<wasm_cpp::Node> & node,
  std::shared_ptr<ServiceTypeSupport> type_support,
  const char * service_name,
  const rmw_qos_profile_t & qos)
{
  auto service = wasm_cpp::Service::make(
    node, service_name, type_support->type_name(), to_wasm_qos(qos));
  if (!service.ok()) {
    to_rmw_ret(service.status());
    return nullptr;
  }
  return std::shared_ptr<ServiceData>(new ServiceData(service.value(), std::move(type_support)));
}

rmw_ret_t ServiceData::take_request(
  rmw_service_info_t * request_header, void * ros_request, bool * taken)
{
  auto take = [this](auto &&... args) {
      return service_->take_request(std::forward<decltype(args)>(args)...);
    };
  return take_and_deserialize(
    take, type_support_->request(), "request", service_->service_name(),
    request_header, ros_request, taken);
}

rmw_ret_t ServiceData::send_response(
  const rmw_request_id_t & request_id, const void * ros_response)
{
  size_t size = 0;
  uint8_t * data = serialize(
    type_support_->response(), ros_response, &size,
    "cannot send a response on service '" + service_->service_name() + "'");
  if (data == nullptr) {
    return RMW_RET_ERROR;
  }
  wasm_cpp::RequestId id;
  std::memcpy(id.writer_guid.data.data(), request_id.writer_guid, wasm_cpp::kGidSize);
  id.sequence_number = request_id.sequence_number;
  return to_rmw_ret(service_->send_response(id, data, size));
}

void ServiceData::shutdown()
{
  service_->shutdown();
}

ClientData::ClientData(
  std::shared_ptr<wasm_cpp::Client> client, std::shared_ptr<ServiceTypeSupport> type_support)
: client_(std::move(client)), type_support_(std::move(type_support))
{
}

std::shared_ptr<ClientData> ClientData::make(
  const std::shared_ptr<wasm_cpp::Node> & node,
  std::shared_ptr<ServiceTypeSupport> type_support,
  const char * service_name,
  const rmw_qos_profile_t & qos)
{
  auto client = wasm_cpp::Client::make(
    node, service_name, type_support->type_name(), to_wasm_qos(qos));
  if (!client.ok()) {
    to_rmw_ret(client.status());
    return nullptr;
  }
  return std::shared_ptr<ClientData>(new ClientData(client.value(), std::move(type_support)));
}

rmw_ret_t ClientData::send_request(const void * ros_request, int64_t * sequence_id)
{
  size_t size = 0;
  uint8_t * data = serialize(
    type_support_->request(), ros_request, &size,
    "cannot send a request on service '" + client_->service_name() + "'");
  if (data == nullptr) {
    return RMW_RET_ERROR;
  }
  return to_rmw_ret(client_->send_request(data, size, sequence_id));
}

rmw_ret_t ClientData::take_response(
  rmw_service_info_t * request_header, void * ros_response, bool * taken)
{
  auto take = [this](auto &&... args) {
      return client_->take_response(std::forward<decltype(args)>(args)...);
    };
  return take_and_deserialize(
    take, type_support_->response(), "response", client_->service_name(),
    request_header, ros_response, taken);
}

void ClientData::shutdown()
{
  client_->shutdown();
}

}  // namespace rmw_wasm_cpp
