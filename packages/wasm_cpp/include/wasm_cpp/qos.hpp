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

#ifndef WASM_CPP__QOS_HPP_
#define WASM_CPP__QOS_HPP_

#include <cstddef>
#include <cstdint>
#include <string>

namespace wasm_cpp
{

/// Durations are nanoseconds; kDurationUnspecified and kDurationInfinite both mean "no limit".
/**
 * rmw's RMW_DURATION_UNSPECIFIED ({0, 0}) maps to kDurationUnspecified and
 * RMW_DURATION_INFINITE maps to kDurationInfinite. Any other value is a
 * positive number of nanoseconds.
 */
using DurationNs = int64_t;

/// "Use the default", which for every duration policy means no limit.
constexpr DurationNs kDurationUnspecified = 0;
/// No limit.
constexpr DurationNs kDurationInfinite = INT64_MAX;

/// History policy; values equal rmw_qos_history_policy_t.
enum class History : int32_t
{
  kSystemDefault = 0,
  kKeepLast = 1,
  kKeepAll = 2,
  kUnknown = 3,
};

/// Reliability policy; values equal rmw_qos_reliability_policy_t.
enum class Reliability : int32_t
{
  kSystemDefault = 0,
  kReliable = 1,
  kBestEffort = 2,
  kUnknown = 3,
};

/// Durability policy; values equal rmw_qos_durability_policy_t.
enum class Durability : int32_t
{
  kSystemDefault = 0,
  kTransientLocal = 1,
  kVolatile = 2,
  kUnknown = 3,
};

/// Liveliness policy; values equal rmw_qos_liveliness_policy_t.
/**
 * kManualByNode (deprecated in ROS 2) is treated as kManualByTopic.
 */
enum class Liveliness : int32_t
{
  kSystemDefault = 0,
  kAutomatic = 1,
  kManualByNode = 2,
  kManualByTopic = 3,
  kUnknown = 4,
};

/// QoS policy kinds; values equal rmw_qos_policy_kind_t (bit flags).
enum class QosPolicyKind : int32_t
{
  kInvalid = 1 << 0,
  kDurability = 1 << 1,
  kDeadline = 1 << 2,
  kLiveliness = 1 << 3,
  kReliability = 1 << 4,
  kHistory = 1 << 5,
  kLifespan = 1 << 6,
  kDepth = 1 << 7,
  kLivelinessLeaseDuration = 1 << 8,
  kAvoidRosNamespaceConventions = 1 << 9,
};

/// A QoS profile, field for field rmw_qos_profile_t (durations in nanoseconds).
struct QoS
{
  History history = History::kKeepLast;
  /// History depth for kKeepLast; ignored for kKeepAll (see ContextOptions::keep_all_depth).
  size_t depth = 10;
  Reliability reliability = Reliability::kReliable;
  Durability durability = Durability::kVolatile;
  /// Expected maximum period between messages.
  DurationNs deadline = kDurationUnspecified;
  /// Age after which a message is no longer delivered.
  DurationNs lifespan = kDurationUnspecified;
  Liveliness liveliness = Liveliness::kAutomatic;
  /// For kManualByTopic: how long after the last assertion the publisher counts as alive.
  DurationNs liveliness_lease_duration = kDurationUnspecified;
  bool avoid_ros_namespace_conventions = false;
};

/// Replace every SYSTEM_DEFAULT value by what the bus actually uses.
/**
 * The bus defaults equal rmw_qos_profile_default: KEEP_LAST, depth 10 when the
 * depth is 0, RELIABLE, VOLATILE, AUTOMATIC liveliness. The result is what
 * `actual_qos()` reports and what the graph shows.
 */
QoS resolve_qos(const QoS & qos);

/// Outcome of a QoS compatibility check; values equal rmw_qos_compatibility_type_t.
enum class QosCompatibility : int32_t
{
  kOk = 0,
  /// Compatible only for some values a SYSTEM_DEFAULT could resolve to.
  kWarning = 1,
  kError = 2,
};

/// Check whether a publisher and a subscription with these profiles would match.
/**
 * Follows rmw_qos_profile_check_compatible (DDS request/offered rules):
 * reliability (a BEST_EFFORT publisher cannot serve a RELIABLE subscription),
 * durability (a VOLATILE publisher cannot serve a TRANSIENT_LOCAL
 * subscription), deadline (the publisher's must not exceed the
 * subscription's), liveliness (AUTOMATIC cannot serve MANUAL_BY_TOPIC; the
 * publisher's lease must not exceed the subscription's).
 *
 * \param[in] publisher the publisher's profile (may contain SYSTEM_DEFAULT)
 * \param[in] subscription the subscription's profile (may contain SYSTEM_DEFAULT)
 * \param[out] first_policy the first incompatible policy, when not kOk; may be null
 * \param[out] reason a sentence explaining the problem, when not kOk; may be null
 */
QosCompatibility check_qos_compatible(
  const QoS & publisher,
  const QoS & subscription,
  QosPolicyKind * first_policy,
  std::string * reason);

/// Default QoS for services and clients (rmw_qos_profile_services_default).
QoS services_default_qos();

}  // namespace wasm_cpp

#endif  // WASM_CPP__QOS_HPP_
