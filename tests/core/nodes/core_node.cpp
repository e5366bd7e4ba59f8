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

// One test executable with many roles, so the core tests compile once.
//
//   core_node ROLE [--option value]...
//
// Every role prints machine-readable lines "RESULT key=value ..." that the
// tests parse, and exits 0 on success (non-zero with an "ERROR ..." line
// otherwise). Payloads carry [u32 index][u32 tag] then bytes (index + i) & 255,
// so receivers check order, origin and content.

#include <atomic>
#include <chrono>
#include <cinttypes>
#include <condition_variable>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "wasm_cpp/wasm_cpp.hpp"

using wasm_cpp::Client;
using wasm_cpp::Context;
using wasm_cpp::Event;
using wasm_cpp::EventStatus;
using wasm_cpp::EventType;
using wasm_cpp::GuardCondition;
using wasm_cpp::Message;
using wasm_cpp::MessageInfo;
using wasm_cpp::Node;
using wasm_cpp::Publisher;
using wasm_cpp::QoS;
using wasm_cpp::Service;
using wasm_cpp::ServiceInfo;
using wasm_cpp::Status;
using wasm_cpp::Subscription;
using wasm_cpp::WaitItem;
using wasm_cpp::WaitSet;
using Clock = std::chrono::steady_clock;

namespace
{

std::map<std::string, std::string> g_opts;

std::string opt(const std::string & key, const std::string & fallback = "")
{
  auto it = g_opts.find(key);
  return it == g_opts.end() ? fallback : it->second;
}

long opt_int(const std::string & key, long fallback)  // NOLINT(runtime/int)
{
  auto it = g_opts.find(key);
  return it == g_opts.end() ? fallback : std::strtol(it->second.c_str(), nullptr, 10);
}

void out(const char * fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  std::vprintf(fmt, ap);
  va_end(ap);
  std::printf("\n");
  std::fflush(stdout);
}

[[noreturn]] void fail(const std::string & what, const Status & s)
{
  std::printf("ERROR %s: %s\n", what.c_str(), s.message().c_str());
  std::fflush(stdout);
  std::exit(3);
}

template<typename T>
T must(wasm_cpp::Result<T> r, const std::string & what)
{
  if (!r.ok()) {
    fail(what, r.status());
  }
  return r.value();
}

double ms_since(Clock::time_point t0)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// "keep_all", "keep_last:N", "best_effort:N", "transient_local:N", optional
// suffixes ",deadline_ms=..", ",lifespan_ms=..", ",manual_lease_ms=..".
QoS parse_qos(const std::string & spec)
{
  QoS q;
  size_t start = 0;
  while (start <= spec.size()) {
    size_t end = spec.find(',', start);
    std::string part = spec.substr(start, end == std::string::npos ? std::string::npos : end - start);
    std::string key = part;
    std::string value;
    size_t sep = part.find_first_of(":=");
    if (sep != std::string::npos) {
      key = part.substr(0, sep);
      value = part.substr(sep + 1);
    }
    const int64_t ms = value.empty() ? 0 : std::atoll(value.c_str());
    if (key == "keep_all") {
      q.history = wasm_cpp::History::kKeepAll;
    } else if (key == "keep_last") {
      q.history = wasm_cpp::History::kKeepLast;
      q.depth = static_cast<size_t>(ms);
    } else if (key == "best_effort") {
      q.reliability = wasm_cpp::Reliability::kBestEffort;
      if (ms) {q.depth = static_cast<size_t>(ms);}
    } else if (key == "transient_local") {
      q.durability = wasm_cpp::Durability::kTransientLocal;
      if (ms) {q.depth = static_cast<size_t>(ms);}
    } else if (key == "deadline_ms") {
      q.deadline = ms * 1000000;
    } else if (key == "lifespan_ms") {
      q.lifespan = ms * 1000000;
    } else if (key == "manual_lease_ms") {
      q.liveliness = wasm_cpp::Liveliness::kManualByTopic;
      q.liveliness_lease_duration = ms * 1000000;
    } else if (!key.empty()) {
      std::printf("ERROR unknown qos part '%s'\n", key.c_str());
      std::exit(2);
    }
    if (end == std::string::npos) {
      break;
    }
    start = end + 1;
  }
  return q;
}

// The non-empty fields of `text` separated by `sep`.
std::vector<std::string> split(const std::string & text, char sep)
{
  std::vector<std::string> fields;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find(sep, start);
    if (end == std::string::npos) {
      end = text.size();
    }
    if (end > start) {
      fields.push_back(text.substr(start, end - start));
    }
    start = end + 1;
  }
  return fields;
}

std::vector<uint8_t> make_payload(uint32_t index, uint32_t tag, size_t size)
{
  std::vector<uint8_t> p(std::max<size_t>(size, 8));
  std::memcpy(&p[0], &index, 4);
  std::memcpy(&p[4], &tag, 4);
  for (size_t i = 8; i < p.size(); ++i) {
    p[i] = static_cast<uint8_t>((index + i) & 255);
  }
  return p;
}

bool check_payload(const Message & m, uint32_t * index, uint32_t * tag)
{
  if (m.size < 8) {
    return false;
  }
  std::memcpy(index, m.data.get(), 4);
  std::memcpy(tag, m.data.get() + 4, 4);
  for (size_t i = 8; i < m.size; ++i) {
    if (m.data[i] != static_cast<uint8_t>((*index + i) & 255)) {
      return false;
    }
  }
  return true;
}

struct Env
{
  std::shared_ptr<Context> ctx;
  std::shared_ptr<Node> node;
  std::shared_ptr<WaitSet> ws;
  std::shared_ptr<GuardCondition> graph;
};

Env make_env(const std::string & default_name)
{
  Env e;
  wasm_cpp::ContextOptions o;
  o.domain_id = wasm_cpp::kDefaultDomainId;
  o.publish_timeout = std::chrono::milliseconds(opt_int("publish-timeout-ms", 10000));
  o.keep_all_depth = static_cast<size_t>(opt_int("keep-all-depth", 1000));
  e.ctx = must(Context::make(o), "context");
  e.node = must(Node::make(e.ctx, opt("name", default_name), opt("ns", "/")), "node");
  e.ws = must(WaitSet::make(e.ctx), "wait set");
  e.graph = must(GuardCondition::make_graph(e.ctx), "graph guard");
  if (e.node->name_was_taken()) {
    // The ROS console format, so the runtime reports severity WARN.
    const double now_s = std::chrono::duration<double>(
      std::chrono::system_clock::now().time_since_epoch()).count();
    out(
      "[WARN] [%.9f] [%s]: node name '%s' is already in use", now_s, e.node->name().c_str(),
      e.node->fully_qualified_name().c_str());
  }
  return e;
}

// Block on the graph guard until pred() holds (no polling: graph changes wake us).
template<typename Pred>
bool wait_graph(Env & e, Pred pred, long timeout_ms)  // NOLINT(runtime/int)
{
  auto t0 = Clock::now();
  while (!pred()) {
    double left = static_cast<double>(timeout_ms) - ms_since(t0);
    if (left <= 0) {
      return false;
    }
    std::vector<WaitItem> items{WaitItem::of(e.graph.get())};
    e.ws->wait(items, std::chrono::microseconds(static_cast<int64_t>(left * 1000)));
  }
  return true;
}

// Wait for one message on a signal topic.
void wait_signal(Env & e, const std::string & topic)
{
  QoS q;
  q.durability = wasm_cpp::Durability::kTransientLocal;
  q.depth = 1;
  auto sub = must(Subscription::make(e.node, topic, "test_msgs/msg/Signal", q), "signal sub");
  for (;;) {
    std::vector<WaitItem> items{WaitItem::of(sub.get())};
    e.ws->wait(items, wasm_cpp::kForever);
    Message m;
    bool taken = false;
    if (sub->take(&m, nullptr, &taken).ok() && taken) {
      return;
    }
  }
}

void send_signal(Env & e, const std::string & topic)
{
  QoS q;
  q.durability = wasm_cpp::Durability::kTransientLocal;
  q.depth = 1;
  static std::vector<std::shared_ptr<Publisher>> keep;
  auto pub = must(Publisher::make(e.node, topic, "test_msgs/msg/Signal", q), "signal pub");
  // The receiver may not have subscribed yet; its signal must not be lost.
  if (!wait_graph(e, [&]() {return pub->matched_subscription_count() > 0;}, 20000)) {
    out("ERROR nobody subscribed to signal %s", topic.c_str());
    std::exit(4);
  }
  uint8_t b = 1;
  Status s = pub->publish(&b, 1);
  if (!s.ok()) {
    fail("signal", s);
  }
  keep.push_back(pub);
}

// ------------------------------------------------------------------ roles

int role_pub()
{
  Env e = make_env("pub");
  const std::string topic = opt("topic", "/chatter");
  const long count = opt_int("count", 10);  // NOLINT(runtime/int)
  const size_t size = static_cast<size_t>(opt_int("size", 16));
  // --sizes a,b,c: message i has size sizes[i % n] (instead of --size).
  std::vector<size_t> sizes;
  for (const std::string & s : split(opt("sizes"), ',')) {
    sizes.push_back(static_cast<size_t>(std::strtol(s.c_str(), nullptr, 10)));
  }
  const uint32_t tag = static_cast<uint32_t>(opt_int("tag", 1));
  auto pub = must(
    Publisher::make(e.node, topic, opt("type", "test_msgs/msg/Bytes"), parse_qos(opt("qos", ""))),
    "publisher");
  const long want = opt_int("wait-matched", 1);  // NOLINT(runtime/int)
  if (!wait_graph(e, [&]() {return static_cast<long>(pub->matched_subscription_count()) >= want;},  // NOLINT
      opt_int("match-timeout-ms", 20000)))
  {
    out("ERROR only %zu of %ld subscriptions matched", pub->matched_subscription_count(), want);
    return 4;
  }
  out("RESULT matched=%zu", pub->matched_subscription_count());
  const long period_us = opt_int("period-us", 0);  // NOLINT(runtime/int)
  auto t0 = Clock::now();
  long failures = 0;  // NOLINT(runtime/int)
  for (long i = 0; count < 0 || i < count; ++i) {  // NOLINT(runtime/int)
    std::vector<uint8_t> p = make_payload(
      static_cast<uint32_t>(i), tag,
      sizes.empty() ? size : sizes[static_cast<size_t>(i) % sizes.size()]);
    Status s = pub->publish(p.data(), p.size());
    if (!s.ok()) {
      out("ERROR publish %ld: %s", i, s.message().c_str());
      if (++failures > 0) {
        return 5;
      }
    }
    if (opt_int("abort-after", -1) == i) {
      out("RESULT aborting_after=%ld", i);
      std::abort();
    }
    if (opt_int("trap-after", -1) == i) {
      // A wasm trap ("unreachable"): no abort hook runs, only the error it throws.
      out("RESULT trapping_after=%ld", i);
      __builtin_trap();
    }
    if (i == opt_int("progress-at", -1)) {
      out("RESULT progress=%ld", i);
    }
    if (period_us > 0) {
      std::this_thread::sleep_for(std::chrono::microseconds(period_us));
    }
  }
  out("RESULT published=%ld ms=%.1f", count, ms_since(t0));
  if (!opt("signal").empty()) {
    send_signal(e, opt("signal"));
  }
  if (opt("acked") == "1") {
    Status s = pub->wait_for_all_acked(std::chrono::seconds(20));
    out("RESULT acked=%d", s.ok() ? 1 : 0);
  }
  if (opt("hold") == "1") {
    wait_signal(e, opt("hold-topic", "/test/release"));
  }
  return 0;
}

int role_sub()
{
  Env e = make_env("sub");
  const std::string topic = opt("topic", "/chatter");
  const long count = opt_int("count", 10);  // NOLINT(runtime/int)
  wasm_cpp::SubscriptionOptions so;
  so.ignore_local_publications = opt("ignore-local") == "1";
  auto sub = must(
    Subscription::make(
      e.node, topic, opt("type", "test_msgs/msg/Bytes"), parse_qos(opt("qos", "")), so),
    "subscription");
  out("RESULT subscribed=1");
  if (!opt("wait-signal").empty()) {
    wait_signal(e, opt("wait-signal"));
  }
  std::map<uint32_t, uint32_t> next_by_tag;
  std::map<uint32_t, long> count_by_tag;  // NOLINT(runtime/int)
  std::vector<uint32_t> indices;
  long got = 0;  // NOLINT(runtime/int)
  long bad = 0;  // NOLINT(runtime/int)
  long out_of_order = 0;  // NOLINT(runtime/int)
  uint64_t last_seq = 0;
  const long timeout_ms = opt_int("timeout-ms", 30000);  // NOLINT(runtime/int)
  const bool drain = opt("drain") == "1";
  auto t0 = Clock::now();
  while (count < 0 || got < count) {
    double left = static_cast<double>(timeout_ms) - ms_since(t0);
    if (drain || left <= 0) {
      if (!drain) {
        out("RESULT timeout=1");
      }
      if (!drain || !sub->has_data()) {
        break;
      }
    } else {
      std::vector<WaitItem> items{WaitItem::of(sub.get())};
      Status ws = e.ws->wait(items, std::chrono::microseconds(static_cast<int64_t>(left * 1000)));
      if (!ws.ok() && ws.code() != wasm_cpp::Code::kTimeout) {
        fail("wait", ws);
      }
    }
    Message m;
    MessageInfo info;
    bool taken = false;
    while ((count < 0 || got < count) && sub->take(&m, &info, &taken).ok() && taken) {
      uint32_t index = 0;
      uint32_t tag = 0;
      if (!check_payload(m, &index, &tag)) {
        ++bad;
        continue;
      }
      if (next_by_tag.count(tag) && index != next_by_tag[tag]) {
        ++out_of_order;
      }
      next_by_tag[tag] = index + 1;
      ++count_by_tag[tag];
      if (info.publication_sequence_number != index + 1u) {
        ++out_of_order;
      }
      if (info.reception_sequence_number != last_seq + 1) {
        ++bad;
      }
      last_seq = info.reception_sequence_number;
      if (indices.size() < 64) {
        indices.push_back(index);
      }
      ++got;
      if (got == opt_int("report-at", -1)) {
        out("RESULT progress=%ld publishers=%zu", got, sub->matched_publisher_count());
      }
    }
  }
  std::string list;
  for (uint32_t i : indices) {
    list += (list.empty() ? "" : ",") + std::to_string(i);
  }
  std::string tags;
  for (auto & kv : count_by_tag) {
    tags += (tags.empty() ? "" : ",") + std::to_string(kv.first) + ":" + std::to_string(kv.second);
  }
  EventStatus lost;
  bool changed = false;
  auto lost_ev = must(Event::make(sub, EventType::kMessageLost), "lost event");
  lost_ev->take(&lost, &changed);
  out(
    "RESULT received=%ld bad=%ld out_of_order=%ld indices=%s tags=%s lost=%" PRId64
    " publishers=%zu ms=%.1f", got, bad, out_of_order, list.empty() ? "-" : list.c_str(),
    tags.empty() ? "-" : tags.c_str(), lost.total_count, sub->matched_publisher_count(),
    ms_since(t0));
  if (!opt("signal").empty()) {
    send_signal(e, opt("signal"));
  }
  return bad == 0 ? 0 : 6;
}

int role_server()
{
  Env e = make_env("server");
  auto srv = must(
    Service::make(
      e.node, opt("service", "/echo"), "test_msgs/srv/Echo", wasm_cpp::services_default_qos()),
    "service");
  const long count = opt_int("count", -1);  // NOLINT(runtime/int)
  const uint32_t tag = static_cast<uint32_t>(opt_int("tag", 7));
  out("RESULT serving=1");
  long served = 0;  // NOLINT(runtime/int)
  while (count < 0 || served < count) {
    std::vector<WaitItem> items{WaitItem::of(srv.get())};
    e.ws->wait(items, wasm_cpp::kForever);
    Message m;
    ServiceInfo info;
    bool taken = false;
    while (srv->take_request(&m, &info, &taken).ok() && taken) {
      // Response: the request bytes, then the server tag and the request's sequence number.
      std::vector<uint8_t> resp(m.data.get(), m.data.get() + m.size);
      resp.resize(m.size + 12);
      std::memcpy(&resp[m.size], &tag, 4);
      std::memcpy(&resp[m.size + 4], &info.request_id.sequence_number, 8);
      Status s = srv->send_response(info.request_id, resp.data(), resp.size());
      if (!s.ok()) {
        fail("send_response", s);
      }
      ++served;
    }
  }
  out("RESULT served=%ld", served);
  return 0;
}

int role_client()
{
  Env e = make_env("client");
  auto cli = must(
    Client::make(
      e.node, opt("service", "/echo"), "test_msgs/srv/Echo", wasm_cpp::services_default_qos()),
    "client");
  if (!wait_graph(e, [&]() {return cli->server_is_available();}, 20000)) {
    out("ERROR no server");
    return 4;
  }
  const long n = opt_int("requests", 10);  // NOLINT(runtime/int)
  const uint32_t me = static_cast<uint32_t>(opt_int("tag", 1));
  std::map<int64_t, uint32_t> sent;  // sequence number -> request index
  for (long i = 0; i < n; ++i) {  // NOLINT(runtime/int)
    std::vector<uint8_t> req = make_payload(static_cast<uint32_t>(i), me, 24);
    int64_t seq = 0;
    Status s = cli->send_request(req.data(), req.size(), &seq);
    if (!s.ok()) {
      fail("send_request", s);
    }
    sent[seq] = static_cast<uint32_t>(i);
  }
  long ok = 0;  // NOLINT(runtime/int)
  long wrong = 0;  // NOLINT(runtime/int)
  auto t0 = Clock::now();
  while (ok + wrong < n && ms_since(t0) < 20000) {
    std::vector<WaitItem> items{WaitItem::of(cli.get())};
    e.ws->wait(items, std::chrono::seconds(20));
    Message m;
    ServiceInfo info;
    bool taken = false;
    while (cli->take_response(&m, &info, &taken).ok() && taken) {
      auto it = sent.find(info.request_id.sequence_number);
      uint32_t index = 0;
      uint32_t tag = 0;
      int64_t echoed_seq = 0;
      bool good = it != sent.end() && info.request_id.writer_guid == cli->gid() && m.size == 36;
      if (good) {
        std::memcpy(&index, m.data.get(), 4);
        std::memcpy(&tag, m.data.get() + 4, 4);
        std::memcpy(&echoed_seq, m.data.get() + 28, 8);
        good = index == it->second && tag == me && echoed_seq == it->first;
        sent.erase(it);
      }
      good ? ++ok : ++wrong;
    }
  }
  out("RESULT responses_ok=%ld wrong=%ld missing=%zu", ok, wrong, sent.size());
  return wrong == 0 && sent.empty() ? 0 : 7;
}

// A timed wait times out on time; a wait is woken by a publish from another process.
int role_waiter()
{
  Env e = make_env("waiter");
  auto sub = must(
    Subscription::make(e.node, opt("topic", "/wake"), "test_msgs/msg/Bytes", QoS()), "sub");
  const long timeout_ms = opt_int("timeout-ms", 200);  // NOLINT(runtime/int)
  std::vector<WaitItem> items{WaitItem::of(sub.get())};
  auto t0 = Clock::now();
  Status s = e.ws->wait(items, std::chrono::milliseconds(timeout_ms));
  out(
    "RESULT timed_wait_ms=%.2f timed_out=%d", ms_since(t0),
    s.code() == wasm_cpp::Code::kTimeout ? 1 : 0);
  out("RESULT ready_for_wake=1");
  items[0].ready = false;
  s = e.ws->wait(items, std::chrono::seconds(30));
  Message m;
  MessageInfo info;
  bool taken = false;
  sub->take(&m, &info, &taken);
  out("RESULT woken=%d taken=%d", items[0].ready ? 1 : 0, taken ? 1 : 0);
  return taken ? 0 : 8;
}

// Incompatible QoS: no match, and an event on this side.
int role_incompat()
{
  Env e = make_env(opt("side") == "pub" ? "incompat_pub" : "incompat_sub");
  const std::string topic = opt("topic", "/incompat");
  std::shared_ptr<Event> ev;
  std::shared_ptr<Publisher> pub;
  std::shared_ptr<Subscription> sub;
  QoS q = parse_qos(opt("qos", ""));
  if (opt("side") == "pub") {
    pub = must(Publisher::make(e.node, topic, "test_msgs/msg/Bytes", q), "pub");
    ev = must(Event::make(pub, EventType::kOfferedQosIncompatible), "event");
  } else {
    sub = must(Subscription::make(e.node, topic, "test_msgs/msg/Bytes", q), "sub");
    ev = must(Event::make(sub, EventType::kRequestedQosIncompatible), "event");
  }
  std::vector<WaitItem> items{WaitItem::of(ev.get())};
  Status s = e.ws->wait(items, std::chrono::milliseconds(opt_int("timeout-ms", 20000)));
  EventStatus st;
  bool taken = false;
  ev->take(&st, &taken);
  size_t matched = pub ? pub->matched_subscription_count() : sub->matched_publisher_count();
  out(
    "RESULT event_ready=%d total=%" PRId64 " change=%" PRId64 " policy=%d matched=%zu",
    items[0].ready ? 1 : 0, st.total_count, st.total_count_change,
    static_cast<int>(st.last_policy_kind), matched);
  if (!opt("signal").empty()) {
    send_signal(e, opt("signal"));
  }
  if (!opt("wait-signal").empty()) {
    wait_signal(e, opt("wait-signal"));
  }
  return s.ok() ? 0 : 9;
}

// Receives from several publishers and reports when one disappears.
int role_survivor()
{
  Env e = make_env("survivor");
  auto sub = must(
    Subscription::make(
      e.node, opt("topic", "/stream"), "test_msgs/msg/Bytes", parse_qos(opt("qos", "keep_last:100"))),
    "sub");
  auto live = must(Event::make(sub, EventType::kLivelinessChanged), "liveliness event");
  const long want_pubs = opt_int("publishers", 2);  // NOLINT(runtime/int)
  std::map<uint32_t, long> by_tag;  // NOLINT(runtime/int)
  bool all_seen = false;
  bool lost_one = false;
  long after_loss = 0;  // NOLINT(runtime/int)
  int liveliness_drop = 0;
  auto t0 = Clock::now();
  while (ms_since(t0) < opt_int("timeout-ms", 30000)) {
    std::vector<WaitItem> items{WaitItem::of(sub.get()), WaitItem::of(live.get())};
    e.ws->wait(items, std::chrono::seconds(1));
    if (items[1].ready) {
      EventStatus st;
      bool taken = false;
      live->take(&st, &taken);
      if (st.alive_count_change < 0) {
        liveliness_drop += -st.alive_count_change;
      }
    }
    Message m;
    MessageInfo info;
    bool taken = false;
    while (sub->take(&m, &info, &taken).ok() && taken) {
      uint32_t index = 0;
      uint32_t tag = 0;
      if (!check_payload(m, &index, &tag)) {
        out("ERROR corrupt payload");
        return 6;
      }
      ++by_tag[tag];
      if (lost_one) {
        ++after_loss;
      }
    }
    if (!all_seen && static_cast<long>(by_tag.size()) >= want_pubs) {  // NOLINT(runtime/int)
      all_seen = true;
      out("RESULT receiving_from=%zu", by_tag.size());
    }
    if (all_seen && !lost_one &&
      static_cast<long>(sub->matched_publisher_count()) < want_pubs)  // NOLINT(runtime/int)
    {
      lost_one = true;
      out("RESULT publisher_gone=1 publishers=%zu", sub->matched_publisher_count());
    }
    if (lost_one && after_loss >= opt_int("after", 1000)) {
      break;
    }
  }
  std::vector<wasm_cpp::NodeInfo> nodes;
  wasm_cpp::graph::get_nodes(*e.ctx, &nodes);
  std::string names;
  for (auto & n : nodes) {
    names += (names.empty() ? "" : ",") + n.name;
  }
  out(
    "RESULT continued=%ld liveliness_drop=%d nodes=%s", after_loss, liveliness_drop,
    names.c_str());
  return lost_one && after_loss >= opt_int("after", 1000) ? 0 : 10;
}

// Oversized and malformed input get clear errors; the bus keeps working.
int role_errors()
{
  Env e = make_env("errors");
  auto pub = must(Publisher::make(e.node, "/errors", "test_msgs/msg/Bytes", QoS()), "pub");
  auto sub = must(Subscription::make(e.node, "/errors", "test_msgs/msg/Bytes", QoS()), "sub");
  const size_t max = e.ctx->max_message_size();
  std::vector<uint8_t> big(max + 1, 1);
  Status s = pub->publish(big.data(), big.size());
  out("RESULT oversized_code=%d", static_cast<int>(s.code()));
  out("MESSAGE oversized: %s", s.message().c_str());
  s = pub->publish(nullptr, 5);
  out("RESULT null_code=%d", static_cast<int>(s.code()));
  out("MESSAGE null: %s", s.message().c_str());
  auto bad_topic = Publisher::make(e.node, "no slash/x", "test_msgs/msg/Bytes", QoS());
  out("RESULT bad_topic_code=%d", static_cast<int>(bad_topic.status().code()));
  out("MESSAGE bad_topic: %s", bad_topic.status().message().c_str());
  auto bad_type = Publisher::make(e.node, "/x", "not a type!", QoS());
  out("RESULT bad_type_code=%d", static_cast<int>(bad_type.status().code()));
  auto bad_node = Node::make(e.ctx, "1bad-name", "/");
  out("RESULT bad_node_code=%d", static_cast<int>(bad_node.status().code()));
  out("MESSAGE bad_node: %s", bad_node.status().message().c_str());
  QoS bad_qos;
  bad_qos.reliability = static_cast<wasm_cpp::Reliability>(42);
  auto bad_q = Publisher::make(e.node, "/y", "test_msgs/msg/Bytes", bad_qos);
  out("RESULT bad_qos_code=%d", static_cast<int>(bad_q.status().code()));
  out("MESSAGE bad_qos: %s", bad_q.status().message().c_str());
  // A message at exactly the maximum still works, and so does a normal one.
  std::vector<uint8_t> p = make_payload(0, 1, 8);
  s = pub->publish(p.data(), p.size());
  Message m;
  bool taken = false;
  sub->take(&m, nullptr, &taken);
  uint32_t index = 99;
  uint32_t tag = 0;
  bool ok = taken && check_payload(m, &index, &tag) && index == 0;
  std::vector<uint8_t> at_max = make_payload(1, 1, max);
  Status s2 = pub->publish(at_max.data(), at_max.size());
  Message m2;
  sub->take(&m2, nullptr, &taken);
  bool ok_max = s2.ok() && taken && m2.size == max && check_payload(m2, &index, &tag) && index == 1;
  out("RESULT after_errors_ok=%d max_ok=%d", ok ? 1 : 0, ok_max ? 1 : 0);
  return 0;
}

// A pthread that logs while main sleeps in a wait must not deadlock.
// --wait-first-ms N: main first waits N ms on the bus (the host then counts
// the program as settled and loads its pthread pool), then starts the thread.
int role_threads()
{
  Env e = make_env("threads");
  auto gc = must(GuardCondition::make(e.ctx), "guard");
  const long wait_first_ms = opt_int("wait-first-ms", 0);  // NOLINT(runtime/int)
  if (wait_first_ms > 0) {
    auto idle = must(GuardCondition::make(e.ctx), "idle guard");
    std::vector<WaitItem> nothing{WaitItem::of(idle.get())};
    e.ws->wait(nothing, std::chrono::milliseconds(wait_first_ms));
  }
  std::thread worker([&]() {
      for (int i = 0; i < 50; ++i) {
        std::printf("thread line %d\n", i);
      }
      std::fflush(stdout);
      gc->trigger();
    });
  std::vector<WaitItem> items{WaitItem::of(gc.get())};
  auto t0 = Clock::now();
  Status s = e.ws->wait(items, std::chrono::seconds(5));
  const double ms = ms_since(t0);
  worker.join();
  out("RESULT guard_ready=%d ms=%.1f", items[0].ready ? 1 : 0, ms);
  return s.ok() ? 0 : 11;
}

// Listener callbacks report new messages without taking them.
std::mutex g_cb_mutex;
std::condition_variable g_cb_cv;
long g_callback_events = 0;  // NOLINT(runtime/int)

void on_new(const void * user, size_t n)
{
  (void)user;
  std::lock_guard<std::mutex> lock(g_cb_mutex);
  g_callback_events += static_cast<long>(n);  // NOLINT(runtime/int)
  g_cb_cv.notify_all();
}

int role_callbacks()
{
  Env e = make_env("callbacks");
  auto sub = must(Subscription::make(e.node, "/cb", "test_msgs/msg/Bytes", QoS()), "sub");
  auto pub = must(Publisher::make(e.node, "/cb", "test_msgs/msg/Bytes", QoS()), "pub");
  for (uint32_t i = 0; i < 3; ++i) {
    auto p = make_payload(i, 1, 8);
    pub->publish(p.data(), p.size());
  }
  Status s = sub->set_on_new_message_callback(&on_new, nullptr);
  if (!s.ok()) {
    out("RESULT callbacks_supported=0 code=%d", static_cast<int>(s.code()));
    out("MESSAGE callbacks: %s", s.message().c_str());
    return 0;
  }
  for (uint32_t i = 3; i < 8; ++i) {
    auto p = make_payload(i, 1, 8);
    pub->publish(p.data(), p.size());
  }
  {
    std::unique_lock<std::mutex> lock(g_cb_mutex);
    g_cb_cv.wait_for(lock, std::chrono::seconds(5), []() {return g_callback_events >= 8;});
  }
  sub->set_on_new_message_callback(nullptr, nullptr);
  long taken_count = 0;  // NOLINT(runtime/int)
  Message m;
  bool taken = false;
  while (sub->take(&m, nullptr, &taken).ok() && taken) {
    ++taken_count;
  }
  std::lock_guard<std::mutex> lock(g_cb_mutex);
  out("RESULT callbacks_supported=1 events=%ld still_takeable=%ld", g_callback_events, taken_count);
  return 0;
}

// Graph queries as the rmw will use them.
int role_graph()
{
  Env e = make_env("grapher");
  auto pub = must(
    Publisher::make(e.node, "/graph/topic", "test_msgs/msg/Bytes", parse_qos("keep_last:7")),
    "pub");
  auto srv = must(
    Service::make(e.node, "/graph/srv", "test_msgs/srv/Echo", wasm_cpp::services_default_qos()),
    "srv");
  // Wait until the peers' publishers are in the graph (a node appears before its endpoints).
  const size_t want = static_cast<size_t>(opt_int("want-pubs", 1));
  wait_graph(e, [&]() {
      size_t n = 0;
      wasm_cpp::graph::count_endpoints(
        *e.ctx, "/graph/topic", wasm_cpp::EndpointKind::kPublisher, &n);
      return n >= want;
    }, 20000);
  std::vector<wasm_cpp::NodeInfo> nodes;
  wasm_cpp::graph::get_nodes(*e.ctx, &nodes);
  std::string names;
  for (auto & n : nodes) {
    names += (names.empty() ? "" : ",") + n.namespace_ + (n.namespace_ == "/" ? "" : "/") + n.name;
  }
  std::vector<wasm_cpp::NameAndTypes> topics;
  wasm_cpp::graph::get_topic_names_and_types(*e.ctx, &topics);
  std::string ts;
  for (auto & t : topics) {
    ts += (ts.empty() ? "" : ",") + t.name + "=" + t.types[0];
  }
  std::vector<wasm_cpp::NameAndTypes> services;
  wasm_cpp::graph::get_service_names_and_types(*e.ctx, &services);
  std::string ss;
  for (auto & t : services) {
    ss += (ss.empty() ? "" : ",") + t.name + "=" + t.types[0];
  }
  std::vector<wasm_cpp::EndpointInfo> pubs;
  wasm_cpp::graph::get_endpoints(*e.ctx, "/graph/topic", wasm_cpp::EndpointKind::kPublisher, &pubs);
  size_t n_subs = 0;
  wasm_cpp::graph::count_endpoints(
    *e.ctx, "/graph/topic", wasm_cpp::EndpointKind::kSubscription, &n_subs);
  std::vector<wasm_cpp::NameAndTypes> by_node;
  Status missing = wasm_cpp::graph::get_names_and_types_by_node(
    *e.ctx, "nobody", "/", wasm_cpp::EndpointKind::kPublisher, &by_node);
  wasm_cpp::graph::get_names_and_types_by_node(
    *e.ctx, e.node->name(), "/", wasm_cpp::EndpointKind::kService, &by_node);
  out("RESULT nodes=%s", names.c_str());
  out("RESULT topics=%s", ts.c_str());
  out("RESULT services=%s", ss.c_str());
  bool gid_ok = false;
  for (auto & info : pubs) {
    gid_ok = gid_ok || (info.gid == pub->gid() && info.node_name == e.node->name());
  }
  out(
    "RESULT pub_count=%zu pub_depth=%zu pub_gid_ok=%d sub_count=%zu missing_code=%d by_node=%s",
    pubs.size(), pubs.empty() ? 0 : pubs[0].qos.depth, gid_ok ? 1 : 0, n_subs,
    static_cast<int>(missing.code()), by_node.empty() ? "-" : by_node[0].name.c_str());
  if (!opt("signal").empty()) {
    send_signal(e, opt("signal"));
  }
  if (!opt("wait-signal").empty()) {
    wait_signal(e, opt("wait-signal"));
  }
  return 0;
}

// Deadline and liveliness events.
int role_deadline()
{
  Env e = make_env("deadline");
  QoS q = parse_qos("deadline_ms=50,manual_lease_ms=50");
  auto pub = must(Publisher::make(e.node, "/deadline", "test_msgs/msg/Bytes", q), "pub");
  auto sub = must(Subscription::make(e.node, "/deadline", "test_msgs/msg/Bytes", q), "sub");
  auto offered = must(Event::make(pub, EventType::kOfferedDeadlineMissed), "offered");
  auto requested = must(Event::make(sub, EventType::kRequestedDeadlineMissed), "requested");
  auto lost = must(Event::make(pub, EventType::kLivelinessLost), "liveliness lost");
  auto changed = must(Event::make(sub, EventType::kLivelinessChanged), "liveliness changed");
  auto p = make_payload(0, 1, 8);
  auto published = Clock::now();
  pub->publish(p.data(), p.size());
  // No timer anywhere: the wait times out at the next deadline by itself.
  std::vector<WaitItem> items{
    WaitItem::of(offered.get()), WaitItem::of(requested.get()), WaitItem::of(lost.get())};
  auto t0 = Clock::now();
  Status s = e.ws->wait(items, std::chrono::seconds(5));
  const double first_ms = ms_since(t0);
  EventStatus so;
  EventStatus sr;
  EventStatus sl;
  EventStatus sc;
  bool t = false;
  offered->take(&so, &t);
  requested->take(&sr, &t);
  lost->take(&sl, &t);
  changed->take(&sc, &t);
  out(
    "RESULT first_event_ms=%.1f taken_ms=%.1f offered=%" PRId64 " requested=%" PRId64
    " liveliness_lost=%" PRId64 " alive=%d not_alive=%d", first_ms, ms_since(published),
    so.total_count, sr.total_count, sl.total_count, sc.alive_count, sc.not_alive_count);
  pub->assert_liveliness();
  changed->take(&sc, &t);
  out("RESULT after_assert_alive=%d", sc.alive_count);
  return s.ok() ? 0 : 12;
}

// Odds and ends: ignore_local_publications, service/client/event callbacks,
// the C++ QoS compatibility check.
std::mutex g_misc_mutex;
std::condition_variable g_misc_cv;
std::map<std::string, long> g_misc_events;  // NOLINT(runtime/int)

void on_misc(const void * user, size_t n)
{
  std::lock_guard<std::mutex> lock(g_misc_mutex);
  g_misc_events[static_cast<const char *>(user)] += static_cast<long>(n);  // NOLINT(runtime/int)
  g_misc_cv.notify_all();
}

int role_misc()
{
  Env e = make_env("misc");
  // ignore_local_publications: a subscription of this context does not hear
  // its own publisher, one of another context does.
  wasm_cpp::SubscriptionOptions ignore;
  ignore.ignore_local_publications = true;
  auto pub = must(Publisher::make(e.node, "/misc/local", "test_msgs/msg/Bytes", QoS()), "pub");
  auto deaf = must(
    Subscription::make(e.node, "/misc/local", "test_msgs/msg/Bytes", QoS(), ignore), "deaf");
  auto other_ctx = must(Context::make(wasm_cpp::ContextOptions()), "context 2");
  auto other_node = must(Node::make(other_ctx, "misc_other", "/"), "node 2");
  auto hears = must(
    Subscription::make(other_node, "/misc/local", "test_msgs/msg/Bytes", QoS(), ignore), "hears");
  auto p = make_payload(0, 1, 8);
  pub->publish(p.data(), p.size());
  out(
    "RESULT ignore_local_matched=%zu other_context_matched=%zu deaf_has_data=%d hears_has_data=%d",
    deaf->matched_publisher_count(), hears->matched_publisher_count(), deaf->has_data() ? 1 : 0,
    hears->has_data() ? 1 : 0);

  // Callbacks of a service (requests), a client (responses) and an event.
  auto srv = must(
    Service::make(e.node, "/misc/srv", "test_msgs/srv/Echo", wasm_cpp::services_default_qos()), "srv");
  auto cli = must(
    Client::make(e.node, "/misc/srv", "test_msgs/srv/Echo", wasm_cpp::services_default_qos()), "cli");
  srv->set_on_new_request_callback(&on_misc, "request");
  cli->set_on_new_response_callback(&on_misc, "response");
  QoS best_effort;
  best_effort.reliability = wasm_cpp::Reliability::kBestEffort;
  auto be_pub = must(Publisher::make(e.node, "/misc/incompat", "test_msgs/msg/Bytes", best_effort), "be pub");
  auto offered = must(Event::make(be_pub, EventType::kOfferedQosIncompatible), "offered event");
  offered->set_callback(&on_misc, "event");
  auto reliable_sub = must(
    Subscription::make(e.node, "/misc/incompat", "test_msgs/msg/Bytes", QoS()), "reliable sub");
  for (int i = 0; i < 3; ++i) {
    int64_t seq = 0;
    cli->send_request(p.data(), p.size(), &seq);
  }
  {
    std::unique_lock<std::mutex> lock(g_misc_mutex);
    g_misc_cv.wait_for(lock, std::chrono::seconds(5), []() {
        return g_misc_events["request"] >= 3 && g_misc_events["event"] >= 1;
      });
  }
  Message m;
  ServiceInfo info;
  bool taken = false;
  while (srv->take_request(&m, &info, &taken).ok() && taken) {
    srv->send_response(info.request_id, m.data.get(), m.size);
  }
  {
    std::unique_lock<std::mutex> lock(g_misc_mutex);
    g_misc_cv.wait_for(lock, std::chrono::seconds(5), []() {return g_misc_events["response"] >= 3;});
    out(
      "RESULT request_events=%ld response_events=%ld event_events=%ld",
      g_misc_events["request"], g_misc_events["response"], g_misc_events["event"]);
  }
  srv->set_on_new_request_callback(nullptr, nullptr);
  cli->set_on_new_response_callback(nullptr, nullptr);
  offered->set_callback(nullptr, nullptr);

  // The C++ compatibility check (what rmw_qos_profile_check_compatible returns).
  struct Case
  {
    const char * name;
    QoS pub;
    QoS sub;
  };
  QoS def;
  QoS be = def;
  be.reliability = wasm_cpp::Reliability::kBestEffort;
  QoS tl = def;
  tl.durability = wasm_cpp::Durability::kTransientLocal;
  QoS dl100 = def;
  dl100.deadline = 100000000;
  QoS dl200 = def;
  dl200.deadline = 200000000;
  QoS manual = def;
  manual.liveliness = wasm_cpp::Liveliness::kManualByTopic;
  QoS sysdef = def;
  sysdef.reliability = wasm_cpp::Reliability::kSystemDefault;
  const Case cases[] = {
    {"same", def, def}, {"be_pub_rel_sub", be, def}, {"rel_pub_be_sub", def, be},
    {"vol_pub_tl_sub", def, tl}, {"no_deadline_pub", def, dl100},
    {"longer_deadline_pub", dl200, dl100}, {"auto_pub_manual_sub", def, manual},
    {"sysdef_pub_rel_sub", sysdef, def},
  };
  std::string res;
  for (const Case & c : cases) {
    wasm_cpp::QosPolicyKind kind = wasm_cpp::QosPolicyKind::kInvalid;
    std::string reason;
    auto r = wasm_cpp::check_qos_compatible(c.pub, c.sub, &kind, &reason);
    res += std::string(res.empty() ? "" : ",") + c.name + ":" + std::to_string(static_cast<int>(r)) +
      ":" + std::to_string(r == wasm_cpp::QosCompatibility::kOk ? 0 : static_cast<int>(kind));
  }
  out("RESULT qos_checks=%s", res.c_str());
  return 0;
}

}  // namespace

/**
 * Role "io": what the runtime hands an executable besides the bus. Prints
 * every argument, the whole standard input and the file named by IO_FILE.
 */
int role_io(int argc, char ** argv)
{
  for (int i = 0; i < argc; ++i) {
    std::printf("ARG %d %s\n", i, argv[i]);
  }
  std::string in;
  for (int c = std::getchar(); c != EOF; c = std::getchar()) {
    in.push_back(c == '\n' ? '|' : static_cast<char>(c));
  }
  std::printf("STDIN %s\n", in.c_str());
  const char * path = std::getenv("IO_FILE");
  if (path != nullptr) {
    std::FILE * f = std::fopen(path, "rb");
    if (f == nullptr) {
      std::printf("FILE-ERROR %s\n", path);
      return 1;
    }
    std::string content;
    char buf[256];
    for (size_t n; (n = std::fread(buf, 1, sizeof(buf), f)) > 0; ) {
      content.append(buf, n);
    }
    std::fclose(f);
    for (char & c : content) {
      if (c == '\n') {c = '|';}
    }
    std::printf("FILE %s\n", content.c_str());
  }
  return 0;
}

/**
 * Role "lines": a terminal program. Prints "LINE n <text>" as soon as each
 * line of standard input arrives, then "EOF n". With threads, a thread
 * prints "THREAD" lines while the main thread sleeps in read(), which only
 * works when the read runs what the thread proxies to it (its printf).
 */
int role_lines()
{
#ifdef __EMSCRIPTEN_PTHREADS__
  std::printf("READY threads=1\n");
#else
  std::printf("READY threads=0\n");
#endif
  std::fflush(stdout);
#ifdef __EMSCRIPTEN_PTHREADS__
  std::thread talker([]() {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      for (int i = 0; i < 3; ++i) {
        std::printf("THREAD %d\n", i);
        std::fflush(stdout);
      }
    });
#endif
  char buf[4096];
  int n = 0;
  while (std::fgets(buf, sizeof(buf), stdin) != nullptr) {
    buf[std::strcspn(buf, "\n")] = '\0';
    std::printf("LINE %d %s\n", ++n, buf);
    std::fflush(stdout);
  }
  std::printf("EOF %d\n", n);
#ifdef __EMSCRIPTEN_PTHREADS__
  talker.join();
#endif
  return 0;
}

int main(int argc, char ** argv)
{
  if (argc < 2) {
    std::printf("usage: core_node ROLE [--key value]...\n");
    return 2;
  }
  const std::string role = argv[1];
  if (role == "io") {return role_io(argc, argv);}
  if (role == "lines") {return role_lines();}
  for (int i = 2; i + 1 < argc; i += 2) {
    std::string k = argv[i];
    if (k.rfind("--", 0) != 0) {
      std::printf("ERROR bad option '%s'\n", k.c_str());
      return 2;
    }
    g_opts[k.substr(2)] = argv[i + 1];
  }
  if (role == "pub") {return role_pub();}
  if (role == "sub") {return role_sub();}
  if (role == "server") {return role_server();}
  if (role == "client") {return role_client();}
  if (role == "waiter") {return role_waiter();}
  if (role == "incompat") {return role_incompat();}
  if (role == "survivor") {return role_survivor();}
  if (role == "errors") {return role_errors();}
  if (role == "threads") {return role_threads();}
  if (role == "callbacks") {return role_callbacks();}
  if (role == "graph") {return role_graph();}
  if (role == "deadline") {return role_deadline();}
  if (role == "misc") {return role_misc();}
  std::printf("ERROR unknown role '%s'\n", role.c_str());
  return 2;
}
