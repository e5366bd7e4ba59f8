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

#include "wasm_cpp/guard_condition.hpp"

#include <memory>
#include <utility>

#include "bus_abi.hpp"

namespace wasm_cpp
{

Result<std::shared_ptr<GuardCondition>> GuardCondition::make(std::shared_ptr<Context> context)
{
  if (!context) {
    return Status(Code::kInvalidArgument, "cannot create guard condition: null context");
  }
  return std::shared_ptr<GuardCondition>(new GuardCondition(std::move(context), false));
}

Result<std::shared_ptr<GuardCondition>> GuardCondition::make_graph(
  std::shared_ptr<Context> context)
{
  if (!context) {
    return Status(Code::kInvalidArgument, "cannot create graph guard condition: null context");
  }
  return std::shared_ptr<GuardCondition>(new GuardCondition(std::move(context), true));
}

GuardCondition::GuardCondition(std::shared_ptr<Context> context, bool graph)
: context_(std::move(context))
{
  state_[0] = graph ? 1 : 0;
  state_[1] = 0;
  // A graph guard condition reports changes made after its creation.
  state_[2] = graph ? wasm_bus_graph_version() : 0;
  state_[3] = 0;
}

GuardCondition::~GuardCondition() = default;

Status GuardCondition::trigger()
{
  __atomic_store_n(&state_[1], 1, __ATOMIC_SEQ_CST);
  wasm_bus_ring_self();
  return Status::Ok();
}

}  // namespace wasm_cpp
