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

#include "detail/api_helpers.hpp"

#include <memory>
#include <string>

#include "rmw/error_handling.h"
#include "rmw/impl/cpp/macros.hpp"
#include "rmw/validate_full_topic_name.h"

#include "detail/identifier.hpp"
#include "detail/type_support.hpp"

namespace rmw_wasm_cpp
{

/// Check a topic name as rmw_create_publisher/subscription must; sets the rmw error.
bool check_topic_name(const char * topic_name, const rmw_qos_profile_t & qos)
{
  if (topic_name[0] == '\0') {
    RMW_SET_ERROR_MSG("invalid topic name: the name is empty");
    return false;
  }
  if (qos.avoid_ros_namespace_conventions) {
    return true;
  }
  int validation_result = RMW_TOPIC_VALID;
  size_t invalid_index = 0;
  if (rmw_validate_full_topic_name(topic_name, &validation_result, &invalid_index) != RMW_RET_OK) {
    return false;
  }
  if (validation_result != RMW_TOPIC_VALID) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "invalid topic name '%s': %s (at character %zu)", topic_name,
      rmw_full_topic_name_validation_result_string(validation_result), invalid_index);
    return false;
  }
  return true;
}

bool check_network_flow_requirement(
  rmw_unique_network_flow_endpoints_requirement_t requirement, const char * what,
  const char * topic_name)
{
  if (requirement != RMW_UNIQUE_NETWORK_FLOW_ENDPOINTS_STRICTLY_REQUIRED) {
    return true;
  }
  RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
    "cannot create a %s on '%s' that strictly requires unique network flow endpoints: "
    "rmw_wasm_cpp nodes talk through shared memory and have no network flows (use "
    "RMW_UNIQUE_NETWORK_FLOW_ENDPOINTS_OPTIONALLY_REQUIRED or NOT_REQUIRED)", what, topic_name);
  return false;
}

/// The scratch buffer of an allocation made by rmw_init_*_allocation, or the thread's.
ScratchBuffer & buffer_of(const char * implementation_identifier, void * data)
{
  if (implementation_identifier == kIdentifier && data != nullptr) {
    return *static_cast<ScratchBuffer *>(data);
  }
  return ScratchBuffer::for_this_thread();
}

/// Preallocate a buffer for the messages of a type (bounded types: their maximum size).
rmw_ret_t init_allocation(
  const rosidl_message_type_support_t * type_support, const char ** identifier, void ** data)
{
  std::string error;
  auto ts = MessageTypeSupport::make(type_support, &error);
  if (ts == nullptr) {
    RMW_SET_ERROR_MSG(error.c_str());
    return RMW_RET_INVALID_ARGUMENT;
  }
  std::unique_ptr<ScratchBuffer> buffer(new ScratchBuffer());
  size_t size = 0;
  if (ts->max_serialized_size(&size, &error) && buffer->reserve(size) == nullptr) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "cannot preallocate %zu bytes for %s", size, ts->type_name().c_str());
    return RMW_RET_BAD_ALLOC;
  }
  *identifier = kIdentifier;
  *data = buffer.release();
  return RMW_RET_OK;
}

/// Release what init_allocation made.
rmw_ret_t fini_allocation(const char ** identifier, void ** data)
{
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    allocation, *identifier, kIdentifier, return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  delete static_cast<ScratchBuffer *>(*data);
  *data = nullptr;
  *identifier = nullptr;
  return RMW_RET_OK;
}

}  // namespace rmw_wasm_cpp
