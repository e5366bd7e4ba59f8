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

#ifndef JSON_HPP_
#define JSON_HPP_

#include <string>

#include "rosidl_typesupport_introspection_cpp/message_introspection.hpp"

/// A C++ message as JSON, field by field through its introspection members.
/**
 * The format of the golden vectors (tests/data/cdr/NAME.json): 64-bit integers
 * as decimal strings, non-finite floats as "NaN"/"Infinity"/"-Infinity",
 * wide strings as JSON strings (UTF-16 converted to UTF-8).
 */
std::string to_json(
  const rosidl_typesupport_introspection_cpp::MessageMembers * members, const void * message);

#endif  // JSON_HPP_
