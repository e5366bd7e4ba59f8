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

#include <cstdio>
#include <cstring>
#include <string>

#include "rmw/error_handling.h"
#include "rmw/qos_profiles.h"

#include "detail/qos.hpp"

extern "C"
{

rmw_ret_t rmw_qos_profile_check_compatible(
  const rmw_qos_profile_t publisher_profile,
  const rmw_qos_profile_t subscription_profile,
  rmw_qos_compatibility_type_t * compatibility,
  char * reason,
  size_t reason_size)
{
  RMW_CHECK_ARGUMENT_FOR_NULL(compatibility, RMW_RET_INVALID_ARGUMENT);
  if (reason == nullptr && reason_size != 0) {
    RMW_SET_ERROR_MSG("reason parameter is null, but reason_size parameter is not zero");
    return RMW_RET_INVALID_ARGUMENT;
  }
  std::string why;
  const wasm_cpp::QosCompatibility result = wasm_cpp::check_qos_compatible(
    rmw_wasm_cpp::to_wasm_qos(publisher_profile),
    rmw_wasm_cpp::to_wasm_qos(subscription_profile), nullptr, &why);
  *compatibility = static_cast<rmw_qos_compatibility_type_t>(result);
  if (reason != nullptr && reason_size > 0) {
    std::snprintf(reason, reason_size, "%s", result == wasm_cpp::QosCompatibility::kOk ? "" :
      why.c_str());
  }
  return RMW_RET_OK;
}

}  // extern "C"
