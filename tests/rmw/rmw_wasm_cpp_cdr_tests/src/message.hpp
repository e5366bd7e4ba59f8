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

#ifndef MESSAGE_HPP_
#define MESSAGE_HPP_

/// \file
/// Test helpers: create, fill and serialize messages of any type through the
/// introspection type supports (C and C++ layouts), independently of
/// rmw_wasm_cpp's own walker, so that the tests check it rather than mirror it.

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "rcutils/allocator.h"
#include "rmw/error_handling.h"
#include "rmw/rmw.h"
#include "rmw/serialized_message.h"
#include "rosidl_runtime_c/message_initialization.h"
#include "rosidl_runtime_c/string_functions.h"
#include "rosidl_runtime_c/u16string_functions.h"
#include "rosidl_typesupport_introspection_c/field_types.h"
#include "rosidl_typesupport_introspection_c/identifier.h"
#include "rosidl_typesupport_introspection_c/message_introspection.h"
#include "rosidl_typesupport_introspection_cpp/identifier.hpp"
#include "rosidl_typesupport_introspection_cpp/message_introspection.hpp"

/// A deterministic random source (splitmix64).
class Rng final
{
public:
  /// A source seeded with `seed`.
  explicit Rng(uint64_t seed)
  : state_(seed * 0x9E3779B97F4A7C15ull + 1) {}

  /// The next 64 random bits.
  uint64_t next()
  {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  /// A number in [0, n).
  size_t below(size_t n) {return n == 0 ? 0 : static_cast<size_t>(next() % n);}

private:
  uint64_t state_;
};

/// How the filler picks lengths.
enum class Lengths
{
  kRandom,  ///< random, small
  kMaximum,  ///< bounded strings and sequences at their bound
};

/// A message of some type in C or C++ layout, created and destroyed through its introspection.
class Message final
{
public:
  /// Create and initialize (with defaults) a message of type `ts` in the C or C++ layout.
  Message(const rosidl_message_type_support_t * ts, bool cpp)
  : cpp_(cpp)
  {
    const rosidl_message_type_support_t * handle = get_message_typesupport_handle(
      ts, cpp ? rosidl_typesupport_introspection_cpp::typesupport_identifier :
      rosidl_typesupport_introspection_c__identifier);
    if (handle == nullptr) {
      std::abort();
    }
    members_ = handle->data;
    data_ = ::operator new(size_of());
    std::memset(data_, 0, size_of());
    if (cpp_) {
      cpp_members()->init_function(data_, rosidl_runtime_cpp::MessageInitialization::ALL);
    } else {
      c_members()->init_function(data_, ROSIDL_RUNTIME_C_MSG_INIT_ALL);
    }
  }

  Message(const Message &) = delete;
  Message & operator=(const Message &) = delete;

  ~Message()
  {
    if (cpp_) {
      cpp_members()->fini_function(data_);
    } else {
      c_members()->fini_function(data_);
    }
    ::operator delete(data_);
  }

  /// The message memory.
  void * data() {return data_;}

  /// The C++ introspection members (C++ layout only).
  const rosidl_typesupport_introspection_cpp::MessageMembers * cpp_members() const
  {
    return static_cast<const rosidl_typesupport_introspection_cpp::MessageMembers *>(members_);
  }

  /// The C introspection members (C layout only).
  const rosidl_typesupport_introspection_c__MessageMembers * c_members() const
  {
    return static_cast<const rosidl_typesupport_introspection_c__MessageMembers *>(members_);
  }

  /// Fill every field with values drawn from `rng`.
  void fill(Rng & rng, Lengths lengths);

private:
  size_t size_of() const {return cpp_ ? cpp_members()->size_of_ : c_members()->size_of_;}

  bool cpp_;
  const void * members_;
  void * data_;
};

/// rmw_serialize into a byte vector; returns false and the rmw error text on failure.
inline bool serialize(
  const void * message, const rosidl_message_type_support_t * ts, std::vector<uint8_t> * bytes,
  std::string * error)
{
  rmw_serialized_message_t serialized = rmw_get_zero_initialized_serialized_message();
  rcutils_allocator_t allocator = rcutils_get_default_allocator();
  if (rmw_serialized_message_init(&serialized, 0, &allocator) != RMW_RET_OK) {
    std::abort();
  }
  const rmw_ret_t ret = rmw_serialize(message, ts, &serialized);
  if (ret == RMW_RET_OK) {
    bytes->assign(serialized.buffer, serialized.buffer + serialized.buffer_length);
  } else {
    *error = rmw_get_error_string().str;
    rmw_reset_error();
  }
  if (rmw_serialized_message_fini(&serialized) != RMW_RET_OK) {
    std::abort();
  }
  return ret == RMW_RET_OK;
}

/// rmw_deserialize from `size` bytes; returns false and the rmw error text on failure.
inline bool deserialize(
  const uint8_t * data, size_t size, const rosidl_message_type_support_t * ts, void * message,
  std::string * error)
{
  rmw_serialized_message_t serialized = rmw_get_zero_initialized_serialized_message();
  serialized.buffer = const_cast<uint8_t *>(data);
  serialized.buffer_length = size;
  serialized.buffer_capacity = size;
  serialized.allocator = rcutils_get_default_allocator();
  const rmw_ret_t ret = rmw_deserialize(&serialized, ts, message);
  if (ret != RMW_RET_OK) {
    *error = rmw_get_error_string().str;
    rmw_reset_error();
  }
  return ret == RMW_RET_OK;
}

/// Lower-case hex of some bytes.
inline std::string to_hex(const std::vector<uint8_t> & bytes)
{
  static const char digits[] = "0123456789abcdef";
  std::string out;
  out.reserve(bytes.size() * 2);
  for (uint8_t b : bytes) {
    out += digits[b >> 4];
    out += digits[b & 15];
  }
  return out;
}

#endif  // MESSAGE_HPP_
