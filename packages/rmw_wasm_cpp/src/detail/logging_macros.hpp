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

#ifndef DETAIL__LOGGING_MACROS_HPP_
#define DETAIL__LOGGING_MACROS_HPP_

#include "rcutils/logging_macros.h"

// rmw_wasm_cpp logs through rcutils' console output, never through /rosout:
// /rosout is itself a topic of this middleware, so logging to it from inside
// the middleware could recurse. The console output reaches the host (Node.js
// or the page's log pane) with its severity.
#define RMW_WASM_LOG_DEBUG(...) RCUTILS_LOG_DEBUG_NAMED("rmw_wasm_cpp", __VA_ARGS__)
#define RMW_WASM_LOG_INFO(...) RCUTILS_LOG_INFO_NAMED("rmw_wasm_cpp", __VA_ARGS__)
#define RMW_WASM_LOG_WARN(...) RCUTILS_LOG_WARN_NAMED("rmw_wasm_cpp", __VA_ARGS__)
#define RMW_WASM_LOG_ERROR(...) RCUTILS_LOG_ERROR_NAMED("rmw_wasm_cpp", __VA_ARGS__)

#endif  // DETAIL__LOGGING_MACROS_HPP_
