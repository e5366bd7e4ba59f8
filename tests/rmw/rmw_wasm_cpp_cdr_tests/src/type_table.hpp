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

#ifndef TYPE_TABLE_HPP_
#define TYPE_TABLE_HPP_

#include <vector>

#include "rosidl_runtime_c/message_type_support_struct.h"

/// One message type under test: its ROS name and its C and C++ type supports.
struct TypeEntry
{
  const char * name;
  const rosidl_message_type_support_t * c;
  const rosidl_message_type_support_t * cpp;
};

/// Every message type of the packages the test was configured with (generated).
const std::vector<TypeEntry> & type_table();

#endif  // TYPE_TABLE_HPP_
