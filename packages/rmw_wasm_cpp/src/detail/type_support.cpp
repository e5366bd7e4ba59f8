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

#include "detail/type_support.hpp"

#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "rcutils/error_handling.h"
#include "rosidl_typesupport_introspection_c/identifier.h"
#include "rosidl_typesupport_introspection_c/service_introspection.h"
#include "rosidl_typesupport_introspection_cpp/identifier.hpp"
#include "rosidl_typesupport_introspection_cpp/service_introspection.hpp"

#include "detail/cdr.hpp"
#include "detail/introspection.hpp"

namespace rmw_wasm_cpp
{

namespace
{

using CWalker = introspection::Walker<introspection::CTraits>;
using CppWalker = introspection::Walker<introspection::CppTraits>;

const rosidl_typesupport_introspection_c__MessageMembers * c_members(const void * members)
{
  return static_cast<const rosidl_typesupport_introspection_c__MessageMembers *>(members);
}

const rosidl_typesupport_introspection_cpp::MessageMembers * cpp_members(const void * members)
{
  return static_cast<const rosidl_typesupport_introspection_cpp::MessageMembers *>(members);
}

// Find the handle of `identifier` behind `type_support`, leaving no error state behind.
template<typename Handle, typename Lookup>
const Handle * find_handle(const Handle * type_support, const char * identifier, Lookup lookup)
{
  if (type_support->typesupport_identifier == identifier ||
    std::string(type_support->typesupport_identifier) == identifier)
  {
    return type_support;
  }
  const Handle * handle = lookup(type_support, identifier);
  if (handle == nullptr) {
    rcutils_reset_error();
  }
  return handle;
}

}  // namespace

std::string make_type_name(const char * namespace_, const char * name)
{
  std::string ns(namespace_ != nullptr ? namespace_ : "");
  std::string out;
  out.reserve(ns.size() + 1 + std::strlen(name));
  for (size_t i = 0; i < ns.size(); ++i) {
    if ((ns[i] == '_' || ns[i] == ':') && i + 1 < ns.size() && ns[i + 1] == ns[i]) {
      out += '/';
      ++i;
    } else {
      out += ns[i];
    }
  }
  if (!out.empty()) {
    out += '/';
  }
  out += name;
  return out;
}

MessageTypeSupport::MessageTypeSupport(const void * members, bool is_cpp, std::string type_name)
: members_(members), is_cpp_(is_cpp), type_name_(std::move(type_name))
{
}

std::shared_ptr<MessageTypeSupport> MessageTypeSupport::from_members(
  const void * members, bool is_cpp)
{
  std::string name = is_cpp ?
    make_type_name(cpp_members(members)->message_namespace_, cpp_members(members)->message_name_) :
    make_type_name(c_members(members)->message_namespace_, c_members(members)->message_name_);
  return std::shared_ptr<MessageTypeSupport>(
    new MessageTypeSupport(members, is_cpp, std::move(name)));
}

std::shared_ptr<MessageTypeSupport> MessageTypeSupport::make(
  const rosidl_message_type_support_t * type_support, std::string * error)
{
  if (type_support == nullptr) {
    *error = "message type support is null";
    return nullptr;
  }
  const rosidl_message_type_support_t * handle = find_handle(
    type_support, rosidl_typesupport_introspection_c__identifier, get_message_typesupport_handle);
  if (handle != nullptr) {
    return from_members(handle->data, false);
  }
  handle = find_handle(
    type_support, rosidl_typesupport_introspection_cpp::typesupport_identifier,
    get_message_typesupport_handle);
  if (handle != nullptr) {
    return from_members(handle->data, true);
  }
  *error = std::string("message type support '") + type_support->typesupport_identifier +
    "' offers neither rosidl_typesupport_introspection_c nor "
    "rosidl_typesupport_introspection_cpp; rmw_wasm_cpp serializes through the "
    "introspection type supports (build the interface package with "
    "rosidl_typesupport_introspection_c/cpp, as `colcon build --wasm` does)";
  return nullptr;
}

bool MessageTypeSupport::serialized_size(
  const void * ros_message, size_t * size, std::string * error) const
{
  cdr::Sizer sizer;
  auto message = static_cast<const uint8_t *>(ros_message);
  if (is_cpp_) {
    CppWalker::write(cpp_members(members_), message, sizer);
  } else {
    CWalker::write(c_members(members_), message, sizer);
  }
  if (!sizer.ok()) {
    *error = "cannot serialize " + type_name_ + ": " + sizer.failure().message();
    return false;
  }
  *size = cdr::kHeaderSize + sizer.body_size();
  return true;
}

void MessageTypeSupport::write(const void * ros_message, uint8_t * out) const
{
  cdr::Writer writer(out);
  auto message = static_cast<const uint8_t *>(ros_message);
  if (is_cpp_) {
    CppWalker::write(cpp_members(members_), message, writer);
  } else {
    CWalker::write(c_members(members_), message, writer);
  }
}

bool MessageTypeSupport::serialize(
  const void * ros_message, std::vector<uint8_t> * buffer, std::string * error) const
{
  size_t size = 0;
  if (!serialized_size(ros_message, &size, error)) {
    return false;
  }
  buffer->resize(size);
  write(ros_message, buffer->data());
  return true;
}

bool MessageTypeSupport::deserialize(
  const uint8_t * data, size_t size, void * ros_message, std::string * error) const
{
  cdr::Reader reader(data, size);
  auto message = static_cast<uint8_t *>(ros_message);
  try {
    if (reader.ok()) {
      if (is_cpp_) {
        CppWalker::read(cpp_members(members_), message, reader);
      } else {
        CWalker::read(c_members(members_), message, reader);
      }
    }
  } catch (const std::bad_alloc &) {
    reader.failure().fail("out of memory while filling the message");
  } catch (const std::length_error &) {
    reader.failure().fail("a field is too long for this platform");
  }
  if (!reader.ok()) {
    *error = "cannot deserialize " + type_name_ + " from " + std::to_string(size) +
      " bytes: " + reader.failure().message();
    return false;
  }
  return true;
}

bool MessageTypeSupport::max_serialized_size(size_t * size, std::string * error) const
{
  cdr::Failure failure;
  size_t body = 0;
  const bool bounded = is_cpp_ ?
    CppWalker::max_size(cpp_members(members_), &body, &failure) :
    CWalker::max_size(c_members(members_), &body, &failure);
  if (!bounded) {
    *error = type_name_ + " has no maximum serialized size: " + failure.message();
    return false;
  }
  *size = cdr::kHeaderSize + body;
  return true;
}

ServiceTypeSupport::ServiceTypeSupport(
  std::string type_name, std::shared_ptr<MessageTypeSupport> request,
  std::shared_ptr<MessageTypeSupport> response)
: type_name_(std::move(type_name)), request_(std::move(request)), response_(std::move(response))
{
}

std::shared_ptr<ServiceTypeSupport> ServiceTypeSupport::make(
  const rosidl_service_type_support_t * type_support, std::string * error)
{
  if (type_support == nullptr) {
    *error = "service type support is null";
    return nullptr;
  }
  const rosidl_service_type_support_t * handle = find_handle(
    type_support, rosidl_typesupport_introspection_c__identifier, get_service_typesupport_handle);
  if (handle != nullptr) {
    auto members =
      static_cast<const rosidl_typesupport_introspection_c__ServiceMembers *>(handle->data);
    return std::shared_ptr<ServiceTypeSupport>(
      new ServiceTypeSupport(
        make_type_name(members->service_namespace_, members->service_name_),
        MessageTypeSupport::from_members(members->request_members_, false),
        MessageTypeSupport::from_members(members->response_members_, false)));
  }
  handle = find_handle(
    type_support, rosidl_typesupport_introspection_cpp::typesupport_identifier,
    get_service_typesupport_handle);
  if (handle != nullptr) {
    auto members =
      static_cast<const rosidl_typesupport_introspection_cpp::ServiceMembers *>(handle->data);
    return std::shared_ptr<ServiceTypeSupport>(
      new ServiceTypeSupport(
        make_type_name(members->service_namespace_, members->service_name_),
        MessageTypeSupport::from_members(members->request_members_, true),
        MessageTypeSupport::from_members(members->response_members_, true)));
  }
  *error = std::string("service type support '") + type_support->typesupport_identifier +
    "' offers neither rosidl_typesupport_introspection_c nor "
    "rosidl_typesupport_introspection_cpp; rmw_wasm_cpp serializes through the "
    "introspection type supports";
  return nullptr;
}

}  // namespace rmw_wasm_cpp
