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

#ifndef DETAIL__RMW_GUARD_CONDITION_DATA_HPP_
#define DETAIL__RMW_GUARD_CONDITION_DATA_HPP_

#include <memory>

#include "wasm_cpp/guard_condition.hpp"

namespace rmw_wasm_cpp
{

/// The data behind an rmw_guard_condition_t (user guard conditions and graph guard conditions).
class GuardConditionData final
{
public:
  /// Wrap a core guard condition.
  static std::unique_ptr<GuardConditionData> make(
    std::shared_ptr<wasm_cpp::GuardCondition> guard_condition)
  {
    return std::unique_ptr<GuardConditionData>(
      new GuardConditionData(std::move(guard_condition)));
  }

  /// The core guard condition.
  wasm_cpp::GuardCondition * guard_condition() const {return guard_condition_.get();}

private:
  explicit GuardConditionData(std::shared_ptr<wasm_cpp::GuardCondition> guard_condition)
  : guard_condition_(std::move(guard_condition)) {}

  // The core guard condition.
  std::shared_ptr<wasm_cpp::GuardCondition> guard_condition_;
};

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__RMW_GUARD_CONDITION_DATA_HPP_
