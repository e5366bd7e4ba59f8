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

#include "detail/graph.hpp"

#include <set>
#include <string>
#include <vector>

#include "rcutils/strdup.h"
#include "rmw/error_handling.h"
#include "rmw/topic_endpoint_info.h"

#include "detail/logging_macros.hpp"
#include "detail/qos.hpp"

namespace rmw_wasm_cpp
{

rmw_ret_t to_rcutils_string_array(
  const std::vector<std::string> & in, rcutils_allocator_t * allocator,
  rcutils_string_array_t * out)
{
  if (rcutils_string_array_init(out, in.size(), allocator) != RCUTILS_RET_OK) {
    rmw_reset_error();  // rcutils' message, replaced by one that says what for
    RMW_SET_ERROR_MSG("cannot allocate a string array");
    return RMW_RET_BAD_ALLOC;
  }
  for (size_t i = 0; i < in.size(); ++i) {
    out->data[i] = rcutils_strdup(in[i].c_str(), *allocator);
    if (out->data[i] == nullptr) {
      if (rcutils_string_array_fini(out) != RCUTILS_RET_OK) {
        rcutils_reset_error();
      }
      rmw_reset_error();
      RMW_SET_ERROR_MSG("cannot allocate a string of a string array");
      return RMW_RET_BAD_ALLOC;
    }
  }
  return RMW_RET_OK;
}

rmw_ret_t to_rmw_names_and_types(
  const std::vector<wasm_cpp::NameAndTypes> & in, rcutils_allocator_t * allocator,
  rmw_names_and_types_t * out)
{
  if (in.empty()) {
    return RMW_RET_OK;
  }
  rmw_ret_t ret = rmw_names_and_types_init(out, in.size(), allocator);
  if (ret != RMW_RET_OK) {
    return ret;
  }
  for (size_t i = 0; i < in.size(); ++i) {
    out->names.data[i] = rcutils_strdup(in[i].name.c_str(), *allocator);
    ret = out->names.data[i] == nullptr ? RMW_RET_BAD_ALLOC :
      to_rcutils_string_array(in[i].types, allocator, &out->types[i]);
    if (ret != RMW_RET_OK) {
      if (rmw_names_and_types_fini(out) != RMW_RET_OK) {
        rcutils_reset_error();
      }
      rmw_reset_error();  // the message of the step that failed, replaced
      RMW_SET_ERROR_MSG("cannot allocate names and types");
      return RMW_RET_BAD_ALLOC;
    }
  }
  return RMW_RET_OK;
}

rmw_ret_t to_rmw_endpoint_info_array(
  const std::vector<wasm_cpp::EndpointInfo> & in, rcutils_allocator_t * allocator,
  rmw_topic_endpoint_info_array_t * out)
{
  rmw_ret_t ret = rmw_topic_endpoint_info_array_init_with_size(out, in.size(), allocator);
  if (ret != RMW_RET_OK) {
    return ret;
  }
  for (size_t i = 0; i < in.size(); ++i) {
    const wasm_cpp::EndpointInfo & endpoint = in[i];
    rmw_topic_endpoint_info_t * info = &out->info_array[i];
    *info = rmw_get_zero_initialized_topic_endpoint_info();
    const rmw_qos_profile_t qos = to_rmw_qos(endpoint.qos);
    ret = rmw_topic_endpoint_info_set_node_name(info, endpoint.node_name.c_str(), allocator);
    if (ret == RMW_RET_OK) {
      ret = rmw_topic_endpoint_info_set_node_namespace(
        info, endpoint.node_namespace.c_str(), allocator);
    }
    if (ret == RMW_RET_OK) {
      ret = rmw_topic_endpoint_info_set_topic_type(info, endpoint.type_name.c_str(), allocator);
    }
    if (ret == RMW_RET_OK) {
      ret = rmw_topic_endpoint_info_set_endpoint_type(
        info, endpoint.kind == wasm_cpp::EndpointKind::kPublisher ?
        RMW_ENDPOINT_PUBLISHER : RMW_ENDPOINT_SUBSCRIPTION);
    }
    if (ret == RMW_RET_OK) {
      ret = rmw_topic_endpoint_info_set_gid(
        info, endpoint.gid.data.data(), endpoint.gid.data.size());
    }
    if (ret == RMW_RET_OK) {
      ret = rmw_topic_endpoint_info_set_qos_profile(info, &qos);
    }
    if (ret != RMW_RET_OK) {
      if (rmw_topic_endpoint_info_array_fini(out, allocator) != RMW_RET_OK) {
        rcutils_reset_error();
      }
      RMW_SET_ERROR_MSG("cannot fill the endpoint info array");
      return ret;
    }
  }
  return RMW_RET_OK;
}

void warn_if_topic_type_differs(
  const wasm_cpp::Context & context, const std::string & topic,
  const std::string & type_name, const char * what)
{
  std::set<std::string> others;
  for (auto kind : {wasm_cpp::EndpointKind::kPublisher, wasm_cpp::EndpointKind::kSubscription}) {
    std::vector<wasm_cpp::EndpointInfo> endpoints;
    if (!wasm_cpp::graph::get_endpoints(context, topic, kind, &endpoints).ok()) {
      return;
    }
    for (const auto & endpoint : endpoints) {
      if (endpoint.type_name != type_name) {
        others.insert(endpoint.type_name);
      }
    }
  }
  if (others.empty()) {
    return;
  }
  std::string list;
  for (const auto & other : others) {
    list += (list.empty() ? "'" : ", '") + other + "'";
  }
  RMW_WASM_LOG_WARN(
    "topic '%s' already has endpoints of type %s: this %s of type '%s' will not match them "
    "(endpoints match only when their types are equal)",
    topic.c_str(), list.c_str(), what, type_name.c_str());
}

}  // namespace rmw_wasm_cpp
