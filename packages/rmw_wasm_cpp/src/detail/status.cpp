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

#include "detail/status.hpp"

#include "rmw/error_handling.h"

namespace rmw_wasm_cpp
{

rmw_ret_t to_rmw_ret(const wasm_cpp::Status & status)
{
  // The codes equal the rmw ones by construction (wasm_cpp/status.hpp).
  static_assert(static_cast<int>(wasm_cpp::Code::kOk) == RMW_RET_OK, "code");
  static_assert(static_cast<int>(wasm_cpp::Code::kError) == RMW_RET_ERROR, "code");
  static_assert(static_cast<int>(wasm_cpp::Code::kTimeout) == RMW_RET_TIMEOUT, "code");
  static_assert(static_cast<int>(wasm_cpp::Code::kUnsupported) == RMW_RET_UNSUPPORTED, "code");
  static_assert(static_cast<int>(wasm_cpp::Code::kBadAlloc) == RMW_RET_BAD_ALLOC, "code");
  static_assert(
    static_cast<int>(wasm_cpp::Code::kInvalidArgument) == RMW_RET_INVALID_ARGUMENT, "code");
  static_assert(
    static_cast<int>(wasm_cpp::Code::kNodeNameNonExistent) == RMW_RET_NODE_NAME_NON_EXISTENT,
    "code");
  if (status.ok()) {
    return RMW_RET_OK;
  }
  RMW_SET_ERROR_MSG(status.message().c_str());
  return static_cast<rmw_ret_t>(status.code());
}

}  // namespace rmw_wasm_cpp
