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
#include "detail/qos.hpp"

#include <cstdint>
#include <string>

#include "rmw/qos_profiles.h"
#include "rmw/time.h"

namespace rmw_wasm_cpp
{

namespace
{

wasm_cpp::DurationNs to_ns(const rmw_time_t & time)
{
  if (time.sec == 0 && time.nsec == 0) {
    return wasm_cpp::kDurationUnspecified;
  }
  const rmw_duration_t ns = rmw_time_total_nsec(time);
  return ns >= INT64_MAX ? wasm_cpp::kDurationInfinite : ns;
}

rmw_time_t to_rmw_time(wasm_cpp::DurationNs ns)
{
  if (ns == wasm_cpp::kDurationUnspecified || ns == wasm_cpp::kDurationInfinite) {
    return RMW_DURATION_INFINITE;
  }
  return rmw_time_from_nsec(ns);
}

}  // namespace

wasm_cpp::QoS to_wasm_qos(const rmw_qos_profile_t & qos)
{
  wasm_cpp::QoS out;
  out.history = static_cast<wasm_cpp::History>(qos.history);
  out.depth = qos.depth;
  out.reliability = static_cast<wasm_cpp::Reliability>(qos.reliability);
  out.durability = static_cast<wasm_cpp::Durability>(qos.durability);
  out.deadline = to_ns(qos.deadline);
  out.lifespan = to_ns(qos.lifespan);
  out.liveliness = static_cast<wasm_cpp::Liveliness>(qos.liveliness);
  out.liveliness_lease_duration = to_ns(qos.liveliness_lease_duration);
  out.avoid_ros_namespace_conventions = qos.avoid_ros_namespace_conventions;
  return out;
}

rmw_qos_profile_t to_rmw_qos(const wasm_cpp::QoS & qos)
{
  rmw_qos_profile_t out = rmw_qos_profile_default;
  out.history = static_cast<rmw_qos_history_policy_t>(qos.history);
  out.depth = qos.depth;
  out.reliability = static_cast<rmw_qos_reliability_policy_t>(qos.reliability);
  out.durability = static_cast<rmw_qos_durability_policy_t>(qos.durability);
  out.deadline = to_rmw_time(qos.deadline);
  out.lifespan = to_rmw_time(qos.lifespan);
  out.liveliness = static_cast<rmw_qos_liveliness_policy_t>(qos.liveliness);
  out.liveliness_lease_duration = to_rmw_time(qos.liveliness_lease_duration);
  out.avoid_ros_namespace_conventions = qos.avoid_ros_namespace_conventions;
  return out;
}

bool is_valid_qos(const rmw_qos_profile_t & qos, std::string * error)
{
  if (qos.history == RMW_QOS_POLICY_HISTORY_UNKNOWN) {
    *error = "QoS history policy is UNKNOWN";
    return false;
  }
  if (qos.reliability == RMW_QOS_POLICY_RELIABILITY_UNKNOWN) {
    *error = "QoS reliability policy is UNKNOWN";
    return false;
  }
  if (qos.durability == RMW_QOS_POLICY_DURABILITY_UNKNOWN) {
    *error = "QoS durability policy is UNKNOWN";
    return false;
  }
  if (qos.liveliness == RMW_QOS_POLICY_LIVELINESS_UNKNOWN) {
    *error = "QoS liveliness policy is UNKNOWN";
    return false;
  }
  return true;
}

}  // namespace rmw_wasm_cpp
