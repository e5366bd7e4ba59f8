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

#include "json.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "rosidl_typesupport_introspection_c/field_types.h"

namespace
{

using rosidl_typesupport_introspection_cpp::MessageMember;
using rosidl_typesupport_introspection_cpp::MessageMembers;

void append_quoted(std::string & out, const std::string & utf8)
{
  out += '"';
  for (unsigned char c : utf8) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof(escape), "\\u%04x", c);
      out += escape;
    } else {
      out += static_cast<char>(c);
    }
  }
  out += '"';
}

std::string utf16_to_utf8(const std::u16string & in)
{
  std::string out;
  for (size_t i = 0; i < in.size(); ++i) {
    uint32_t cp = in[i];
    if (cp >= 0xd800 && cp < 0xdc00 && i + 1 < in.size() && in[i + 1] >= 0xdc00 &&
      in[i + 1] < 0xe000)
    {
      cp = 0x10000 + ((cp - 0xd800) << 10) + (in[i + 1] - 0xdc00);
      ++i;
    }
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xc0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xe0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else {
      out += static_cast<char>(0xf0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3f));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    }
  }
  return out;
}

void append_float(std::string & out, double value)
{
  if (std::isnan(value)) {
    out += "\"NaN\"";
  } else if (std::isinf(value)) {
    out += value > 0 ? "\"Infinity\"" : "\"-Infinity\"";
  } else {
    char text[40];
    std::snprintf(text, sizeof(text), "%.17g", value);
    out += text;
  }
}

template<typename T>
T load(const uint8_t * p)
{
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

void append_message(std::string & out, const MessageMembers * members, const uint8_t * message);

// One element of a member's type at `p`.
void append_element(std::string & out, const MessageMember & member, const uint8_t * p)
{
  char text[32];
  switch (member.type_id_) {
    case rosidl_typesupport_introspection_c__ROS_TYPE_BOOLEAN:
      out += *p ? "true" : "false";
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_OCTET:
    case rosidl_typesupport_introspection_c__ROS_TYPE_UINT8:
    case rosidl_typesupport_introspection_c__ROS_TYPE_CHAR:
      out += std::to_string(static_cast<unsigned>(*p));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_INT8:
      out += std::to_string(static_cast<int>(static_cast<int8_t>(*p)));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_UINT16:
    case rosidl_typesupport_introspection_c__ROS_TYPE_WCHAR:
      out += std::to_string(load<uint16_t>(p));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_INT16:
      out += std::to_string(load<int16_t>(p));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_UINT32:
      out += std::to_string(load<uint32_t>(p));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_INT32:
      out += std::to_string(load<int32_t>(p));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_UINT64:
      std::snprintf(text, sizeof(text), "\"%" PRIu64 "\"", load<uint64_t>(p));
      out += text;
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_INT64:
      std::snprintf(text, sizeof(text), "\"%" PRId64 "\"", load<int64_t>(p));
      out += text;
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_FLOAT:
      append_float(out, load<float>(p));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_DOUBLE:
      append_float(out, load<double>(p));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_LONG_DOUBLE:
      append_float(out, static_cast<double>(load<long double>(p)));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_STRING:
      append_quoted(out, *reinterpret_cast<const std::string *>(p));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_WSTRING:
      append_quoted(out, utf16_to_utf8(*reinterpret_cast<const std::u16string *>(p)));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_MESSAGE:
      append_message(out, static_cast<const MessageMembers *>(member.members_->data), p);
      return;
    default:
      out += "null";
      return;
  }
}

size_t stride(const MessageMember & member)
{
  switch (member.type_id_) {
    case rosidl_typesupport_introspection_c__ROS_TYPE_STRING: return sizeof(std::string);
    case rosidl_typesupport_introspection_c__ROS_TYPE_WSTRING: return sizeof(std::u16string);
    case rosidl_typesupport_introspection_c__ROS_TYPE_MESSAGE:
      return static_cast<const MessageMembers *>(member.members_->data)->size_of_;
    case rosidl_typesupport_introspection_c__ROS_TYPE_FLOAT: return 4;
    case rosidl_typesupport_introspection_c__ROS_TYPE_DOUBLE: return 8;
    case rosidl_typesupport_introspection_c__ROS_TYPE_LONG_DOUBLE: return sizeof(long double);
    case rosidl_typesupport_introspection_c__ROS_TYPE_WCHAR:
    case rosidl_typesupport_introspection_c__ROS_TYPE_UINT16:
    case rosidl_typesupport_introspection_c__ROS_TYPE_INT16: return 2;
    case rosidl_typesupport_introspection_c__ROS_TYPE_UINT32:
    case rosidl_typesupport_introspection_c__ROS_TYPE_INT32: return 4;
    case rosidl_typesupport_introspection_c__ROS_TYPE_UINT64:
    case rosidl_typesupport_introspection_c__ROS_TYPE_INT64: return 8;
    default: return 1;
  }
}

void append_message(std::string & out, const MessageMembers * members, const uint8_t * message)
{
  out += '{';
  for (uint32_t i = 0; i < members->member_count_; ++i) {
    const MessageMember & member = members->members_[i];
    const uint8_t * field = message + member.offset_;
    if (i > 0) {
      out += ", ";
    }
    append_quoted(out, member.name_);
    out += ": ";
    if (!member.is_array_) {
      append_element(out, member, field);
      continue;
    }
    out += '[';
    if (member.type_id_ == rosidl_typesupport_introspection_c__ROS_TYPE_BOOLEAN &&
      !(member.array_size_ > 0 && !member.is_upper_bound_))
    {
      const auto & bits = *reinterpret_cast<const std::vector<bool> *>(field);
      for (size_t k = 0; k < bits.size(); ++k) {
        out += k > 0 ? ", " : "";
        out += bits[k] ? "true" : "false";
      }
    } else {
      const bool fixed = member.array_size_ > 0 && !member.is_upper_bound_;
      const size_t count = fixed ? member.array_size_ : member.size_function(field);
      const uint8_t * data = fixed ? field :
        (count > 0 ? static_cast<const uint8_t *>(member.get_const_function(field, 0)) : nullptr);
      for (size_t k = 0; k < count; ++k) {
        out += k > 0 ? ", " : "";
        append_element(out, member, data + k * stride(member));
      }
    }
    out += ']';
  }
  out += '}';
}

}  // namespace

std::string to_json(const MessageMembers * members, const void * message)
{
  std::string out;
  append_message(out, members, static_cast<const uint8_t *>(message));
  return out;
}
