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

#include <memory>

#include "rmw/allocators.h"
#include "rmw/error_handling.h"
#include "rmw/impl/cpp/macros.hpp"
#include "rmw/rmw.h"

#include "detail/identifier.hpp"
#include "detail/rmw_context_impl_s.hpp"
#include "detail/rmw_guard_condition_data.hpp"
#include "detail/rmw_wait_set_data.hpp"
#include "detail/status.hpp"

using rmw_wasm_cpp::GuardConditionData;
using rmw_wasm_cpp::kIdentifier;
using rmw_wasm_cpp::WaitSetData;

extern "C"
{

rmw_guard_condition_t * rmw_create_guard_condition(rmw_context_t * context)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(context, nullptr);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    context, context->implementation_identifier, kIdentifier, return nullptr);
  RMW_CHECK_FOR_NULL_WITH_MSG(context->impl, "expected initialized context", return nullptr);
  auto guard_condition = wasm_cpp::GuardCondition::make(context->impl->context());
  if (!guard_condition.ok()) {
    rmw_wasm_cpp::to_rmw_ret(guard_condition.status());
    return nullptr;
  }
  rmw_guard_condition_t * handle = rmw_guard_condition_allocate();
  RMW_CHECK_FOR_NULL_WITH_MSG(handle, "cannot allocate a guard condition", return nullptr);
  handle->implementation_identifier = kIdentifier;
  handle->data = GuardConditionData::make(guard_condition.value()).release();
  handle->context = context;
  return handle;
}

rmw_ret_t rmw_destroy_guard_condition(rmw_guard_condition_t * guard_condition)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(guard_condition, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    guard_condition, guard_condition->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  delete static_cast<GuardConditionData *>(guard_condition->data);
  rmw_guard_condition_free(guard_condition);
  return RMW_RET_OK;
}

rmw_ret_t rmw_trigger_guard_condition(const rmw_guard_condition_t * guard_condition)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(guard_condition, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    guard_condition, guard_condition->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  return rmw_wasm_cpp::to_rmw_ret(
    static_cast<GuardConditionData *>(guard_condition->data)->guard_condition()->trigger());
}

rmw_wait_set_t * rmw_create_wait_set(rmw_context_t * context, size_t max_conditions)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(context, nullptr);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    context, context->implementation_identifier, kIdentifier, return nullptr);
  RMW_CHECK_FOR_NULL_WITH_MSG(context->impl, "expected initialized context", return nullptr);
  auto data = WaitSetData::make(context->impl->context(), max_conditions);
  if (data == nullptr) {
    return nullptr;
  }
  rmw_wait_set_t * wait_set = rmw_wait_set_allocate();
  RMW_CHECK_FOR_NULL_WITH_MSG(wait_set, "cannot allocate a wait set", return nullptr);
  wait_set->implementation_identifier = kIdentifier;
  wait_set->guard_conditions = nullptr;
  wait_set->data = data.release();
  return wait_set;
}

rmw_ret_t rmw_destroy_wait_set(rmw_wait_set_t * wait_set)
{
  // rmw.h: RMW_RET_ERROR for a null wait set (test_rmw_implementation checks it)
  RMW_CHECK_ARGUMENT_FOR_NULL(wait_set, RMW_RET_ERROR);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    wait_set, wait_set->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  delete static_cast<WaitSetData *>(wait_set->data);
  rmw_wait_set_free(wait_set);
  return RMW_RET_OK;
}

rmw_ret_t rmw_wait(
  rmw_subscriptions_t * subscriptions,
  rmw_guard_conditions_t * guard_conditions,
  rmw_services_t * services,
  rmw_clients_t * clients,
  rmw_events_t * events,
  rmw_wait_set_t * wait_set,
  const rmw_time_t * wait_timeout)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(wait_set, RMW_RET_INVALID_ARGUMENT);
  RMW_CHECK_TYPE_IDENTIFIERS_MATCH(
    wait_set, wait_set->implementation_identifier, kIdentifier,
    return RMW_RET_INCORRECT_RMW_IMPLEMENTATION);
  return static_cast<WaitSetData *>(wait_set->data)->wait(
    subscriptions, guard_conditions, services, clients, events, wait_timeout);
}

}  // extern "C"
