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

#ifndef WASM_CPP__WASM_CPP_HPP_
#define WASM_CPP__WASM_CPP_HPP_

/// \file
/// The whole wasm_cpp API: the C++ core of the colcon-wasm middleware.
///
/// wasm_cpp carries opaque byte messages between the nodes of one page or
/// one Node.js process over a shared-memory bus (a SharedArrayBuffer owned
/// by the wasm_js Runtime). Objects follow the rmw_zenoh style: `final`
/// classes created with a static `make()` that returns a `Result` holding a
/// `std::shared_ptr`, and every operation returns a `Status` whose message
/// says what failed.
///
///     auto ctx = wasm_cpp::Context::make({}).value();
///     auto node = wasm_cpp::Node::make(ctx, "talker", "/").value();
///     auto pub = wasm_cpp::Publisher::make(
///       node, "/chatter", "std_msgs/msg/String", wasm_cpp::QoS{}).value();
///     pub->publish(bytes, size);

#include "wasm_cpp/context.hpp"
#include "wasm_cpp/events.hpp"
#include "wasm_cpp/graph.hpp"
#include "wasm_cpp/guard_condition.hpp"
#include "wasm_cpp/node.hpp"
#include "wasm_cpp/publisher.hpp"
#include "wasm_cpp/qos.hpp"
#include "wasm_cpp/service.hpp"
#include "wasm_cpp/status.hpp"
#include "wasm_cpp/subscription.hpp"
#include "wasm_cpp/types.hpp"
#include "wasm_cpp/wait_set.hpp"

#endif  // WASM_CPP__WASM_CPP_HPP_
