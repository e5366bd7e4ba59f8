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

/// \file
/// Check rmw_wasm_cpp's CDR against golden vectors produced by real Fast CDR.
///
/// Arguments: TYPE=HEX items (ROS type name and the stream in hex). For each,
/// the stream is deserialized into a C and a C++ message, both are serialized
/// again and must give the same bytes, and the C++ message is printed as JSON:
///   OK TYPE JSON       or       FAIL TYPE: why
/// tests/test_rmw_cdr.py compares the JSON with the vector's value.

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "json.hpp"
#include "message.hpp"
#include "type_table.hpp"

namespace
{

bool from_hex(const char * hex, std::vector<uint8_t> * out)
{
  const size_t n = std::strlen(hex);
  if (n % 2 != 0) {
    return false;
  }
  for (size_t i = 0; i < n; i += 2) {
    unsigned value = 0;
    if (std::sscanf(hex + i, "%2x", &value) != 1) {
      return false;
    }
    out->push_back(static_cast<uint8_t>(value));
  }
  return true;
}

std::string check_vector(const TypeEntry & entry, const std::vector<uint8_t> & bytes)
{
  std::string json;
  for (bool cpp : {false, true}) {
    const rosidl_message_type_support_t * ts = cpp ? entry.cpp : entry.c;
    Message message(ts, cpp);
    std::string error;
    if (!deserialize(bytes.data(), bytes.size(), ts, message.data(), &error)) {
      return std::string("FAIL ") + entry.name + ": deserialize (" + (cpp ? "C++" : "C") +
             "): " + error;
    }
    std::vector<uint8_t> again;
    if (!serialize(message.data(), ts, &again, &error)) {
      return std::string("FAIL ") + entry.name + ": serialize (" + (cpp ? "C++" : "C") +
             "): " + error;
    }
    if (again != bytes) {
      return std::string("FAIL ") + entry.name + ": " + (cpp ? "C++" : "C") +
             " bytes differ from Fast CDR's:\n  fast cdr " + to_hex(bytes) +
             "\n  rmw_wasm " + to_hex(again);
    }
    if (cpp) {
      json = to_json(message.cpp_members(), message.data());
    }
  }
  return std::string("OK ") + entry.name + " " + json;
}

}  // namespace

int main(int argc, char ** argv)
{
  int failures = 0;
  for (int i = 1; i < argc; ++i) {
    const char * eq = std::strchr(argv[i], '=');
    std::string line;
    std::vector<uint8_t> bytes;
    if (eq == nullptr || !from_hex(eq + 1, &bytes)) {
      line = std::string("FAIL ") + argv[i] + ": expected TYPE=HEX";
    } else {
      const std::string name(argv[i], static_cast<size_t>(eq - argv[i]));
      line = "FAIL " + name + ": type not in the table";
      for (const TypeEntry & entry : type_table()) {
        if (name == entry.name) {
          line = check_vector(entry, bytes);
          break;
        }
      }
    }
    failures += line.compare(0, 3, "OK ") == 0 ? 0 : 1;
    std::printf("%s\n", line.c_str());
  }
  return failures == 0 ? 0 : 1;
}
