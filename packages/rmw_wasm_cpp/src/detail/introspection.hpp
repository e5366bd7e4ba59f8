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

#ifndef DETAIL__INTROSPECTION_HPP_
#define DETAIL__INTROSPECTION_HPP_

/// \file
/// Walks a message through its introspection members and moves every field
/// to or from a CDR stream, in the order and with the rules of
/// rosidl_typesupport_fastrtps (Humble): fields in declaration order, nested
/// messages inline, fixed arrays without a count, sequences (bounded or not)
/// with a uint32 count, booleans as one byte 0/1, wchar as a uint32.
///
/// One template serves both layouts; the C and C++ differences (strings,
/// sequences, std::vector<bool>) are in the two Traits classes. The walk has
/// no objects with destructors and throws nothing itself, so that a build with
/// Emscripten's JS exceptions keeps its calls direct.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "rosidl_runtime_c/string.h"
#include "rosidl_runtime_c/string_functions.h"
#include "rosidl_runtime_c/u16string.h"
#include "rosidl_runtime_c/u16string_functions.h"
#include "rosidl_typesupport_introspection_c/field_types.h"
#include "rosidl_typesupport_introspection_c/message_introspection.h"
#include "rosidl_typesupport_introspection_cpp/message_introspection.hpp"

#include "detail/cdr.hpp"

namespace rmw_wasm_cpp
{
namespace introspection
{

/// The C layout (rosidl_typesupport_introspection_c).
struct CTraits
{
  using MessageMembers = rosidl_typesupport_introspection_c__MessageMembers;
  using MessageMember = rosidl_typesupport_introspection_c__MessageMember;

  /// Every C sequence has this layout.
  struct Sequence
  {
    void * data;
    size_t size;
    size_t capacity;
  };

  static constexpr size_t kStringSize = sizeof(rosidl_runtime_c__String);
  static constexpr size_t kWStringSize = sizeof(rosidl_runtime_c__U16String);
  static constexpr bool kHasVectorBool = false;

  static void get_string(const void * field, const char ** data, size_t * length)
  {
    auto s = static_cast<const rosidl_runtime_c__String *>(field);
    *data = s->data != nullptr ? s->data : "";
    *length = s->data != nullptr ? s->size : 0;
  }

  static bool set_string(void * field, const char * data, size_t length)
  {
    return rosidl_runtime_c__String__assignn(
      static_cast<rosidl_runtime_c__String *>(field), data, length);
  }

  static void get_wstring(const void * field, const uint16_t ** data, size_t * length)
  {
    auto s = static_cast<const rosidl_runtime_c__U16String *>(field);
    *data = reinterpret_cast<const uint16_t *>(s->data);
    *length = s->data != nullptr ? s->size : 0;
  }

  /// Resize a wide string to `length` units; returns where to write them, or null.
  static uint16_t * resize_wstring(void * field, size_t length)
  {
    auto s = static_cast<rosidl_runtime_c__U16String *>(field);
    if (!rosidl_runtime_c__U16String__resize(s, length)) {
      return nullptr;
    }
    return reinterpret_cast<uint16_t *>(s->data);
  }

  static size_t sequence_size(const MessageMember &, const void * field)
  {
    return static_cast<const Sequence *>(field)->size;
  }

  static const void * sequence_data(const MessageMember &, const void * field)
  {
    return static_cast<const Sequence *>(field)->data;
  }

  /// Resize a sequence (its elements are re-initialized); returns its data (the field
  /// itself when empty), or null when out of memory.
  static void * resize_sequence(const MessageMember & member, void * field, size_t size)
  {
    if (member.resize_function == nullptr || !member.resize_function(field, size)) {
      return nullptr;
    }
    // An empty sequence has no data: return the field itself, never read through.
    return size > 0 ? static_cast<Sequence *>(field)->data : field;
  }

  static const MessageMembers * sub_members(const MessageMember & member)
  {
    return static_cast<const MessageMembers *>(member.members_->data);
  }

  // Unused for C (no std::vector<bool>).
  static size_t bool_vector_size(const void *) {return 0;}
  static bool bool_vector_get(const void *, size_t) {return false;}
  static void bool_vector_resize(void *, size_t) {}
  static void bool_vector_set(void *, size_t, bool) {}
};

/// The C++ layout (rosidl_typesupport_introspection_cpp).
struct CppTraits
{
  using MessageMembers = rosidl_typesupport_introspection_cpp::MessageMembers;
  using MessageMember = rosidl_typesupport_introspection_cpp::MessageMember;

  static constexpr size_t kStringSize = sizeof(std::string);
  static constexpr size_t kWStringSize = sizeof(std::u16string);
  static constexpr bool kHasVectorBool = true;

  static void get_string(const void * field, const char ** data, size_t * length)
  {
    auto s = static_cast<const std::string *>(field);
    *data = s->data();
    *length = s->size();
  }

  static bool set_string(void * field, const char * data, size_t length)
  {
    static_cast<std::string *>(field)->assign(data, length);
    return true;
  }

  static void get_wstring(const void * field, const uint16_t ** data, size_t * length)
  {
    auto s = static_cast<const std::u16string *>(field);
    *data = reinterpret_cast<const uint16_t *>(s->data());
    *length = s->size();
  }

  static uint16_t * resize_wstring(void * field, size_t length)
  {
    auto s = static_cast<std::u16string *>(field);
    s->resize(length);
    return reinterpret_cast<uint16_t *>(&(*s)[0]);
  }

  // Sequences are std::vector<T> (BoundedVector<T, N> has the same layout):
  // the generated size/get functions give the size and the contiguous storage.
  static size_t sequence_size(const MessageMember & member, const void * field)
  {
    return member.size_function(field);
  }

  static const void * sequence_data(const MessageMember & member, const void * field)
  {
    return member.get_const_function(field, 0);
  }

  static void * resize_sequence(const MessageMember & member, void * field, size_t size)
  {
    if (member.resize_function == nullptr) {
      return nullptr;
    }
    member.resize_function(field, size);
    return size > 0 ? member.get_function(field, 0) : field;
  }

  static const MessageMembers * sub_members(const MessageMember & member)
  {
    return static_cast<const MessageMembers *>(member.members_->data);
  }

  // Sequences of booleans are std::vector<bool>: packed bits, no element addresses.
  static size_t bool_vector_size(const void * field)
  {
    return static_cast<const std::vector<bool> *>(field)->size();
  }
  static bool bool_vector_get(const void * field, size_t i)
  {
    return (*static_cast<const std::vector<bool> *>(field))[i];
  }
  static void bool_vector_resize(void * field, size_t size)
  {
    static_cast<std::vector<bool> *>(field)->resize(size);
  }
  static void bool_vector_set(void * field, size_t i, bool value)
  {
    (*static_cast<std::vector<bool> *>(field))[i] = value;
  }
};

/// Field type ids (equal in C and C++ introspection).
enum TypeId : uint8_t
{
  kFloat = rosidl_typesupport_introspection_c__ROS_TYPE_FLOAT,
  kDouble = rosidl_typesupport_introspection_c__ROS_TYPE_DOUBLE,
  kLongDouble = rosidl_typesupport_introspection_c__ROS_TYPE_LONG_DOUBLE,
  kChar = rosidl_typesupport_introspection_c__ROS_TYPE_CHAR,
  kWChar = rosidl_typesupport_introspection_c__ROS_TYPE_WCHAR,
  kBoolean = rosidl_typesupport_introspection_c__ROS_TYPE_BOOLEAN,
  kOctet = rosidl_typesupport_introspection_c__ROS_TYPE_OCTET,
  kUint8 = rosidl_typesupport_introspection_c__ROS_TYPE_UINT8,
  kInt8 = rosidl_typesupport_introspection_c__ROS_TYPE_INT8,
  kUint16 = rosidl_typesupport_introspection_c__ROS_TYPE_UINT16,
  kInt16 = rosidl_typesupport_introspection_c__ROS_TYPE_INT16,
  kUint32 = rosidl_typesupport_introspection_c__ROS_TYPE_UINT32,
  kInt32 = rosidl_typesupport_introspection_c__ROS_TYPE_INT32,
  kUint64 = rosidl_typesupport_introspection_c__ROS_TYPE_UINT64,
  kInt64 = rosidl_typesupport_introspection_c__ROS_TYPE_INT64,
  kString = rosidl_typesupport_introspection_c__ROS_TYPE_STRING,
  kWString = rosidl_typesupport_introspection_c__ROS_TYPE_WSTRING,
  kMessage = rosidl_typesupport_introspection_c__ROS_TYPE_MESSAGE,
};

/// Size in memory of a primitive field type; 0 for strings and messages.
inline size_t memory_size(uint8_t type_id)
{
  switch (type_id) {
    case kFloat: return sizeof(float);
    case kDouble: return sizeof(double);
    case kLongDouble: return sizeof(long double);
    case kChar: case kBoolean: case kOctet: case kUint8: case kInt8: return 1;
    case kWChar: return sizeof(char16_t);
    case kUint16: case kInt16: return 2;
    case kUint32: case kInt32: return 4;
    case kUint64: case kInt64: return 8;
    default: return 0;
  }
}

/// Size on the wire of a primitive field type; 0 for strings and messages.
/**
 * wchar goes out as a uint32 (Fast CDR's wchar_t); long double as 16 bytes
 * (IEEE binary128, the wasm32 long double), aligned to 8 like Fast CDR.
 */
inline size_t wire_size(uint8_t type_id)
{
  if (type_id == kWChar) {
    return 4;
  }
  if (type_id == kLongDouble) {
    return 16;
  }
  return memory_size(type_id);
}

/// The fewest bytes one element of this member can take on the wire (for count checks).
inline size_t min_wire_size(uint8_t type_id)
{
  if (type_id == kString || type_id == kWString) {
    return 4;
  }
  if (type_id == kMessage) {
    return 1;
  }
  return wire_size(type_id);
}

/// Human-readable name of a field type, for error messages.
inline const char * type_id_name(uint8_t type_id)
{
  switch (type_id) {
    case kFloat: return "float32";
    case kDouble: return "float64";
    case kLongDouble: return "long double";
    case kChar: return "char";
    case kWChar: return "wchar";
    case kBoolean: return "bool";
    case kOctet: return "byte";
    case kUint8: return "uint8";
    case kInt8: return "int8";
    case kUint16: return "uint16";
    case kInt16: return "int16";
    case kUint32: return "uint32";
    case kInt32: return "int32";
    case kUint64: return "uint64";
    case kInt64: return "int64";
    case kString: return "string";
    case kWString: return "wstring";
    case kMessage: return "message";
    default: return "unknown";
  }
}

/// Serialization (Sizer or Writer) and deserialization of one layout.
template<typename Traits>
class Walker final
{
public:
  using MessageMembers = typename Traits::MessageMembers;
  using MessageMember = typename Traits::MessageMember;

  /// Send every field of `message` to `out` (a cdr::Sizer or cdr::Writer).
  template<typename Out>
  static void write(const MessageMembers * members, const uint8_t * message, Out & out)
  {
    for (uint32_t i = 0; i < members->member_count_; ++i) {
      const MessageMember & member = members->members_[i];
      write_member(member, message + member.offset_, out);
      if (!out.ok()) {
        out.failure().add_field(member.name_);
        return;
      }
    }
  }

  /// Fill every field of `message` (initialized) from `in`.
  static void read(const MessageMembers * members, uint8_t * message, cdr::Reader & in)
  {
    for (uint32_t i = 0; i < members->member_count_; ++i) {
      const MessageMember & member = members->members_[i];
      read_member(member, message + member.offset_, in);
      if (!in.ok()) {
        in.failure().add_field(member.name_);
        return;
      }
    }
  }

  /// An upper bound of the stream body size, or false when a field is unbounded.
  static bool max_size(const MessageMembers * members, size_t * size, cdr::Failure * failure)
  {
    for (uint32_t i = 0; i < members->member_count_; ++i) {
      const MessageMember & member = members->members_[i];
      size_t count = 1;
      if (member.is_array_) {
        if (member.array_size_ == 0) {
          failure->fail("unbounded sequence: no maximum serialized size");
          failure->add_field(member.name_);
          return false;
        }
        count = member.array_size_;
        if (member.is_upper_bound_) {
          *size += 4 + 3;  // count and its worst-case padding
        }
      }
      size_t element = 0;
      if (member.type_id_ == kString || member.type_id_ == kWString) {
        if (member.string_upper_bound_ == 0) {
          failure->fail("unbounded string: no maximum serialized size");
          failure->add_field(member.name_);
          return false;
        }
        element = 4 + 3 + (member.type_id_ == kString ?
          member.string_upper_bound_ + 1 : 4 * member.string_upper_bound_);
      } else if (member.type_id_ == kMessage) {
        if (!max_size(Traits::sub_members(member), &element, failure)) {
          failure->add_field(member.name_);
          return false;
        }
      } else {
        const size_t wire = wire_size(member.type_id_);
        element = wire + (wire > 8 ? 7 : wire - 1);
      }
      *size += count * element;
    }
    return true;
  }

private:
  template<typename Out>
  static void write_member(const MessageMember & member, const uint8_t * field, Out & out)
  {
    if (!member.is_array_) {
      write_elements(member, field, 1, out);
      return;
    }
    if (member.array_size_ > 0 && !member.is_upper_bound_) {
      write_elements(member, field, member.array_size_, out);
      return;
    }
    const bool bools = Traits::kHasVectorBool && member.type_id_ == kBoolean;
    const size_t size = bools ?
      Traits::bool_vector_size(field) : Traits::sequence_size(member, field);
    if (member.is_upper_bound_ && size > member.array_size_) {
      out.failure().fail(
        "sequence of " + std::to_string(size) + " elements exceeds its bound of " +
        std::to_string(member.array_size_));
      return;
    }
    out.uint32(static_cast<uint32_t>(size));
    if (size == 0) {
      return;
    }
    if (bools) {
      for (size_t i = 0; i < size; ++i) {
        out.boolean(Traits::bool_vector_get(field, i));
      }
      return;
    }
    write_elements(
      member, static_cast<const uint8_t *>(Traits::sequence_data(member, field)), size, out);
  }

  // Write `count` contiguous elements of the member's type starting at `data`.
  template<typename Out>
  static void write_elements(
    const MessageMember & member, const uint8_t * data, size_t count, Out & out)
  {
    switch (member.type_id_) {
      case kBoolean:
        for (size_t i = 0; i < count; ++i) {
          out.boolean(data[i] != 0);
        }
        return;
      case kWChar:
        for (size_t i = 0; i < count; ++i) {
          char16_t unit;
          std::memcpy(&unit, data + i * sizeof(char16_t), sizeof(unit));
          const uint32_t wide = unit;
          out.primitive(&wide, 4);
        }
        return;
      case kString:
        for (size_t i = 0; i < count; ++i) {
          const char * chars;
          size_t length;
          Traits::get_string(data + i * Traits::kStringSize, &chars, &length);
          if (member.string_upper_bound_ > 0 && length > member.string_upper_bound_) {
            out.failure().fail(
              "string of " + std::to_string(length) + " characters exceeds its bound of " +
              std::to_string(member.string_upper_bound_));
            if (count > 1 || member.is_array_) {out.failure().add_index(i);}
            return;
          }
          out.string(chars, length);
        }
        return;
      case kWString:
        for (size_t i = 0; i < count; ++i) {
          const uint16_t * units;
          size_t length;
          Traits::get_wstring(data + i * Traits::kWStringSize, &units, &length);
          if (member.string_upper_bound_ > 0 && length > member.string_upper_bound_) {
            out.failure().fail(
              "wide string of " + std::to_string(length) + " characters exceeds its bound of " +
              std::to_string(member.string_upper_bound_));
            if (count > 1 || member.is_array_) {out.failure().add_index(i);}
            return;
          }
          out.wstring(units, length);
        }
        return;
      case kMessage:
        {
          const MessageMembers * sub = Traits::sub_members(member);
          for (size_t i = 0; i < count; ++i) {
            write(sub, data + i * sub->size_of_, out);
            if (!out.ok()) {
              if (member.is_array_) {out.failure().add_index(i);}
              return;
            }
          }
        }
        return;
      default:
        {
          const size_t size = wire_size(member.type_id_);
          if (size == 0) {
            out.failure().fail(
              "unknown field type id " + std::to_string(member.type_id_));
            return;
          }
          out.primitives(data, size, count);
        }
        return;
    }
  }

  static void read_member(const MessageMember & member, uint8_t * field, cdr::Reader & in)
  {
    if (!member.is_array_) {
      read_elements(member, field, 1, in);
      return;
    }
    if (member.array_size_ > 0 && !member.is_upper_bound_) {
      read_elements(member, field, member.array_size_, in);
      return;
    }
    const size_t size = in.count(min_wire_size(member.type_id_));
    if (!in.ok()) {
      return;
    }
    if (member.is_upper_bound_ && size > member.array_size_) {
      in.failure().fail(
        "sequence of " + std::to_string(size) + " elements exceeds its bound of " +
        std::to_string(member.array_size_));
      return;
    }
    if (Traits::kHasVectorBool && member.type_id_ == kBoolean) {
      Traits::bool_vector_resize(field, size);
      for (size_t i = 0; i < size; ++i) {
        Traits::bool_vector_set(field, i, in.boolean());
      }
      return;
    }
    auto data = static_cast<uint8_t *>(Traits::resize_sequence(member, field, size));
    if (data == nullptr) {
      in.failure().fail("cannot allocate a sequence of " + std::to_string(size) + " elements");
      return;
    }
    if (size > 0) {
      read_elements(member, data, size, in);
    }
  }

  // Read `count` contiguous elements of the member's type into `data`.
  static void read_elements(
    const MessageMember & member, uint8_t * data, size_t count, cdr::Reader & in)
  {
    switch (member.type_id_) {
      case kBoolean:
        for (size_t i = 0; i < count; ++i) {
          const bool value = in.boolean();
          std::memcpy(data + i, &value, 1);
        }
        return;
      case kWChar:
        for (size_t i = 0; i < count; ++i) {
          uint32_t wide = 0;
          in.primitive(&wide, 4);
          const char16_t unit = static_cast<char16_t>(wide);
          std::memcpy(data + i * sizeof(char16_t), &unit, sizeof(unit));
        }
        return;
      case kString:
        for (size_t i = 0; i < count && in.ok(); ++i) {
          const char * chars;
          size_t length;
          in.string(&chars, &length);
          if (!in.ok()) {
            return;
          }
          if (member.string_upper_bound_ > 0 && length > member.string_upper_bound_) {
            in.failure().fail(
              "string of " + std::to_string(length) + " characters exceeds its bound of " +
              std::to_string(member.string_upper_bound_));
            return;
          }
          if (!Traits::set_string(data + i * Traits::kStringSize, chars, length)) {
            in.failure().fail("cannot allocate a string of " + std::to_string(length) + " bytes");
            return;
          }
        }
        return;
      case kWString:
        for (size_t i = 0; i < count && in.ok(); ++i) {
          const size_t length = in.wstring_length();
          if (!in.ok()) {
            return;
          }
          if (member.string_upper_bound_ > 0 && length > member.string_upper_bound_) {
            in.failure().fail(
              "wide string of " + std::to_string(length) + " characters exceeds its bound of " +
              std::to_string(member.string_upper_bound_));
            return;
          }
          uint16_t * units = Traits::resize_wstring(data + i * Traits::kWStringSize, length);
          if (units == nullptr) {
            in.failure().fail(
              "cannot allocate a wide string of " + std::to_string(length) + " characters");
            return;
          }
          for (size_t u = 0; u < length; ++u) {
            units[u] = in.wstring_unit();
          }
        }
        return;
      case kMessage:
        {
          const MessageMembers * sub = Traits::sub_members(member);
          for (size_t i = 0; i < count; ++i) {
            read(sub, data + i * sub->size_of_, in);
            if (!in.ok()) {
              if (member.is_array_) {in.failure().add_index(i);}
              return;
            }
          }
        }
        return;
      default:
        {
          const size_t size = wire_size(member.type_id_);
          if (size == 0) {
            in.failure().fail("unknown field type id " + std::to_string(member.type_id_));
            return;
          }
          in.primitives(data, size, count);
        }
        return;
    }
  }
};

}  // namespace introspection
}  // namespace rmw_wasm_cpp

#endif  // DETAIL__INTROSPECTION_HPP_
