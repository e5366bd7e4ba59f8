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

#include "wasm_cpp/context.hpp"

#include <cerrno>
#include <cstdlib>
#include <memory>
#include <string>

#include "bus_abi.hpp"

namespace wasm_cpp
{

namespace
{

// Resolve kDefaultDomainId from ROS_DOMAIN_ID (0 when unset or empty).
Status resolve_domain(size_t requested, size_t * domain)
{
  if (requested != kDefaultDomainId) {
    if (requested > 0x7fffffffu) {
      return Status(
        Code::kInvalidArgument, "invalid domain id " + std::to_string(requested) +
        ": must be at most 2147483647");
    }
    *domain = requested;
    return Status::Ok();
  }
  const char * env = std::getenv("ROS_DOMAIN_ID");
  if (env == nullptr || env[0] == '\0') {
    *domain = 0;
    return Status::Ok();
  }
  errno = 0;
  char * end = nullptr;
  long value = std::strtol(env, &end, 10);  // NOLINT(runtime/int): strtol's type
  if (errno != 0 || end == env || *end != '\0' || value < 0 || value > 0x7fffffffL) {
    return Status(
      Code::kInvalidArgument, std::string("invalid ROS_DOMAIN_ID '") + env +
      "': expected a non-negative integer");
  }
  *domain = static_cast<size_t>(value);
  return Status::Ok();
}

}  // namespace

Result<std::shared_ptr<Context>> Context::make(const ContextOptions & options)
{
  size_t domain = 0;
  Status s = resolve_domain(options.domain_id, &domain);
  if (!s.ok()) {
    return s;
  }
  if (options.keep_all_depth == 0 || options.keep_all_depth > (1u << 20)) {
    return Status(
      Code::kInvalidArgument, "invalid keep_all_depth " + std::to_string(options.keep_all_depth) +
      ": must be 1..1048576");
  }
  if (!wasm_bus_attached()) {
    return Status(Code::kError, detail::last_error());
  }
  int id = wasm_bus_context_create();
  if (id <= 0) {
    return detail::bus_status(-id, "creating a context");
  }
  return std::shared_ptr<Context>(new Context(options, domain, static_cast<uint32_t>(id)));
}

Context::Context(const ContextOptions & options, size_t domain_id, uint32_t instance_id)
: options_(options), domain_id_(domain_id), instance_id_(instance_id)
{
  options_.domain_id = domain_id;
  if (options_.enclave.empty()) {
    options_.enclave = "/";
  }
}

Context::~Context() = default;

uint32_t Context::process_id() const
{
  return static_cast<uint32_t>(wasm_bus_process_id());
}

size_t Context::max_message_size() const
{
  return static_cast<size_t>(wasm_bus_max_message());
}

Status Context::shutdown()
{
  shut_down_.store(true);
  return Status::Ok();
}

}  // namespace wasm_cpp
