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

#ifndef DETAIL__GRAPH_HPP_
#define DETAIL__GRAPH_HPP_

#include <string>
#include <vector>

#include "rcutils/allocator.h"
#include "rcutils/types/string_array.h"
#include "rmw/names_and_types.h"
#include "rmw/topic_endpoint_info_array.h"
#include "rmw/types.h"
#include "wasm_cpp/context.hpp"
#include "wasm_cpp/graph.hpp"

namespace rmw_wasm_cpp
{

/// Fill a zero-initialized rmw_names_and_types_t; on failure leaves it zero-initialized.
rmw_ret_t to_rmw_names_and_types(
  const std::vector<wasm_cpp::NameAndTypes> & in, rcutils_allocator_t * allocator,
  rmw_names_and_types_t * out);

/// Fill a zero-initialized string array; on failure leaves it zero-initialized.
rmw_ret_t to_rcutils_string_array(
  const std::vector<std::string> & in, rcutils_allocator_t * allocator,
  rcutils_string_array_t * out);

/// Fill a zero-initialized endpoint info array; on failure leaves it zero-initialized.
rmw_ret_t to_rmw_endpoint_info_array(
  const std::vector<wasm_cpp::EndpointInfo> & in, rcutils_allocator_t * allocator,
  rmw_topic_endpoint_info_array_t * out);

/// Log a warning when `topic` already has publishers or subscriptions of a type other than
/// `type_name`: they will not match a new `what` ("publisher" or "subscription").
void warn_if_topic_type_differs(
  const wasm_cpp::Context & context, const std::string & topic,
  const std::string & type_name, const char * what);

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__GRAPH_HPP_
