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

#include "wasm_cpp/publisher.hpp"

#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "bus_abi.hpp"

namespace wasm_cpp
{

Result<std::shared_ptr<Publisher>> Publisher::make(
  std::shared_ptr<Node> node, const std::string & topic_name, const std::string & type_name,
  const QoS & qos, const PublisherOptions & options)
{
  if (!node) {
    return Status(Code::kInvalidArgument, "cannot create publisher on '" + topic_name + "': null node");
  }
  detail::EndpointHandle h;
  Status s = detail::create_endpoint(
    detail::kBusPublisher, *node, topic_name, type_name, qos, 0, &h);
  if (!s.ok()) {
    return s;
  }
  Timeout timeout = options.publish_timeout.count() < 0 ?
    node->context()->options().publish_timeout : options.publish_timeout;
  return std::shared_ptr<Publisher>(
    new Publisher(std::move(node), topic_name, type_name, h.qos, timeout, h.handle, h.gid));
}

Publisher::Publisher(
  std::shared_ptr<Node> node, std::string topic_name, std::string type_name,
  const QoS & qos, Timeout publish_timeout, int32_t handle, const Gid & gid)
: node_(std::move(node)), topic_name_(std::move(topic_name)), type_name_(std::move(type_name)),
  qos_(qos), publish_timeout_(publish_timeout), handle_(handle), gid_(gid)
{
}

Publisher::~Publisher()
{
  shutdown();
}

Status Publisher::publish(const void * data, size_t size)
{
  return publish(data, size, publish_timeout_);
}

Status Publisher::publish(const void * data, size_t size, Timeout timeout)
{
  if (handle_ < 0) {
    return Status(Code::kError, "publish on '" + topic_name_ + "' failed: the publisher was shut down");
  }
  if (data == nullptr && size != 0) {
    return Status(
      Code::kInvalidArgument, "publish on '" + topic_name_ + "' failed: null data with size " +
      std::to_string(size));
  }
  if (size > static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    return Status(
      Code::kBadAlloc, "publish on '" + topic_name_ + "' failed: message of " +
      std::to_string(size) + " bytes exceeds the bus maximum of " +
      std::to_string(wasm_bus_max_message()) + " bytes (Runtime option maxMessageBytes)");
  }
  int rc = wasm_bus_publish(
    handle_, data, static_cast<int>(size), detail::timeout_ms(timeout), nullptr);
  return detail::bus_status(rc, ("publish on '" + topic_name_ + "'").c_str());
}

size_t Publisher::matched_subscription_count() const
{
  if (handle_ < 0) {
    return 0;
  }
  int n = wasm_bus_matched_count(handle_);
  return n > 0 ? static_cast<size_t>(n) : 0;
}

Status Publisher::assert_liveliness()
{
  if (handle_ < 0) {
    return Status(Code::kError, "assert_liveliness on '" + topic_name_ + "': publisher shut down");
  }
  return detail::bus_status(wasm_bus_assert_liveliness(handle_), "assert_liveliness");
}

Status Publisher::wait_for_all_acked(Timeout timeout)
{
  if (handle_ < 0) {
    return Status(Code::kError, "wait_for_all_acked on '" + topic_name_ + "': publisher shut down");
  }
  int rc = wasm_bus_wait_for_acked(handle_, detail::timeout_ms(timeout));
  if (rc == static_cast<int>(Code::kTimeout)) {
    return Status(
      Code::kTimeout, "wait_for_all_acked on '" + topic_name_ +
      "' timed out: a reliable subscription has not taken every message yet");
  }
  return detail::bus_status(rc, "wait_for_all_acked");
}

Status Publisher::shutdown()
{
  return detail::destroy_endpoint(&handle_, topic_name_);
}

}  // namespace wasm_cpp
