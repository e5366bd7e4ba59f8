// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// A seeded native fuzz driver of rmw_wasm_cpp's CDR reader
// (packages/rmw_wasm_cpp/src/detail/cdr.hpp, included as it is), built by
// tests/test_fuzz.py with the host's g++ and -fsanitize=address,undefined
// in a temporary folder (not part of any package build; the host's clang
// has no libFuzzer runtime, so the mutations are this file's own).
//
//   cdr_reader_driver SEED COUNT SEED_FILE...
//
// Each input is a seed (a golden vector's bytes) mutated from SEED: bit
// flips, edge values, 32-bit counts, truncation, inserts. Each is read by a
// traversal that the input's own bytes steer (primitives of 1, 2, 4 and 8
// bytes, arrays of them with a count, bools, strings, wide strings), as the
// typesupport does for any message type. The rules: the sanitizers find
// nothing, the position never passes the end, a failed reader stays failed
// and gives zeros, and a read never takes a long time. Prints
// `ok INPUTS FAILED` at the end.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cdr.hpp"

namespace
{

uint32_t next(uint32_t & state)
{
  state += 0x6d2b79f5u;
  uint32_t t = state;
  t = (t ^ (t >> 15)) * (t | 1u);
  t ^= t + (t ^ (t >> 7)) * (t | 61u);
  return t ^ (t >> 14);
}

std::vector<uint8_t> mutate(std::vector<uint8_t> in, uint32_t & rng)
{
  static const uint32_t edges[] = {0u, 1u, 3u, 4u, 0x7fu, 0x80u, 0xffu, 0xffffu, 0x10000u,
    0x7fffffffu, 0x80000000u, 0xfffffffeu, 0xffffffffu};
  const int rounds = 1 + static_cast<int>(next(rng) % 4);
  for (int r = 0; r < rounds; ++r) {
    const size_t n = in.size();
    const size_t at = n ? next(rng) % n : 0;
    switch (next(rng) % 6) {
      case 0: if (n) {in[at] ^= static_cast<uint8_t>(1u << (next(rng) % 8));} break;
      case 1: if (n) {in[at] = static_cast<uint8_t>(next(rng));} break;
      case 2:
        if (n >= 4) {
          const uint32_t v = edges[next(rng) % (sizeof(edges) / sizeof(edges[0]))];
          const size_t p = next(rng) % (n - 3);
          for (int i = 0; i < 4; ++i) {in[p + i] = static_cast<uint8_t>(v >> (8 * i));}
        }
        break;
      case 3: in.resize(n ? next(rng) % n : 0); break;
      case 4: in.insert(in.begin() + at, 1 + next(rng) % 8, static_cast<uint8_t>(next(rng))); break;
      default: if (n > 1) {in.erase(in.begin() + at, in.begin() + at + 1);} break;
    }
  }
  return in;
}

// Read the whole stream the way the input steers; returns false on a broken rule.
bool traverse(const std::vector<uint8_t> & input, uint32_t steer, std::string & why)
{
  rmw_wasm_cpp::cdr::Reader reader(input.data(), input.size());
  const size_t body = input.size() >= 4 ? input.size() - 4 : 0;
  for (int step = 0; step < 256 && reader.ok(); ++step) {
    const size_t before = reader.body_position();
    switch (next(steer) % 8) {
      case 0: {uint8_t v; reader.primitive(&v, 1); break;}
      case 1: {uint16_t v; reader.primitive(&v, 2); break;}
      case 2: {uint32_t v; reader.primitive(&v, 4); break;}
      case 3: {uint64_t v; reader.primitive(&v, 8); break;}
      case 4: {
          static const size_t sizes[] = {1, 2, 4, 8};
          const size_t size = sizes[next(steer) % 4];
          const size_t count = reader.count(size);
          std::vector<uint8_t> values(size * count + 1);
          reader.primitives(values.data(), size, count);
          break;
        }
      case 5: reader.boolean(); break;
      case 6: {
          const char * data = nullptr;
          size_t length = 0;
          reader.string(&data, &length);
          // every byte the reader hands out lies inside the input
          if (length && (reinterpret_cast<const uint8_t *>(data) < input.data() ||
            reinterpret_cast<const uint8_t *>(data) + length > input.data() + input.size()))
          {
            why = "a string points outside the input";
            return false;
          }
          volatile char sink = 0;
          for (size_t i = 0; i < length; ++i) {sink = static_cast<char>(sink ^ data[i]);}
          break;
        }
      default: {
          const size_t units = reader.wstring_length();
          for (size_t i = 0; i < units; ++i) {reader.wstring_unit();}
          break;
        }
    }
    if (reader.body_position() > body) {
      why = "the position passed the end of the stream";
      return false;
    }
    if (!reader.ok()) {
      // a failed reader stays failed and reads zeros
      uint64_t v = 1;
      reader.primitive(&v, 8);
      if (v != 0 || reader.ok()) {
        why = "a failed reader read a value";
        return false;
      }
    } else if (reader.body_position() < before) {
      why = "the position went back";
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char ** argv)
{
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s SEED COUNT SEED_FILE...\n", argv[0]);
    return 2;
  }
  uint32_t rng = static_cast<uint32_t>(std::strtoul(argv[1], nullptr, 10)) | 1u;
  const long count = std::strtol(argv[2], nullptr, 10);
  std::vector<std::vector<uint8_t>> seeds;
  for (int i = 3; i < argc; ++i) {
    std::ifstream f(argv[i], std::ios::binary);
    seeds.emplace_back(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  }
  long failed = 0;
  for (long n = 0; n < count; ++n) {
    const auto & base = seeds[next(rng) % seeds.size()];
    std::vector<uint8_t> input = n < static_cast<long>(seeds.size()) ? seeds[n] : mutate(base, rng);
    std::string why;
    const uint32_t steer = next(rng);
    if (!traverse(input, steer, why)) {
      std::printf("FINDING %s (input %ld, %zu bytes:", why.c_str(), n, input.size());
      for (uint8_t b : input) {std::printf(" %02x", b);}
      std::printf(")\n");
      return 1;
    }
    rmw_wasm_cpp::cdr::Reader probe(input.data(), input.size());
    if (!probe.ok()) {++failed;}
  }
  std::printf("ok %ld %ld\n", count, failed);
  return 0;
}
