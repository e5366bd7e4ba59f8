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

#include "detail/rmw_publisher_data.hpp"

#include <memory>
#include <string>
#include <utility>

#include "rmw/error_handling.h"

#include "detail/cdr.hpp"
#include "detail/graph.hpp"
#include "detail/qos.hpp"
#include "detail/status.hpp"

namespace rmw_wasm_cpp
{

PublisherData::PublisherData(
  std::shared_ptr<wasm_cpp::Publisher> publisher,
  std::shared_ptr<MessageTypeSupport> type_support)
: publisher_(std::move(publisher)), type_support_(std::move(type_support))
{
}

std::shared_ptr<PublisherData> PublisherData::make(
  const std::shared_ptr<wasm_cpp::Node> & node,
  std::shared_ptr<MessageTypeSupport> type_support,
  const char * topic_name,
  const rmw_qos_profile_t & qos)
{
  warn_if_topic_type_differs(
    *node->context(), topic_name, type_support->type_name(), "publisher");
  auto publisher = wasm_cpp::Publisher::make(
    node, topic_name, type_support->type_name(), to_wasm_qos(qos));
  if (!publisher.ok()) {
    to_rmw_ret(publisher.status());
    return nullptr;
  }
  return std::shared_ptr<PublisherData>(
    new PublisherData(publisher.value(), std::move(type_support)));
}

rmw_ret_t PublisherData::send(const uint8_t * data, size_t size)
{
  const size_t maximum = publisher_->node()->context()->max_message_size();
  if (size > maximum) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "cannot publish on '%s': the serialized %s is %zu bytes, over the bus maximum of "
      "%zu bytes (raise the wasm_js Runtime option maxMessageBytes)",
      publisher_->topic_name().c_str(), type_support_->type_name().c_str(), size, maximum);
    return RMW_RET_ERROR;
  }
  return to_rmw_ret(publisher_->publish(data, size));
}

rmw_ret_t PublisherData::publish(const void * ros_message, ScratchBuffer & buffer)
{
  size_t size = 0;
  std::string error;
  if (!type_support_->serialized_size(ros_message, &size, &error)) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "cannot publish on '%s': %s", publisher_->topic_name().c_str(), error.c_str());
    return RMW_RET_ERROR;
  }
  uint8_t * data = buffer.reserve(size);
  if (data == nullptr) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "cannot publish on '%s': out of memory for a %zu-byte message",
      publisher_->topic_name().c_str(), size);
    return RMW_RET_BAD_ALLOC;
  }
  type_support_->write(ros_message, data);
  return send(data, size);
}

rmw_ret_t PublisherData::publish_serialized(const rmw_serialized_message_t & message)
{
  if (message.buffer_length < cdr::kHeaderSize || message.buffer == nullptr ||
    message.buffer[0] != 0 ||
    (message.buffer[1] != cdr::kEncapsulationLittleEndian &&
    message.buffer[1] != cdr::kEncapsulationBigEndian))
  {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "cannot publish on '%s': the serialized message (%zu bytes) does not start with a "
      "CDR encapsulation header (00 01 00 00); serialize it with rmw_serialize()",
      publisher_->topic_name().c_str(), message.buffer_length);
    return RMW_RET_INVALID_ARGUMENT;
  }
  return send(message.buffer, message.buffer_length);
}

EventData * PublisherData::event(rmw_event_type_t type)
{
  return events_.get(publisher_, type, wasm_cpp::is_publisher_event, "publisher");
}

void PublisherData::shutdown()
{
  events_.clear();
  publisher_->shutdown();
}

}  // namespace rmw_wasm_cpp
