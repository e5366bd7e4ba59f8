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
#ifndef DETAIL__QOS_HPP_
#define DETAIL__QOS_HPP_

#include <string>

#include "rmw/types.h"
#include "wasm_cpp/qos.hpp"

namespace rmw_wasm_cpp
{

/// Convert an rmw QoS profile to the core's (SYSTEM_DEFAULT values are kept for the core to
/// resolve; RMW_DURATION_UNSPECIFIED and RMW_DURATION_INFINITE become "no limit").
wasm_cpp::QoS to_wasm_qos(const rmw_qos_profile_t & qos);

/// Convert the core's QoS to an rmw profile; "no limit" durations are reported as
/// RMW_DURATION_INFINITE, as the DDS implementations report them.
rmw_qos_profile_t to_rmw_qos(const wasm_cpp::QoS & qos);

/// Check that no policy of `qos` is UNKNOWN; otherwise describe the first bad one in *error.
bool is_valid_qos(const rmw_qos_profile_t & qos, std::string * error);

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__QOS_HPP_
