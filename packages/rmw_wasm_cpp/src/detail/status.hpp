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

#ifndef DETAIL__STATUS_HPP_
#define DETAIL__STATUS_HPP_

#include "rmw/ret_types.h"
#include "wasm_cpp/status.hpp"

namespace rmw_wasm_cpp
{

/// Turn a wasm_cpp::Status into an rmw return code; on failure set the rmw error message to
/// the status' message (which says what failed and what to do).
rmw_ret_t to_rmw_ret(const wasm_cpp::Status & status);

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__STATUS_HPP_
