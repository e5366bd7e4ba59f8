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

#ifndef WASM_CPP__STATUS_HPP_
#define WASM_CPP__STATUS_HPP_

#include <string>
#include <utility>

namespace wasm_cpp
{

/// What kind of failure a Status carries.
/**
 * The codes map one to one onto rmw return codes, so that an rmw adapter can
 * translate them without guessing:
 *
 * | Code                  | rmw                                  |
 * |-----------------------|--------------------------------------|
 * | kOk                   | RMW_RET_OK                           |
 * | kError                | RMW_RET_ERROR                        |
 * | kTimeout              | RMW_RET_TIMEOUT                      |
 * | kUnsupported          | RMW_RET_UNSUPPORTED                  |
 * | kBadAlloc             | RMW_RET_BAD_ALLOC                    |
 * | kInvalidArgument      | RMW_RET_INVALID_ARGUMENT             |
 * | kNodeNameNonExistent  | RMW_RET_NODE_NAME_NON_EXISTENT       |
 */
enum class Code : int
{
  kOk = 0,
  /// Unspecified failure (the message says what failed).
  kError = 1,
  /// A blocking call (publish on a full KEEP_ALL history, wait, ...) timed out.
  kTimeout = 2,
  /// The operation is not available in this build (e.g. callbacks without pthreads).
  kUnsupported = 3,
  /// Bus memory or one of its tables is exhausted, or a message is over the maximum size.
  kBadAlloc = 10,
  /// An argument is malformed (invalid name, null pointer, bad QoS, ...).
  kInvalidArgument = 11,
  /// A graph query named a node that does not exist.
  kNodeNameNonExistent = 203,
};

/// The outcome of an operation: a code and, on failure, a human-readable message.
/**
 * The message says what failed, where, and what to do, e.g.
 * "publish on '/chatter' failed: message of 80000000 bytes exceeds the bus
 * maximum of 67108864 bytes (Runtime option maxMessageBytes)".
 */
class Status final
{
public:
  /// A successful status.
  Status() = default;

  /// A status with the given code and message.
  Status(Code code, std::string message)
  : code_(code), message_(std::move(message)) {}

  /// A successful status.
  static Status Ok() {return Status();}

  /// True when the operation succeeded.
  bool ok() const {return code_ == Code::kOk;}

  /// The code of this status.
  Code code() const {return code_;}

  /// The human-readable message; empty on success.
  const std::string & message() const {return message_;}

private:
  // What kind of failure, kOk on success.
  Code code_ = Code::kOk;
  // Human-readable description of the failure.
  std::string message_;
};

/// Either a value or the Status that explains why there is none.
template<typename T>
class Result final
{
public:
  /// A successful result holding `value`.
  Result(T value)  // NOLINT(runtime/explicit): implicit on purpose
  : value_(std::move(value)) {}

  /// A failed result; `status` must not be ok.
  Result(Status status)  // NOLINT(runtime/explicit): implicit on purpose
  : status_(std::move(status)) {}

  /// True when a value is present.
  bool ok() const {return status_.ok();}

  /// The status (ok when a value is present).
  const Status & status() const {return status_;}

  /// The value; only meaningful when ok().
  T & value() {return value_;}

  /// The value; only meaningful when ok().
  const T & value() const {return value_;}

private:
  // Failure description, ok when value_ is valid.
  Status status_;
  // The value, default constructed on failure.
  T value_{};
};

}  // namespace wasm_cpp

#endif  // WASM_CPP__STATUS_HPP_
