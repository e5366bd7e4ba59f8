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

#include "wasm_cpp/node.hpp"

#include <memory>
#include <string>
#include <utility>

#include "bus_abi.hpp"

namespace wasm_cpp
{

Result<std::shared_ptr<Node>> Node::make(
  std::shared_ptr<Context> context, const std::string & name, const std::string & namespace_)
{
  if (!context) {
    return Status(Code::kInvalidArgument, "cannot create node '" + name + "': null context");
  }
  if (context->is_shut_down()) {
    return Status(
      Code::kError, "cannot create node '" + name + "': the context has been shut down");
  }
  int32_t out[6] = {};
  int rc = wasm_bus_node_create(
    static_cast<int>(context->domain_id()), static_cast<int>(context->instance_id()),
    name.c_str(), namespace_.c_str(), context->enclave().c_str(), out);
  if (rc != 0) {
    return detail::bus_status(rc, ("creating node '" + name + "'").c_str());
  }
  return std::shared_ptr<Node>(
    new Node(
      std::move(context), name, namespace_, out[0], detail::gid_from_words(&out[1]),
      out[5] != 0));
}

Node::Node(
  std::shared_ptr<Context> context, std::string name, std::string namespace_,
  int32_t handle, const Gid & gid, bool name_was_taken)
: context_(std::move(context)), name_(std::move(name)), ns_(std::move(namespace_)),
  handle_(handle), gid_(gid), name_was_taken_(name_was_taken)
{
}

Node::~Node()
{
  shutdown();
}

std::string Node::fully_qualified_name() const
{
  if (ns_ == "/") {
    return "/" + name_;
  }
  return ns_ + "/" + name_;
}

Status Node::assert_liveliness()
{
  if (handle_ < 0) {
    return Status(Code::kError, "assert_liveliness: node '" + name_ + "' was shut down");
  }
  return detail::bus_status(wasm_bus_assert_liveliness(-1 - handle_), "assert_liveliness");
}

Status Node::shutdown()
{
  if (handle_ < 0) {
    return Status::Ok();
  }
  int rc = wasm_bus_node_destroy(handle_);
  handle_ = -1;
  return detail::bus_status(rc, ("destroying node '" + name_ + "'").c_str());
}

}  // namespace wasm_cpp
