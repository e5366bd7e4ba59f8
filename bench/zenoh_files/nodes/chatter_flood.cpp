// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// bench/zenoh's publisher in the page: a wasm_cpp node that publishes
// demo_interfaces/msg/Chatter on /bench (KEEP_ALL, RELIABLE: nothing is
// dropped on the bus), one run per line of its standard input:
//
//   SIZE COUNT RATE_HZ     (RATE_HZ 0: as fast as it can)
//
// Each message's text starts with its send time (ns since the epoch, the
// page's clock: performance.timeOrigin + now()) and '|', as the Python
// floor's; its count is its index. After a run it prints
// "RESULT size=S count=N seconds=T" once every message was taken.

#include <emscripten.h>

#include <chrono>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "wasm_cpp/wasm_cpp.hpp"

namespace
{

// The wall clock in ns with the page's resolution (clock_gettime(CLOCK_REALTIME) is
// Date.now(): milliseconds).
EM_JS(double, wall_ms, (), {
  return performance.timeOrigin + performance.now();
});

template<typename T>
T must(wasm_cpp::Result<T> r, const char * what)
{
  if (!r.ok()) {
    std::printf("ERROR %s: %s\n", what, r.status().message().c_str());
    std::exit(3);
  }
  return r.value();
}

// Chatter in CDR: header, string (length, bytes, NUL), padding, uint32 count.
size_t chatter(std::vector<uint8_t> & out, const std::string & text, uint32_t count)
{
  const uint32_t len = static_cast<uint32_t>(text.size() + 1);
  size_t at = 8 + len;
  at += (4 - at % 4) % 4;
  out.assign(at + 4, 0);
  out[1] = 1;
  std::memcpy(out.data() + 4, &len, 4);
  std::memcpy(out.data() + 8, text.data(), text.size());
  std::memcpy(out.data() + at, &count, 4);
  return out.size();
}

}  // namespace

int main()
{
  auto ctx = must(wasm_cpp::Context::make({}), "context");
  auto node = must(wasm_cpp::Node::make(ctx, "zenoh_bench_publisher", "/"), "node");
  wasm_cpp::QoS qos;
  qos.history = wasm_cpp::History::kKeepAll;
  auto pub = must(
    wasm_cpp::Publisher::make(node, "/bench", "demo_interfaces/msg/Chatter", qos), "publisher");
  std::printf("READY\n");
  std::fflush(stdout);
  std::vector<uint8_t> cdr;
  size_t size = 0;
  long count = 0;  // NOLINT(runtime/int)
  double rate = 0;
  while (std::cin >> size >> count >> rate) {
    // the text: a 19-digit stamp, '|', filler; the message is built once, its stamp and count
    // written in place
    const size_t at = chatter(cdr, std::string(19, '0') + "|" + std::string(size > 24 ? size - 24 : 0, 'x'), 0) - 4;
    char stamp[24];
    const auto t0 = std::chrono::steady_clock::now();
    for (long i = 0; i < count; ++i) {  // NOLINT(runtime/int)
      std::snprintf(stamp, sizeof(stamp), "%019" PRId64, static_cast<int64_t>(wall_ms() * 1e6));
      std::memcpy(cdr.data() + 8, stamp, 19);
      const uint32_t n = static_cast<uint32_t>(i);
      std::memcpy(cdr.data() + at, &n, 4);
      wasm_cpp::Status s = pub->publish(cdr.data(), cdr.size());
      if (!s.ok()) {
        std::printf("ERROR publish %ld: %s\n", i, s.message().c_str());
        return 4;
      }
      if (rate > 0) {
        std::this_thread::sleep_until(t0 + std::chrono::duration<double>((i + 1) / rate));
      }
    }
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    pub->wait_for_all_acked(std::chrono::seconds(60));
    std::printf("RESULT size=%zu count=%ld seconds=%.4f\n", size, count, seconds);
    std::fflush(stdout);
  }
  return 0;
}
