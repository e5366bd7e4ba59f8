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
/// Round trip of every message type through rmw_wasm_cpp's CDR, in both layouts.
///
/// For each type of the generated table, for a default-initialized message,
/// two random fillings and one with every bounded field at its bound:
/// - the C and the C++ message (filled alike) serialize to the same bytes;
/// - those bytes deserialize into a fresh C and a fresh C++ message that
///   serialize back to the same bytes;
/// - every strict prefix of the bytes is refused with an error (no crash, no
///   partial success).
/// Then a few malformed streams are checked to be refused with a clear error.
/// Prints one line per type ("PASS <type> <bytes>" or "FAIL <type>: why") and a
/// summary; exits non-zero when anything failed. Optional argument: a type
/// name prefix to test only some types.

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "message.hpp"
#include "type_table.hpp"

namespace
{

struct Failure
{
  std::string what;
};

void check(bool condition, const std::string & what)
{
  if (!condition) {
    throw Failure{what};
  }
}

// Serialize `message` or fail with the rmw error.
std::vector<uint8_t> must_serialize(
  Message & message, const rosidl_message_type_support_t * ts, const char * layout)
{
  std::vector<uint8_t> bytes;
  std::string error;
  check(
    serialize(message.data(), ts, &bytes, &error),
    std::string("rmw_serialize (") + layout + ") failed: " + error);
  return bytes;
}

// Deserialize `bytes` into a fresh message, serialize it again and compare.
void check_round_trip(
  const std::vector<uint8_t> & bytes, const rosidl_message_type_support_t * ts, bool cpp,
  const char * what)
{
  Message fresh(ts, cpp);
  std::string error;
  check(
    deserialize(bytes.data(), bytes.size(), ts, fresh.data(), &error),
    std::string("rmw_deserialize (") + (cpp ? "C++" : "C") + ", " + what + ") failed: " + error);
  std::vector<uint8_t> again = must_serialize(fresh, ts, cpp ? "C++" : "C");
  check(
    again == bytes, std::string("round trip through the ") + (cpp ? "C++" : "C") +
    " layout changed the bytes (" + what + "):\n  sent " + to_hex(bytes) + "\n  got  " +
    to_hex(again));
}

// Every strict prefix of a valid stream must be refused.
void check_prefixes(const std::vector<uint8_t> & bytes, const rosidl_message_type_support_t * ts)
{
  Message target(ts, true);
  for (size_t length = 0; length < bytes.size(); ++length) {
    std::string error;
    check(
      !deserialize(bytes.data(), length, ts, target.data(), &error),
      "a prefix of " + std::to_string(length) + " of the " + std::to_string(bytes.size()) +
      " bytes was accepted");
    check(!error.empty(), "a refused prefix left no error message");
  }
}

void test_type(const TypeEntry & entry, size_t * size_out)
{
  const struct
  {
    const char * name;
    uint64_t seed;
    Lengths lengths;
  } cases[] = {
    {"defaults", 0, Lengths::kRandom},
    {"random 1", 1, Lengths::kRandom},
    {"random 2", 2, Lengths::kRandom},
    {"bounds at maximum", 3, Lengths::kMaximum},
  };
  for (const auto & c : cases) {
    Message c_message(entry.c, false);
    Message cpp_message(entry.cpp, true);
    if (c.seed != 0) {
      Rng c_rng(c.seed);
      Rng cpp_rng(c.seed);
      c_message.fill(c_rng, c.lengths);
      cpp_message.fill(cpp_rng, c.lengths);
    }
    const std::vector<uint8_t> c_bytes = must_serialize(c_message, entry.c, "C");
    const std::vector<uint8_t> cpp_bytes = must_serialize(cpp_message, entry.cpp, "C++");
    check(
      c_bytes == cpp_bytes, std::string("the C and C++ layouts serialize differently (") +
      c.name + "):\n  C   " + to_hex(c_bytes) + "\n  C++ " + to_hex(cpp_bytes));
    check(
      c_bytes.size() >= 5 && c_bytes[0] == 0 && c_bytes[1] == 1 && c_bytes[2] == 0 &&
      c_bytes[3] == 0, "the stream does not start with the header 00 01 00 00");
    check_round_trip(c_bytes, entry.c, false, c.name);
    check_round_trip(c_bytes, entry.cpp, true, c.name);
    if (c.seed == 1) {
      check_prefixes(c_bytes, entry.cpp);
      *size_out = c_bytes.size();
    }
  }
}

const TypeEntry * find_type(const char * name)
{
  for (const auto & entry : type_table()) {
    if (std::strcmp(entry.name, name) == 0) {
      return &entry;
    }
  }
  return nullptr;
}

// A malformed stream must be refused with an error that contains `expected`.
void expect_refused(
  const char * type_name, const std::vector<uint8_t> & bytes, const std::string & expected,
  const char * label, int * failures)
{
  const TypeEntry * entry = find_type(type_name);
  if (entry == nullptr) {
    std::printf("FAIL malformed/%s: type %s is not in the table\n", label, type_name);
    ++*failures;
    return;
  }
  for (bool cpp : {false, true}) {
    Message message(cpp ? entry->cpp : entry->c, cpp);
    std::string error;
    if (deserialize(bytes.data(), bytes.size(), cpp ? entry->cpp : entry->c, message.data(),
      &error))
    {
      std::printf("FAIL malformed/%s: accepted %s\n", label, to_hex(bytes).c_str());
      ++*failures;
      return;
    }
    if (error.find(expected) == std::string::npos) {
      std::printf(
        "FAIL malformed/%s: error '%s' does not mention '%s'\n", label, error.c_str(),
        expected.c_str());
      ++*failures;
      return;
    }
  }
  std::printf("PASS malformed/%s\n", label);
}

// Over-bound values must be refused when serializing, naming the field.
void expect_unserializable(
  const char * type_name, const char * field, const std::string & expected, int * failures)
{
  const TypeEntry * entry = find_type(type_name);
  if (entry == nullptr) {
    std::printf("FAIL overbound/%s: type %s is not in the table\n", field, type_name);
    ++*failures;
    return;
  }
  Message message(entry->cpp, true);
  const auto * members = message.cpp_members();
  for (uint32_t i = 0; i < members->member_count_; ++i) {
    const auto & member = members->members_[i];
    if (std::strcmp(member.name_, field) != 0) {
      continue;
    }
    void * data = static_cast<uint8_t *>(message.data()) + member.offset_;
    if (member.type_id_ == rosidl_typesupport_introspection_c__ROS_TYPE_STRING) {
      *static_cast<std::string *>(data) = std::string(member.string_upper_bound_ + 1, 'x');
    } else {
      member.resize_function(data, member.array_size_ + 1);
    }
    std::vector<uint8_t> bytes;
    std::string error;
    if (serialize(message.data(), entry->cpp, &bytes, &error)) {
      std::printf("FAIL overbound/%s: serialized anyway\n", field);
      ++*failures;
    } else if (error.find(expected) == std::string::npos ||
      error.find(field) == std::string::npos)
    {
      std::printf(
        "FAIL overbound/%s: error '%s' should name the field and say '%s'\n", field,
        error.c_str(), expected.c_str());
      ++*failures;
    } else {
      std::printf("PASS overbound/%s\n", field);
    }
    return;
  }
  std::printf("FAIL overbound/%s: no such field in %s\n", field, type_name);
  ++*failures;
}

int check_malformed()
{
  int failures = 0;
  // bool[<=3] bool_values comes first: a count of 4 is over the bound.
  expect_refused(
    "test_msgs/msg/BoundedPlainSequences", {0, 1, 0, 0, 4, 0, 0, 0, 1, 1, 1, 1},
    "exceeds its bound of 3", "count over bound", &failures);
  // A huge count must be refused before anything is allocated.
  expect_refused(
    "test_msgs/msg/UnboundedSequences", {0, 1, 0, 0, 0xff, 0xff, 0xff, 0xff, 1},
    "element count 4294967295", "huge count", &failures);
  expect_refused(
    "std_msgs/msg/String", {0, 1, 0, 0, 0xf0, 0xff, 0xff, 0x7f, 'a', 0},
    "CDR stream ends", "string longer than the stream", &failures);
  expect_refused(
    "std_msgs/msg/Int32", {0x00, 0x07, 0x00, 0x00, 1, 2, 3, 4},
    "encapsulation header 00 07 00 00", "not plain CDR", &failures);
  expect_refused("std_msgs/msg/Int32", {0x00, 0x01}, "shorter than the 4-byte", "no header",
    &failures);
  expect_unserializable(
    "test_msgs/msg/BoundedPlainSequences", "int32_values", "exceeds its bound", &failures);
  expect_unserializable("test_msgs/msg/Strings", "bounded_string_value", "exceeds its bound",
    &failures);
  // A big-endian stream (Fast CDR can read both) is read too.
  {
    const TypeEntry * entry = find_type("std_msgs/msg/Int32");
    const std::vector<uint8_t> big = {0x00, 0x00, 0x00, 0x00, 0x01, 0x02, 0x03, 0x04};
    std::string error = "std_msgs/msg/Int32 is not in the table";
    int32_t value = 0;
    if (entry != nullptr) {
      Message message(entry->cpp, true);
      if (deserialize(big.data(), big.size(), entry->cpp, message.data(), &error)) {
        std::memcpy(&value, message.data(), sizeof(value));
      }
    }
    if (value == 0x01020304) {
      std::printf("PASS malformed/big endian read\n");
    } else {
      std::printf("FAIL malformed/big endian read: got %d (%s)\n", value, error.c_str());
      ++failures;
    }
  }
  return failures;
}

}  // namespace

int main(int argc, char ** argv)
{
  const char * filter = argc > 1 ? argv[1] : "";
  size_t tested = 0;
  int failures = 0;
  for (const TypeEntry & entry : type_table()) {
    if (std::strncmp(entry.name, filter, std::strlen(filter)) != 0) {
      continue;
    }
    ++tested;
    size_t size = 0;
    try {
      test_type(entry, &size);
      std::printf("PASS %s %zu\n", entry.name, size);
    } catch (const Failure & failure) {
      std::printf("FAIL %s: %s\n", entry.name, failure.what.c_str());
      ++failures;
    }
  }
  if (filter[0] == '\0') {
    failures += check_malformed();
  }
  std::printf("SUMMARY %zu types, %d failures\n", tested, failures);
  return failures == 0 ? 0 : 1;
}
