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

#include "wasm_cpp/service.hpp"

#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "bus_abi.hpp"
#include "listener.hpp"

namespace wasm_cpp
{

namespace
{

void fill_service_info(const wasm_bus_take_info & ti, ServiceInfo * info)
{
  if (info == nullptr) {
    return;
  }
  info->source_timestamp = detail::ms_to_ns(ti.source_ms);
  info->received_timestamp = detail::ms_to_ns(ti.received_ms);
  info->request_id.writer_guid = detail::gid_from_words(ti.gid);
  info->request_id.sequence_number = static_cast<int64_t>(
    (static_cast<uint64_t>(ti.req_seq_hi) << 32) | ti.req_seq_lo);
}

Status check_payload(const void * data, size_t size, const std::string & what)
{
  if (data == nullptr && size != 0) {
    return Status(
      Code::kInvalidArgument, what + " failed: null data with size " + std::to_string(size));
  }
  if (size > static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    return Status(
      Code::kBadAlloc, what + " failed: message of " + std::to_string(size) +
      " bytes exceeds the bus maximum of " + std::to_string(wasm_bus_max_message()) +
      " bytes (Runtime option maxMessageBytes)");
  }
  return Status::Ok();
}

}  // namespace

// ---------------------------------------------------------------- Service

Result<std::shared_ptr<Service>> Service::make(
  std::shared_ptr<Node> node, const std::string & service_name, const std::string & type_name,
  const QoS & qos)
{
  if (!node) {
    return Status(
      Code::kInvalidArgument, "cannot create service '" + service_name + "': null node");
  }
  detail::EndpointHandle h;
  Status s = detail::create_endpoint(
    detail::kBusService, *node, service_name, type_name, qos, 0, &h);
  if (!s.ok()) {
    return s;
  }
  return std::shared_ptr<Service>(
    new Service(std::move(node), service_name, type_name, h.qos, h.handle, h.gid));
}

Service::Service(
  std::shared_ptr<Node> node, std::string service_name, std::string type_name,
  const QoS & qos, int32_t handle, const Gid & gid)
: node_(std::move(node)), service_name_(std::move(service_name)),
  type_name_(std::move(type_name)), qos_(qos), handle_(handle), gid_(gid)
{
}

Service::~Service()
{
  shutdown();
}

Status Service::take_request(Message * message, ServiceInfo * info, bool * taken)
{
  if (message == nullptr) {
    return Status(Code::kInvalidArgument, "take_request on '" + service_name_ + "': null message");
  }
  uint8_t * data = nullptr;
  size_t size = 0;
  Status s = take_request(detail::reusing_allocator(*message), &data, &size, info, taken);
  if (s.ok() && *taken) {
    detail::adopt(message, data, size);
  }
  return s;
}

Status Service::take_request(
  const Allocator & allocator, uint8_t ** data, size_t * size, ServiceInfo * info, bool * taken)
{
  wasm_bus_take_info ti;
  Status s = detail::take(
    handle_, detail::kTakeRequest, allocator, data, size, &ti, taken, "take_request on",
    service_name_);
  if (s.ok() && *taken) {
    fill_service_info(ti, info);
  }
  return s;
}

Status Service::send_response(const RequestId & request_id, const void * data, size_t size)
{
  if (handle_ < 0 || (data == nullptr && size != 0) ||
    size > static_cast<size_t>(std::numeric_limits<int32_t>::max()))
  {
    const std::string what = "send_response on '" + service_name_ + "'";
    if (handle_ < 0) {
      return Status(Code::kError, what + " failed: the service was shut down");
    }
    return check_payload(data, size, what);
  }
  int32_t gid[4];
  detail::gid_to_words(request_id.writer_guid, gid);
  uint64_t seq = static_cast<uint64_t>(request_id.sequence_number);
  int rc = wasm_bus_send_response(
    handle_, gid, static_cast<uint32_t>(seq & 0xffffffffu), static_cast<uint32_t>(seq >> 32),
    data, static_cast<int>(size),
    detail::timeout_ms(node_->context()->options().publish_timeout));
  if (rc == 0) {
    return Status::Ok();
  }
  return detail::bus_status(rc, ("send_response on '" + service_name_ + "'").c_str());
}

bool Service::has_request() const
{
  return handle_ >= 0 && wasm_bus_has_data(handle_, detail::kTakeRequest) == 1;
}

Status Service::set_on_new_request_callback(EventCallback callback, const void * user_data)
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (handle_ < 0) {
    return Status(Code::kError, "set_on_new_request_callback: service was shut down");
  }
  return detail::Listener::instance().set(
    &listener_id_, detail::kListenService, handle_, 0, callback, user_data);
}

Status Service::shutdown()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (listener_id_ != 0) {
      detail::Listener::instance().set(&listener_id_, 0, handle_, 0, nullptr, nullptr);
    }
  }
  return detail::destroy_endpoint(&handle_, service_name_);
}

// ---------------------------------------------------------------- Client

Result<std::shared_ptr<Client>> Client::make(
  std::shared_ptr<Node> node, const std::string & service_name, const std::string & type_name,
  const QoS & qos)
{
  if (!node) {
    return Status(
      Code::kInvalidArgument, "cannot create client of '" + service_name + "': null node");
  }
  detail::EndpointHandle h;
  Status s = detail::create_endpoint(
    detail::kBusClient, *node, service_name, type_name, qos, 0, &h);
  if (!s.ok()) {
    return s;
  }
  return std::shared_ptr<Client>(
    new Client(std::move(node), service_name, type_name, h.qos, h.handle, h.gid));
}

Client::Client(
  std::shared_ptr<Node> node, std::string service_name, std::string type_name,
  const QoS & qos, int32_t handle, const Gid & gid)
: node_(std::move(node)), service_name_(std::move(service_name)),
  type_name_(std::move(type_name)), qos_(qos), handle_(handle), gid_(gid)
{
}

Client::~Client()
{
  shutdown();
}

Status Client::send_request(const void * data, size_t size, int64_t * sequence_number)
{
  if (handle_ < 0 || sequence_number == nullptr || (data == nullptr && size != 0) ||
    size > static_cast<size_t>(std::numeric_limits<int32_t>::max()))
  {
    const std::string what = "send_request on '" + service_name_ + "'";
    if (handle_ < 0) {
      return Status(Code::kError, what + " failed: the client was shut down");
    }
    if (sequence_number == nullptr) {
      return Status(Code::kInvalidArgument, what + " failed: null sequence_number");
    }
    return check_payload(data, size, what);
  }
  uint32_t seq[2] = {0, 0};
  int rc = wasm_bus_publish(
    handle_, data, static_cast<int>(size),
    detail::timeout_ms(node_->context()->options().publish_timeout), seq);
  if (rc != 0) {
    return detail::bus_status(rc, ("send_request on '" + service_name_ + "'").c_str());
  }
  *sequence_number = static_cast<int64_t>((static_cast<uint64_t>(seq[1]) << 32) | seq[0]);
  return Status::Ok();
}

Status Client::take_response(Message * message, ServiceInfo * info, bool * taken)
{
  if (message == nullptr) {
    return Status(
      Code::kInvalidArgument, "take_response on '" + service_name_ + "': null message");
  }
  uint8_t * data = nullptr;
  size_t size = 0;
  Status s = take_response(detail::reusing_allocator(*message), &data, &size, info, taken);
  if (s.ok() && *taken) {
    detail::adopt(message, data, size);
  }
  return s;
}

Status Client::take_response(
  const Allocator & allocator, uint8_t ** data, size_t * size, ServiceInfo * info, bool * taken)
{
  wasm_bus_take_info ti;
  Status s = detail::take(
    handle_, detail::kTakeResponse, allocator, data, size, &ti, taken, "take_response on",
    service_name_);
  if (s.ok() && *taken) {
    fill_service_info(ti, info);
  }
  return s;
}

bool Client::has_response() const
{
  return handle_ >= 0 && wasm_bus_has_data(handle_, detail::kTakeResponse) == 1;
}

bool Client::server_is_available() const
{
  return handle_ >= 0 && wasm_bus_matched_count(handle_) > 0;
}

Status Client::set_on_new_response_callback(EventCallback callback, const void * user_data)
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (handle_ < 0) {
    return Status(Code::kError, "set_on_new_response_callback: client was shut down");
  }
  return detail::Listener::instance().set(
    &listener_id_, detail::kListenClient, handle_, 0, callback, user_data);
}

Status Client::shutdown()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (listener_id_ != 0) {
      detail::Listener::instance().set(&listener_id_, 0, handle_, 0, nullptr, nullptr);
    }
  }
  return detail::destroy_endpoint(&handle_, service_name_);
}

}  // namespace wasm_cpp
