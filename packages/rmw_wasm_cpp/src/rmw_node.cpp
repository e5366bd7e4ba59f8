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

#include <cstring>

#include "rcutils/strdup.h"
#include "rmw/allocators.h"
#include "rmw/error_handling.h"
#include "rmw/impl/cpp/macros.hpp"
#include "rmw/rmw.h"
#include "rmw/validate_namespace.h"
#include "rmw/validate_node_name.h"

#include "detail/identifier.hpp"
#include "detail/rmw_context_impl_s.hpp"
#include "detail/rmw_node_data.hpp"
#include "detail/status.hpp"

using rmw_wasm_cpp::kIdentifier;
using rmw_wasm_cpp::NodeData;

extern "C"
{

rmw_node_t * rmw_create_node(rmw_context_t * context, const char * name, const char * namespace_)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(context, nullptr);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    context, context->implementation_identifier, kIdentifier, return nullptr);
  RMW_CHECK_FOR_NULL_WITH_MSG(context->impl, "expected initialized context", return nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(name, nullptr);
  RMW_CHECK_ARGUMENT_FOR_NULL(namespace_, nullptr);
  if (context->impl->is_shutdown()) {
    RMW_SET_ERROR_MSG("cannot create a node: the context has been shut down");
    return nullptr;
  }
  int validation_result = RMW_NODE_NAME_VALID;
  if (rmw_validate_node_name(name, &validation_result, nullptr) != RMW_RET_OK) {
    return nullptr;
  }
  if (validation_result != RMW_NODE_NAME_VALID) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "invalid node name '%s': %s", name,
      rmw_node_name_validation_result_string(validation_result));
    return nullptr;
  }
  validation_result = RMW_NAMESPACE_VALID;
  if (rmw_validate_namespace(namespace_, &validation_result, nullptr) != RMW_RET_OK) {
    return nullptr;
  }
  if (validation_result != RMW_NAMESPACE_VALID) {
    RMW_SET_ERROR_MSG_WITH_FORMAT_STRING(
      "invalid node namespace '%s': %s", namespace_,
      rmw_namespace_validation_result_string(validation_result));
    return nullptr;
  }

  rmw_node_t * node = rmw_node_allocate();
  RMW_CHECK_FOR_NULL_WITH_MSG(node, "cannot allocate an rmw node", return nullptr);
  std::memset(node, 0, sizeof(*node));
  rcutils_allocator_t allocator = rcutils_get_default_allocator();
  char * name_copy = rcutils_strdup(name, allocator);
  char * namespace_copy = rcutils_strdup(namespace_, allocator);
  auto data = (name_copy && namespace_copy) ?
    context->impl->create_node(node, name, namespace_) : nullptr;
  if (data == nullptr) {
    if (!name_copy || !namespace_copy) {
      RMW_SET_ERROR_MSG("cannot allocate the node name");
    }
    allocator.deallocate(name_copy, allocator.state);
    allocator.deallocate(namespace_copy, allocator.state);
    rmw_node_free(node);
    return nullptr;
  }
  node->implementation_identifier = kIdentifier;
  node->data = data.get();
  node->name = name_copy;
  node->namespace_ = namespace_copy;
  node->context = context;
  return node;
}

rmw_ret_t rmw_destroy_node(rmw_node_t * node)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  node->context->impl->destroy_node(node);
  rcutils_allocator_t allocator = rcutils_get_default_allocator();
  allocator.deallocate(const_cast<char *>(node->name), allocator.state);
  allocator.deallocate(const_cast<char *>(node->namespace_), allocator.state);
  rmw_node_free(node);
  return RMW_RET_OK;
}

rmw_ret_t rmw_node_assert_liveliness(const rmw_node_t * node)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  return rmw_wasm_cpp::to_rmw_ret(static_cast<NodeData *>(node->data)->node()->assert_liveliness());
}

const rmw_guard_condition_t * rmw_node_get_graph_guard_condition(const rmw_node_t * node)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(node, nullptr);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    node, node->implementation_identifier, kIdentifier, return nullptr);
  return static_cast<NodeData *>(node->data)->graph_guard_condition();
}

}  // extern "C"
