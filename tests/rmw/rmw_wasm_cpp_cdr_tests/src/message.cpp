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

#include "message.hpp"

#include <string>
#include <vector>

namespace
{

// What differs between the C and the C++ layout, for filling.
struct CLayout
{
  using Members = rosidl_typesupport_introspection_c__MessageMembers;
  using Member = rosidl_typesupport_introspection_c__MessageMember;
  struct Sequence
  {
    void * data;
    size_t size;
    size_t capacity;
  };
  static constexpr size_t kString = sizeof(rosidl_runtime_c__String);
  static constexpr size_t kWString = sizeof(rosidl_runtime_c__U16String);

  static void set_string(void * field, const std::string & value)
  {
    rosidl_runtime_c__String__assignn(
      static_cast<rosidl_runtime_c__String *>(field), value.data(), value.size());
  }
  static void set_wstring(void * field, const std::u16string & value)
  {
    rosidl_runtime_c__U16String__assignn(
      static_cast<rosidl_runtime_c__U16String *>(field),
      reinterpret_cast<const uint16_t *>(value.data()), value.size());
  }
  static uint8_t * resize(const Member & member, void * field, size_t size)
  {
    member.resize_function(field, size);
    return static_cast<uint8_t *>(static_cast<Sequence *>(field)->data);
  }
  static bool is_bool_vector(const Member &) {return false;}
  static void set_bools(void *, const std::vector<bool> &) {}
  static const Members * sub(const Member & member)
  {
    return static_cast<const Members *>(member.members_->data);
  }
};

struct CppLayout
{
  using Members = rosidl_typesupport_introspection_cpp::MessageMembers;
  using Member = rosidl_typesupport_introspection_cpp::MessageMember;
  static constexpr size_t kString = sizeof(std::string);
  static constexpr size_t kWString = sizeof(std::u16string);

  static void set_string(void * field, const std::string & value)
  {
    *static_cast<std::string *>(field) = value;
  }
  static void set_wstring(void * field, const std::u16string & value)
  {
    *static_cast<std::u16string *>(field) = value;
  }
  static uint8_t * resize(const Member & member, void * field, size_t size)
  {
    member.resize_function(field, size);
    return size == 0 ? nullptr : static_cast<uint8_t *>(member.get_function(field, 0));
  }
  static bool is_bool_vector(const Member & member)
  {
    return member.type_id_ == rosidl_typesupport_introspection_c__ROS_TYPE_BOOLEAN;
  }
  static void set_bools(void * field, const std::vector<bool> & values)
  {
    *static_cast<std::vector<bool> *>(field) = values;
  }
  static const Members * sub(const Member & member)
  {
    return static_cast<const Members *>(member.members_->data);
  }
};

size_t primitive_size(uint8_t type_id)
{
  switch (type_id) {
    case rosidl_typesupport_introspection_c__ROS_TYPE_FLOAT: return 4;
    case rosidl_typesupport_introspection_c__ROS_TYPE_DOUBLE: return 8;
    case rosidl_typesupport_introspection_c__ROS_TYPE_LONG_DOUBLE: return sizeof(long double);
    case rosidl_typesupport_introspection_c__ROS_TYPE_WCHAR: return 2;
    case rosidl_typesupport_introspection_c__ROS_TYPE_UINT16:
    case rosidl_typesupport_introspection_c__ROS_TYPE_INT16: return 2;
    case rosidl_typesupport_introspection_c__ROS_TYPE_UINT32:
    case rosidl_typesupport_introspection_c__ROS_TYPE_INT32: return 4;
    case rosidl_typesupport_introspection_c__ROS_TYPE_UINT64:
    case rosidl_typesupport_introspection_c__ROS_TYPE_INT64: return 8;
    default: return 1;
  }
}

std::string random_string(Rng & rng, size_t length)
{
  std::string out;
  while (out.size() < length) {
    if (out.size() + 2 <= length && rng.below(8) == 0) {
      out += "\xc3\xa9";  // a two-byte UTF-8 character
    } else {
      out += static_cast<char>(0x20 + rng.below(0x5f));
    }
  }
  return out;
}

std::u16string random_wstring(Rng & rng, size_t length)
{
  std::u16string out;
  for (size_t i = 0; i < length; ++i) {
    out += static_cast<char16_t>(1 + rng.below(0xfffe));
  }
  return out;
}

template<typename L>
void fill_members(
  const typename L::Members * members, uint8_t * message, Rng & rng, Lengths lengths,
  int depth);

template<typename L>
void fill_element(
  const typename L::Member & member, uint8_t * element, Rng & rng, Lengths lengths, int depth)
{
  const size_t bound = member.string_upper_bound_;
  switch (member.type_id_) {
    case rosidl_typesupport_introspection_c__ROS_TYPE_STRING:
      L::set_string(
        element, random_string(
          rng, lengths == Lengths::kMaximum && bound ? bound : rng.below(bound ? bound + 1 : 12)));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_WSTRING:
      L::set_wstring(
        element, random_wstring(
          rng, lengths == Lengths::kMaximum && bound ? bound : rng.below(bound ? bound + 1 : 6)));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_MESSAGE:
      fill_members<L>(L::sub(member), element, rng, lengths, depth + 1);
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_BOOLEAN:
      *element = static_cast<uint8_t>(rng.below(2));
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_FLOAT:
      {
        const float value = static_cast<float>(static_cast<int>(rng.below(20001)) - 10000) / 8;
        std::memcpy(element, &value, sizeof(value));
      }
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_DOUBLE:
      {
        const double value = static_cast<double>(static_cast<int64_t>(rng.next() >> 12)) / 64;
        std::memcpy(element, &value, sizeof(value));
      }
      return;
    case rosidl_typesupport_introspection_c__ROS_TYPE_LONG_DOUBLE:
      {
        const long double value = static_cast<long double>(rng.below(1000000)) / 16;
        std::memcpy(element, &value, sizeof(value));
      }
      return;
    default:
      {
        const uint64_t bits = rng.next();
        std::memcpy(element, &bits, primitive_size(member.type_id_));
      }
      return;
  }
}

template<typename L>
size_t element_size(const typename L::Member & member)
{
  switch (member.type_id_) {
    case rosidl_typesupport_introspection_c__ROS_TYPE_STRING: return L::kString;
    case rosidl_typesupport_introspection_c__ROS_TYPE_WSTRING: return L::kWString;
    case rosidl_typesupport_introspection_c__ROS_TYPE_MESSAGE: return L::sub(member)->size_of_;
    default: return primitive_size(member.type_id_);
  }
}

template<typename L>
void fill_members(
  const typename L::Members * members, uint8_t * message, Rng & rng, Lengths lengths,
  int depth)
{
  for (uint32_t i = 0; i < members->member_count_; ++i) {
    const typename L::Member & member = members->members_[i];
    uint8_t * field = message + member.offset_;
    if (!member.is_array_) {
      fill_element<L>(member, field, rng, lengths, depth);
      continue;
    }
    const size_t stride = element_size<L>(member);
    if (member.array_size_ > 0 && !member.is_upper_bound_) {
      for (size_t k = 0; k < member.array_size_; ++k) {
        fill_element<L>(member, field + k * stride, rng, lengths, depth);
      }
      continue;
    }
    size_t size;
    if (member.is_upper_bound_) {
      size = lengths == Lengths::kMaximum ? member.array_size_ : rng.below(member.array_size_ + 1);
    } else {
      size = depth > 2 ? 0 : rng.below(4);
    }
    if (L::is_bool_vector(member)) {
      std::vector<bool> values;
      for (size_t k = 0; k < size; ++k) {
        values.push_back(rng.below(2) != 0);
      }
      L::set_bools(field, values);
      continue;
    }
    uint8_t * data = L::resize(member, field, size);
    for (size_t k = 0; k < size; ++k) {
      fill_element<L>(member, data + k * stride, rng, lengths, depth);
    }
  }
}

}  // namespace

void Message::fill(Rng & rng, Lengths lengths)
{
  if (cpp_) {
    fill_members<CppLayout>(cpp_members(), static_cast<uint8_t *>(data_), rng, lengths, 0);
  } else {
    fill_members<CLayout>(c_members(), static_cast<uint8_t *>(data_), rng, lengths, 0);
  }
}
