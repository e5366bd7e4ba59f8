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

#ifndef DETAIL__API_HELPERS_HPP_
#define DETAIL__API_HELPERS_HPP_

#include "rmw/types.h"
#include "rosidl_runtime_c/message_type_support_struct.h"

#include "detail/scratch_buffer.hpp"

namespace rmw_wasm_cpp
{

/// Check a topic or service name as rmw_create_* must (a valid fully qualified ROS name,
/// unless the QoS avoids ROS namespace conventions); sets the rmw error when it is not.
bool check_topic_name(const char * topic_name, const rmw_qos_profile_t & qos);

/// Refuse an endpoint that strictly requires unique network flow endpoints (there are none
/// on a shared-memory bus); sets the rmw error. NOT_REQUIRED and OPTIONALLY_REQUIRED pass.
bool check_network_flow_requirement(
  rmw_unique_network_flow_endpoints_requirement_t requirement, const char * what,
  const char * topic_name);

/// The scratch buffer of an allocation made by rmw_init_*_allocation, or the thread's.
ScratchBuffer & buffer_of(const char * implementation_identifier, void * data);

/// Preallocate a buffer for the messages of a type (bounded types: their maximum size) and
/// store it in an rmw_publisher_allocation_t or rmw_subscription_allocation_t.
rmw_ret_t init_allocation(
  const rosidl_message_type_support_t * type_support, const char ** identifier, void ** data);

/// Release what init_allocation made.
rmw_ret_t fini_allocation(const char ** identifier, void ** data);

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__API_HELPERS_HPP_
