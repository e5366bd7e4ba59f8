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

#include <string>

#include "rcutils/types/uint8_array.h"
#include "rmw/error_handling.h"
#include "rmw/rmw.h"

#include "detail/identifier.hpp"
#include "detail/type_support.hpp"

using rmw_wasm_cpp::MessageTypeSupport;

extern "C"
{

const char * rmw_get_serialization_format(void)
{
  return rmw_wasm_cpp::kSerializationFormat;
}

rmw_ret_t rmw_serialize(
  const void * ros_message, const rosidl_message_type_support_t * type_support,
  rmw_serialized_message_t * serialized_message)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(ros_message, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(type_support, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(serialized_message, RMW_RET_INVALID_ARGUMENT);
  std::string error;
  auto ts = MessageTypeSupport::make(type_support, &error);
  if (ts == nullptr) {
    RMW_SET_ERROR_MSG(error.c_str());
    return RMW_RET_ERROR;
  }
  size_t size = 0;
  if (!ts->serialized_size(ros_message, &size, &error)) {
    RMW_SET_ERROR_MSG(error.c_str());
    return RMW_RET_ERROR;
  }
  if (serialized_message->buffer_capacity < size &&
    rcutils_uint8_array_resize(serialized_message, size) != RCUTILS_RET_OK)
  {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "cannot grow the serialized message to %zu bytes for %s", size, ts->type_name().c_str());
    return RMW_RET_BAD_ALLOC;
  }
  ts->write(ros_message, serialized_message->buffer);
  serialized_message->buffer_length = size;
  return RMW_RET_OK;
}

rmw_ret_t rmw_deserialize(
  const rmw_serialized_message_t * serialized_message,
  const rosidl_message_type_support_t * type_support, void * ros_message)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(serialized_message, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(type_support, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(ros_message, RMW_RET_INVALID_ARGUMENT);
  std::string error;
  auto ts = MessageTypeSupport::make(type_support, &error);
  if (ts == nullptr) {
    RMW_SET_ERROR_MSG(error.c_str());
    return RMW_RET_ERROR;
  }
  if (!ts->deserialize(
      serialized_message->buffer, serialized_message->buffer_length, ros_message, &error))
  {
    RMW_SET_ERROR_MSG(error.c_str());
    return RMW_RET_ERROR;
  }
  return RMW_RET_OK;
}

rmw_ret_t rmw_get_serialized_message_size(
  const rosidl_message_type_support_t * type_support,
  const rosidl_runtime_c__Sequence__bound * message_bounds, size_t * size)
{
  (void)message_bounds;  // Humble's bounds type carries no sizes
  RMW_CHECK_ARGUMENT_FOR_NULL(type_support, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_ARGUMENT_FOR_NULL(size, RMW_RET_INVALID_ARGUMENT);
  std::string error;
  auto ts = MessageTypeSupport::make(type_support, &error);
  if (ts == nullptr) {
    RMW_SET_ERROR_MSG(error.c_str());
    return RMW_RET_ERROR;
  }
  if (!ts->max_serialized_size(size, &error)) {
    RMW_SET_ERROR_MSG(error.c_str());
    return RMW_RET_ERROR;
  }
  return RMW_RET_OK;
}

}  // extern "C"
