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

#ifndef WASM_CPP__CONTEXT_HPP_
#define WASM_CPP__CONTEXT_HPP_

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "wasm_cpp/status.hpp"
#include "wasm_cpp/types.hpp"

namespace wasm_cpp
{

/// Options of a context (what rmw_init_options_t carries, plus bus settings).
struct ContextOptions
{
  /// ROS domain id; entities of different domains never see each other.
  /**
   * Use kDefaultDomainId to read ROS_DOMAIN_ID from the environment (0 when
   * unset), like RMW_DEFAULT_DOMAIN_ID.
   */
  size_t domain_id = 0;
  /// The security enclave name reported in graph queries ("/" when empty).
  std::string enclave;
  /// Ring size (messages) of KEEP_ALL publishers: the bound at which publish blocks.
  size_t keep_all_depth = 1000;
  /// How long publish(), send_request() and send_response() may block on a full
  /// KEEP_ALL history (or an unread request/response) before returning kTimeout.
  Timeout publish_timeout = std::chrono::seconds(10);
};

/// Pass as ContextOptions::domain_id to use ROS_DOMAIN_ID.
constexpr size_t kDefaultDomainId = SIZE_MAX;

/// A middleware context: one attachment of this bus process to the bus, in one domain.
/**
 * Creating a context needs a bus: the one the wasm_js Runtime gave this
 * process, or a private one the JS library creates when the executable runs
 * alone (`node exe.js`). Contexts are cheap; several may exist in a process.
 */
class Context final
{
public:
  /// Create a context; fails with a clear message when no bus is attached.
  static Result<std::shared_ptr<Context>> make(const ContextOptions & options);

  /// The domain id actually used (after resolving kDefaultDomainId).
  size_t domain_id() const {return domain_id_;}

  /// The enclave name ("/" by default).
  const std::string & enclave() const {return options_.enclave;}

  /// The options this context was created with (domain id resolved).
  const ContextOptions & options() const {return options_;}

  /// A bus-wide unique id of this context (used by ignore_local_publications).
  uint32_t instance_id() const {return instance_id_;}

  /// The bus process id of this executable.
  uint32_t process_id() const;

  /// The largest message the bus accepts, in bytes (Runtime option maxMessageBytes).
  size_t max_message_size() const;

  /// Mark the context shut down; creating entities on it then fails. Idempotent.
  Status shutdown();

  /// True after shutdown().
  bool is_shut_down() const {return shut_down_.load();}

  ~Context();

private:
  Context(const ContextOptions & options, size_t domain_id, uint32_t instance_id);

  // Options with the domain id resolved.
  ContextOptions options_;
  // Domain id in use.
  size_t domain_id_;
  // Bus-wide unique id of this context.
  uint32_t instance_id_;
  // Set by shutdown().
  std::atomic<bool> shut_down_{false};
};

}  // namespace wasm_cpp

#endif  // WASM_CPP__CONTEXT_HPP_
