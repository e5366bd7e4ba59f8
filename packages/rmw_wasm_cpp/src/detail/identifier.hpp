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

#ifndef DETAIL__IDENTIFIER_HPP_
#define DETAIL__IDENTIFIER_HPP_

namespace rmw_wasm_cpp
{

/// The implementation identifier of every handle this rmw creates ("rmw_wasm_cpp").
/**
 * rmw's RMW_CHECK_TYPE_IDENTIFIERS_MATCH compares pointers, so every handle
 * stores this very pointer.
 */
extern const char * const kIdentifier;

/// The serialization format of every message on the bus ("cdr").
extern const char * const kSerializationFormat;

}  // namespace rmw_wasm_cpp

#endif  // DETAIL__IDENTIFIER_HPP_
