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

#include "wasm_cpp/qos.hpp"

#include <string>

namespace wasm_cpp
{

QoS resolve_qos(const QoS & qos)
{
  QoS q = qos;
  if (q.history == History::kSystemDefault) {
    q.history = History::kKeepLast;
  }
  if (q.history == History::kKeepLast && q.depth == 0) {
    q.depth = 10;
  }
  if (q.reliability == Reliability::kSystemDefault) {
    q.reliability = Reliability::kReliable;
  }
  if (q.durability == Durability::kSystemDefault) {
    q.durability = Durability::kVolatile;
  }
  if (q.liveliness == Liveliness::kSystemDefault) {
    q.liveliness = Liveliness::kAutomatic;
  }
  if (q.liveliness == Liveliness::kManualByNode) {
    q.liveliness = Liveliness::kManualByTopic;
  }
  return q;
}

QoS services_default_qos()
{
  QoS q;
  q.history = History::kKeepLast;
  q.depth = 10;
  q.reliability = Reliability::kReliable;
  q.durability = Durability::kVolatile;
  return q;
}

namespace
{

bool is_infinite(DurationNs d)
{
  return d == kDurationUnspecified || d == kDurationInfinite || d < 0;
}

bool is_unresolved_reliability(Reliability r)
{
  return r == Reliability::kSystemDefault || r == Reliability::kUnknown;
}

bool is_unresolved_durability(Durability d)
{
  return d == Durability::kSystemDefault || d == Durability::kUnknown;
}

bool is_unresolved_liveliness(Liveliness l)
{
  return l == Liveliness::kSystemDefault || l == Liveliness::kUnknown;
}

QosCompatibility report(
  QosCompatibility result, QosPolicyKind policy, const char * text,
  QosPolicyKind * first_policy, std::string * reason)
{
  if (first_policy != nullptr) {
    *first_policy = policy;
  }
  if (reason != nullptr) {
    *reason = text;
  }
  return result;
}

}  // namespace

QosCompatibility check_qos_compatible(
  const QoS & pub, const QoS & sub, QosPolicyKind * first_policy, std::string * reason)
{
  if (reason != nullptr) {
    reason->clear();
  }
  const Liveliness pub_live =
    pub.liveliness == Liveliness::kManualByNode ? Liveliness::kManualByTopic : pub.liveliness;
  const Liveliness sub_live =
    sub.liveliness == Liveliness::kManualByNode ? Liveliness::kManualByTopic : sub.liveliness;

  // Errors: combinations no resolution of a SYSTEM_DEFAULT can fix.
  if (pub.reliability == Reliability::kBestEffort && sub.reliability == Reliability::kReliable) {
    return report(
      QosCompatibility::kError, QosPolicyKind::kReliability,
      "ERROR: Best effort publisher and reliable subscription;", first_policy, reason);
  }
  if (pub.durability == Durability::kVolatile && sub.durability == Durability::kTransientLocal) {
    return report(
      QosCompatibility::kError, QosPolicyKind::kDurability,
      "ERROR: Volatile publisher and transient local subscription;", first_policy, reason);
  }
  if (!is_infinite(sub.deadline) && is_infinite(pub.deadline)) {
    return report(
      QosCompatibility::kError, QosPolicyKind::kDeadline,
      "ERROR: Subscription has a deadline, but publisher does not;", first_policy, reason);
  }
  if (!is_infinite(sub.deadline) && !is_infinite(pub.deadline) && pub.deadline > sub.deadline) {
    return report(
      QosCompatibility::kError, QosPolicyKind::kDeadline,
      "ERROR: Subscription deadline is less than publisher deadline;", first_policy, reason);
  }
  if (pub_live == Liveliness::kAutomatic && sub_live == Liveliness::kManualByTopic) {
    return report(
      QosCompatibility::kError, QosPolicyKind::kLiveliness,
      "ERROR: Publisher's liveliness is automatic and subscription's is manual by topic;",
      first_policy, reason);
  }
  if (!is_infinite(sub.liveliness_lease_duration) && is_infinite(pub.liveliness_lease_duration)) {
    return report(
      QosCompatibility::kError, QosPolicyKind::kLivelinessLeaseDuration,
      "ERROR: Subscription has a liveliness lease duration, but publisher does not;",
      first_policy, reason);
  }
  if (!is_infinite(sub.liveliness_lease_duration) && !is_infinite(pub.liveliness_lease_duration) &&
    pub.liveliness_lease_duration > sub.liveliness_lease_duration)
  {
    return report(
      QosCompatibility::kError, QosPolicyKind::kLivelinessLeaseDuration,
      "ERROR: Subscription liveliness lease duration is less than publisher;",
      first_policy, reason);
  }

  // Warnings: a SYSTEM_DEFAULT or UNKNOWN that could resolve to an incompatible value.
  if (is_unresolved_reliability(pub.reliability) && sub.reliability == Reliability::kReliable) {
    return report(
      QosCompatibility::kWarning, QosPolicyKind::kReliability,
      "WARNING: Publisher reliability is SYSTEM_DEFAULT or UNKNOWN and subscription reliability "
      "is RELIABLE;", first_policy, reason);
  }
  if (pub.reliability == Reliability::kBestEffort && is_unresolved_reliability(sub.reliability)) {
    return report(
      QosCompatibility::kWarning, QosPolicyKind::kReliability,
      "WARNING: Publisher reliability is BEST_EFFORT and subscription reliability is "
      "SYSTEM_DEFAULT or UNKNOWN;", first_policy, reason);
  }
  if (is_unresolved_durability(pub.durability) && sub.durability == Durability::kTransientLocal) {
    return report(
      QosCompatibility::kWarning, QosPolicyKind::kDurability,
      "WARNING: Publisher durability is SYSTEM_DEFAULT or UNKNOWN and subscription durability "
      "is TRANSIENT_LOCAL;", first_policy, reason);
  }
  if (pub.durability == Durability::kVolatile && is_unresolved_durability(sub.durability)) {
    return report(
      QosCompatibility::kWarning, QosPolicyKind::kDurability,
      "WARNING: Publisher durability is VOLATILE and subscription durability is SYSTEM_DEFAULT "
      "or UNKNOWN;", first_policy, reason);
  }
  if (is_unresolved_liveliness(pub_live) && sub_live == Liveliness::kManualByTopic) {
    return report(
      QosCompatibility::kWarning, QosPolicyKind::kLiveliness,
      "WARNING: Publisher liveliness is SYSTEM_DEFAULT or UNKNOWN and subscription liveliness "
      "is MANUAL_BY_TOPIC;", first_policy, reason);
  }
  if (pub_live == Liveliness::kAutomatic && is_unresolved_liveliness(sub_live)) {
    return report(
      QosCompatibility::kWarning, QosPolicyKind::kLiveliness,
      "WARNING: Publisher liveliness is AUTOMATIC and subscription liveliness is SYSTEM_DEFAULT "
      "or UNKNOWN;", first_policy, reason);
  }
  return QosCompatibility::kOk;
}

}  // namespace wasm_cpp
