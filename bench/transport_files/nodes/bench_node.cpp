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

// bench/transport's wasm_cpp nodes (the real path: wait set, take into a
// malloc'd buffer, publish from the wasm heap).
//
//   bench_node ping  --size S --count N --warmup W   latency (ping-pong)
//   bench_node pong  --size S                          echoes /bench/ping
//   bench_node flood --size S --count N --subs K       publishes as fast as it can
//   bench_node sink  --size S --count N                counts, checks order
//   bench_node hello                                   publishes one message at once
//   bench_node loop  --size S --count N                publish/take cost in one thread
//
// Each prints "RESULT key=value ...".

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "wasm_cpp/wasm_cpp.hpp"

using Clock = std::chrono::steady_clock;
using wasm_cpp::Message;
using wasm_cpp::MessageInfo;
using wasm_cpp::QoS;
using wasm_cpp::WaitItem;

namespace
{

std::map<std::string, std::string> g_opts;

long opt(const std::string & key, long fallback)  // NOLINT(runtime/int)
{
  auto it = g_opts.find(key);
  return it == g_opts.end() ? fallback : std::strtol(it->second.c_str(), nullptr, 10);
}

template<typename T>
T must(wasm_cpp::Result<T> r, const char * what)
{
  if (!r.ok()) {
    std::printf("ERROR %s: %s\n", what, r.status().message().c_str());
    std::exit(3);
  }
  return r.value();
}

struct Node
{
  std::shared_ptr<wasm_cpp::Context> ctx;
  std::shared_ptr<wasm_cpp::Node> node;
  std::shared_ptr<wasm_cpp::WaitSet> ws;
  std::shared_ptr<wasm_cpp::GuardCondition> graph;

  explicit Node(const char * name)
  {
    wasm_cpp::ContextOptions o;
    o.keep_all_depth = static_cast<size_t>(opt("depth", 256));
    ctx = must(wasm_cpp::Context::make(o), "context");
    node = must(wasm_cpp::Node::make(ctx, name, "/"), "node");
    ws = must(wasm_cpp::WaitSet::make(ctx), "wait set");
    graph = must(wasm_cpp::GuardCondition::make_graph(ctx), "graph guard");
  }

  template<typename Pred>
  void wait_graph(Pred pred)
  {
    while (!pred()) {
      std::vector<WaitItem> items{WaitItem::of(graph.get())};
      ws->wait(items, std::chrono::seconds(30));
    }
  }

  bool take_one(wasm_cpp::Subscription & sub, Message * m, MessageInfo * info)
  {
    bool taken = false;
    for (;;) {
      if (!sub.take(m, info, &taken).ok()) {
        return false;
      }
      if (taken) {
        return true;
      }
      std::vector<WaitItem> items{WaitItem::of(&sub)};
      if (!ws->wait(items, std::chrono::seconds(30)).ok()) {
        return false;
      }
    }
  }
};

QoS latency_qos()
{
  QoS q;
  q.history = wasm_cpp::History::kKeepLast;
  q.depth = 16;
  return q;
}

QoS flood_qos()
{
  QoS q;
  q.history = wasm_cpp::History::kKeepAll;
  return q;
}

int ping()
{
  Node n("bench_ping");
  const size_t size = static_cast<size_t>(opt("size", 64));
  const long count = opt("count", 1000);  // NOLINT(runtime/int)
  const long warmup = opt("warmup", 100);  // NOLINT(runtime/int)
  auto pub = must(wasm_cpp::Publisher::make(n.node, "/bench/ping", "bench/msg/Bytes", latency_qos()), "pub");
  auto sub = must(wasm_cpp::Subscription::make(n.node, "/bench/pong", "bench/msg/Bytes", latency_qos()), "sub");
  n.wait_graph([&]() {return pub->matched_subscription_count() > 0 && sub->matched_publisher_count() > 0;});
  // Let the start-up work of both processes (their pthread pools' last
  // garbage collections, JIT) finish before measuring.
  std::this_thread::sleep_for(std::chrono::milliseconds(opt("settle-ms", 0)));
  std::vector<uint8_t> payload(size, 0x5a);
  std::vector<double> rtt;
  rtt.reserve(static_cast<size_t>(count));
  Message m;
  MessageInfo info;
  for (long i = 0; i < warmup + count; ++i) {  // NOLINT(runtime/int)
    std::memcpy(payload.data(), &i, std::min(sizeof(i), size));
    auto t0 = Clock::now();
    if (!pub->publish(payload.data(), payload.size()).ok() || !n.take_one(*sub, &m, &info)) {
      std::printf("ERROR ping %ld failed\n", i);
      return 4;
    }
    const double us = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    if (m.size != size || std::memcmp(m.data.get(), payload.data(), std::min<size_t>(size, 8)) != 0) {
      std::printf("ERROR ping %ld: wrong echo\n", i);
      return 5;
    }
    if (i >= warmup) {
      rtt.push_back(us / 2);
    }
  }
  // Tell the echo node to stop: an empty message.
  pub->publish(payload.data(), 0);
  std::sort(rtt.begin(), rtt.end());
  auto pct = [&](double p) {return rtt[std::min(rtt.size() - 1, static_cast<size_t>(p * rtt.size()))];};
  std::printf(
    "RESULT size=%zu count=%zu p50_us=%.2f p99_us=%.2f min_us=%.2f max_us=%.2f\n",
    size, rtt.size(), pct(0.5), pct(0.99), rtt.front(), rtt.back());
  return 0;
}

int pong()
{
  Node n("bench_pong");
  auto sub = must(wasm_cpp::Subscription::make(n.node, "/bench/ping", "bench/msg/Bytes", latency_qos()), "sub");
  auto pub = must(wasm_cpp::Publisher::make(n.node, "/bench/pong", "bench/msg/Bytes", latency_qos()), "pub");
  Message m;
  MessageInfo info;
  long echoed = 0;  // NOLINT(runtime/int)
  while (n.take_one(*sub, &m, &info) && m.size > 0) {
    pub->publish(m.data.get(), m.size);
    ++echoed;
  }
  std::printf("RESULT echoed=%ld\n", echoed);
  return 0;
}

int flood()
{
  Node n("bench_flood");
  const size_t size = static_cast<size_t>(opt("size", 1024));
  const long count = opt("count", 100000);  // NOLINT(runtime/int)
  const size_t subs = static_cast<size_t>(opt("subs", 1));
  auto pub = must(wasm_cpp::Publisher::make(n.node, "/bench/flood", "bench/msg/Bytes", flood_qos()), "pub");
  n.wait_graph([&]() {return pub->matched_subscription_count() >= subs;});
  std::vector<uint8_t> payload(size, 0x33);
  auto t0 = Clock::now();
  for (long i = 0; i < count; ++i) {  // NOLINT(runtime/int)
    std::memcpy(payload.data(), &i, std::min(sizeof(i), size));
    wasm_cpp::Status s = pub->publish(payload.data(), payload.size());
    if (!s.ok()) {
      std::printf("ERROR publish %ld: %s\n", i, s.message().c_str());
      return 4;
    }
  }
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  pub->wait_for_all_acked(std::chrono::seconds(60));
  std::printf("RESULT published=%ld publish_ms=%.2f\n", count, ms);
  return 0;
}

int sink()
{
  Node n("bench_sink");
  const long count = opt("count", 100000);  // NOLINT(runtime/int)
  const size_t size = static_cast<size_t>(opt("size", 1024));
  auto sub = must(wasm_cpp::Subscription::make(n.node, "/bench/flood", "bench/msg/Bytes", flood_qos()), "sub");
  std::printf("RESULT ready=1\n");
  std::fflush(stdout);
  Message m;
  MessageInfo info;
  long got = 0;  // NOLINT(runtime/int)
  long disorder = 0;  // NOLINT(runtime/int)
  Clock::time_point first;
  uint64_t expect = 1;
  while (got < count && n.take_one(*sub, &m, &info)) {
    if (got == 0) {
      first = Clock::now();
    }
    if (info.publication_sequence_number != expect || m.size != size) {
      ++disorder;
    }
    expect = info.publication_sequence_number + 1;
    ++got;
  }
  const double s = std::chrono::duration<double>(Clock::now() - first).count();
  // The first message started the clock: count-1 intervals.
  const double rate = static_cast<double>(got - 1) / s;
  std::printf(
    "RESULT received=%ld disorder=%ld seconds=%.4f msgs_per_s=%.0f mb_per_s=%.1f\n",
    got, disorder, s, rate, rate * static_cast<double>(size) / 1e6);
  return 0;
}

// Per-operation cost without wake-ups: publish a batch, then take it, in one thread.
int loop()
{
  Node n("bench_loop");
  const size_t size = static_cast<size_t>(opt("size", 1024));
  const long count = opt("count", 200000);  // NOLINT(runtime/int)
  auto pub = must(wasm_cpp::Publisher::make(n.node, "/bench/loop", "bench/msg/Bytes", flood_qos()), "pub");
  auto sub = must(wasm_cpp::Subscription::make(n.node, "/bench/loop", "bench/msg/Bytes", flood_qos()), "sub");
  std::vector<uint8_t> payload(size, 0x11);
  Message m;
  MessageInfo info;
  double pub_s = 0;
  double take_s = 0;
  const long batch = 256;  // NOLINT(runtime/int)
  for (long done = 0; done < count; done += batch) {  // NOLINT(runtime/int)
    auto t0 = Clock::now();
    for (long i = 0; i < batch; ++i) {  // NOLINT(runtime/int)
      pub->publish(payload.data(), payload.size());
    }
    auto t1 = Clock::now();
    for (long i = 0; i < batch; ++i) {  // NOLINT(runtime/int)
      bool taken = false;
      sub->take(&m, &info, &taken);
      if (!taken) {
        std::printf("ERROR loop: message missing\n");
        return 4;
      }
    }
    auto t2 = Clock::now();
    pub_s += std::chrono::duration<double>(t1 - t0).count();
    take_s += std::chrono::duration<double>(t2 - t1).count();
  }
  std::printf(
    "RESULT size=%zu publish_ns=%.0f take_ns=%.0f\n", size, pub_s * 1e9 / count,
    take_s * 1e9 / count);
  return 0;
}

int hello()
{
  Node n("bench_hello");
  auto pub = must(wasm_cpp::Publisher::make(n.node, "/bench/hello", "bench/msg/Bytes", QoS()), "pub");
  uint8_t b = 1;
  pub->publish(&b, 1);
  std::printf("RESULT hello=1\n");
  return 0;
}

}  // namespace

int main(int argc, char ** argv)
{
  if (argc < 2) {
    std::printf("usage: bench_node ping|pong|flood|sink|hello [--key value]...\n");
    return 2;
  }
  for (int i = 2; i + 1 < argc; i += 2) {
    g_opts[std::string(argv[i]).substr(2)] = argv[i + 1];
  }
  const std::string role = argv[1];
  if (role == "ping") {return ping();}
  if (role == "pong") {return pong();}
  if (role == "flood") {return flood();}
  if (role == "sink") {return sink();}
  if (role == "hello") {return hello();}
  if (role == "loop") {return loop();}
  std::printf("ERROR unknown role %s\n", role.c_str());
  return 2;
}
