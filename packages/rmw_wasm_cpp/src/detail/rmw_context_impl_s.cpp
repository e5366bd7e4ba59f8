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

#include "detail/rmw_context_impl_s.hpp"

#include <memory>
#include <string>
#include <utility>

#include "rmw/error_handling.h"

#include "detail/rmw_node_data.hpp"
#include "detail/status.hpp"

rmw_context_impl_s::rmw_context_impl_s(std::shared_ptr<wasm_cpp::Context> context)
: context_(std::move(context))
{
}

std::unique_ptr<rmw_context_impl_s> rmw_context_impl_s::make(const rmw_init_options_t & options)
{
  wasm_cpp::ContextOptions context_options;
  // RMW_DEFAULT_DOMAIN_ID and wasm_cpp::kDefaultDomainId are both SIZE_MAX: ROS_DOMAIN_ID.
  context_options.domain_id = options.domain_id;
  context_options.enclave = options.enclave != nullptr ? options.enclave : "";
  auto context = wasm_cpp::Context::make(context_options);
  if (!context.ok()) {
    rmw_wasm_cpp::to_rmw_ret(context.status());
    return nullptr;
  }
  return std::unique_ptr<rmw_context_impl_s>(new rmw_context_impl_s(context.value()));
}

std::shared_ptr<rmw_wasm_cpp::NodeData> rmw_context_impl_s::create_node(
  const rmw_node_t * handle, const char * name, const char * namespace_)
{
  auto node = rmw_wasm_cpp::NodeData::make(context_, name, namespace_);
  if (node == nullptr) {
    return nullptr;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  nodes_[handle] = node;
  return node;
}

void rmw_context_impl_s::destroy_node(const rmw_node_t * handle)
{
  std::shared_ptr<rmw_wasm_cpp::NodeData> node;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = nodes_.find(handle);
    if (it == nodes_.end()) {
      return;
    }
    node = std::move(it->second);
    nodes_.erase(it);
  }
  node->shutdown();
}

rmw_ret_t rmw_context_impl_s::shutdown()
{
  return rmw_wasm_cpp::to_rmw_ret(context_->shutdown());
}

bool rmw_context_impl_s::is_shutdown() const
{
  return context_->is_shut_down();
}
