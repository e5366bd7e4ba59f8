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

#ifndef DETAIL__TYPE_SUPPORT_HPP_
#define DETAIL__TYPE_SUPPORT_HPP_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rosidl_runtime_c/message_type_support_struct.h"
#include "rosidl_runtime_c/service_type_support_struct.h"

namespace rmw_wasm_cpp
{

/// One message type, seen through its introspection type support (C or C++), and its CDR.
/**
 * Serializes a ROS message of that type to a CDR stream byte-identical to
 * rmw_fastrtps_cpp's, and back. Immutable after creation; thread-safe.
 */
class MessageTypeSupport final
{
public:
  /// The introspection type support behind `type_support` (C preferred, then C++).
  /**
   * \return the type support, or null with `*error` saying what was looked for
   */
  static std::shared_ptr<MessageTypeSupport> make(
    const rosidl_message_type_support_t * type_support, std::string * error);

  /// A type support for introspection members (C when `is_cpp` is false).
  static std::shared_ptr<MessageTypeSupport> from_members(const void * members, bool is_cpp);

  /// The ROS type name, e.g. "std_msgs/msg/String".
  const std::string & type_name() const {return type_name_;}

  /// True for a C++ (rosidl_typesupport_introspection_cpp) message layout.
  bool is_cpp() const {return is_cpp_;}

  /// The introspection members (rosidl_typesupport_introspection_c(pp) MessageMembers).
  const void * members() const {return members_;}

  /// Compute the size of the CDR stream (header included) of `ros_message`.
  /**
   * \return false, with `*error` naming the field, when the message cannot be
   *   serialized (a bounded string or sequence over its bound)
   */
  bool serialized_size(const void * ros_message, size_t * size, std::string * error) const;

  /// Write the CDR stream of `ros_message` into `out`, which holds serialized_size() bytes.
  void write(const void * ros_message, uint8_t * out) const;

  /// Serialize `ros_message` into `buffer`, resized to the stream's size.
  bool serialize(
    const void * ros_message, std::vector<uint8_t> * buffer, std::string * error) const;

  /// Fill `ros_message` (an initialized message of this type) from a CDR stream.
  /**
   * Every read is checked against the end of the stream; counts are checked
   * against what remains before anything is allocated.
   * \return false, with `*error` saying which field and byte, for a malformed
   *   stream (the message is then in a valid but unspecified state)
   */
  bool deserialize(
    const uint8_t * data, size_t size, void * ros_message, std::string * error) const;

  /// The largest CDR stream a message of this type can have.
  /**
   * \return false, with `*error` naming the unbounded field, when there is no maximum
   */
  bool max_serialized_size(size_t * size, std::string * error) const;

private:
  MessageTypeSupport(const void * members, bool is_cpp, std::string type_name);

  // rosidl_typesupport_introspection_c(pp) MessageMembers.
  const void * members_;
  // Which layout members_ describes.
  bool is_cpp_;
  // "pkg/msg/Type".
  std::string type_name_;
};

/// A service type: the name and the request and response message type supports.
class ServiceTypeSupport final
{
public:
  /// The introspection type support behind `type_support` (C preferred, then C++).
  static std::shared_ptr<ServiceTypeSupport> make(
    const rosidl_service_type_support_t * type_support, std::string * error);

  /// The ROS type name, e.g. "example_interfaces/srv/AddTwoInts".
  const std::string & type_name() const {return type_name_;}

  /// The request message.
  const MessageTypeSupport & request() const {return *request_;}

  /// The response message.
  const MessageTypeSupport & response() const {return *response_;}

private:
  ServiceTypeSupport(
    std::string type_name, std::shared_ptr<MessageTypeSupport> request,
    std::shared_ptr<MessageTypeSupport> response);

  // "pkg/srv/Type".
  std::string type_name_;
  // Request and response.
  std::shared_ptr<MessageTypeSupport> request_;
  std::shared_ptr<MessageTypeSupport> response_;
};

/// Turn an introspection namespace and name ("std_msgs__msg" or "std_msgs::msg", "String")
/// into a ROS type name ("std_msgs/msg/String").
std::string make_type_name(const char * namespace_, const char * name);

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__TYPE_SUPPORT_HPP_
