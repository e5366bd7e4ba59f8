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

#include "wasm_cpp/graph.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "bus_abi.hpp"

namespace wasm_cpp
{
namespace graph
{

namespace
{

/// Reads the buffer wasm_bus_graph() produces, with bounds checks.
class Reader final
{
public:
  Reader(const uint8_t * data, size_t size)
  : data_(data), size_(size) {}

  bool u32(uint32_t * v)
  {
    if (pos_ + 4 > size_) {
      return fail();
    }
    std::memcpy(v, data_ + pos_, 4);
    pos_ += 4;
    return true;
  }

  bool words(int32_t * w, size_t n)
  {
    if (pos_ + 4 * n > size_) {
      return fail();
    }
    std::memcpy(w, data_ + pos_, 4 * n);
    pos_ += 4 * n;
    return true;
  }

  bool str(std::string * s)
  {
    uint32_t n = 0;
    if (!u32(&n) || pos_ + n > size_) {
      return fail();
    }
    s->assign(reinterpret_cast<const char *>(data_ + pos_), n);
    pos_ += n;
    return true;
  }

  bool ok() const {return ok_;}

private:
  bool fail()
  {
    ok_ = false;
    return false;
  }

  const uint8_t * data_;
  size_t size_;
  size_t pos_ = 0;
  bool ok_ = true;
};

struct Snapshot
{
  std::vector<NodeInfo> nodes;
  std::vector<EndpointInfo> endpoints;
};

Status read_snapshot(const Context & context, Snapshot * snap)
{
  uint8_t * buf = nullptr;
  int len = 0;
  int rc = wasm_bus_graph(static_cast<int>(context.domain_id()), &buf, &len);
  if (rc != 0) {
    return detail::bus_status(rc, "graph query");
  }
  Reader r(buf, static_cast<size_t>(len));
  uint32_t n = 0;
  if (r.u32(&n)) {
    snap->nodes.resize(n);
    for (NodeInfo & node : snap->nodes) {
      int32_t gid[4];
      r.str(&node.name);
      r.str(&node.namespace_);
      r.str(&node.enclave);
      r.words(gid, 4);
      node.gid = detail::gid_from_words(gid);
    }
  }
  if (r.u32(&n)) {
    snap->endpoints.resize(n);
    for (EndpointInfo & e : snap->endpoints) {
      uint32_t kind = 0;
      int32_t gid[4];
      int32_t qos[detail::kQosWords];
      r.u32(&kind);
      e.kind = static_cast<EndpointKind>(kind);
      r.str(&e.name);
      r.str(&e.type_name);
      r.str(&e.node_name);
      r.str(&e.node_namespace);
      r.words(gid, 4);
      r.words(qos, detail::kQosWords);
      e.gid = detail::gid_from_words(gid);
      e.qos = detail::qos_from_wire(qos);
    }
  }
  std::free(buf);
  if (!r.ok()) {
    return Status(Code::kError, "graph query: the bus returned a truncated snapshot");
  }
  return Status::Ok();
}

bool is_topic(EndpointKind k)
{
  return k == EndpointKind::kPublisher || k == EndpointKind::kSubscription;
}

void collect(
  const std::vector<EndpointInfo> & endpoints, bool topics, const std::string * node_name,
  const std::string * node_namespace, EndpointKind only, std::vector<NameAndTypes> * out)
{
  std::map<std::string, std::set<std::string>> names;
  for (const EndpointInfo & e : endpoints) {
    if (node_name != nullptr) {
      if (e.kind != only || e.node_name != *node_name || e.node_namespace != *node_namespace) {
        continue;
      }
    } else if (is_topic(e.kind) != topics) {
      continue;
    }
    names[e.name].insert(e.type_name);
  }
  out->clear();
  for (auto & kv : names) {
    out->push_back(NameAndTypes{kv.first, std::vector<std::string>(kv.second.begin(), kv.second.end())});
  }
}

}  // namespace

Status get_nodes(const Context & context, std::vector<NodeInfo> * nodes)
{
  if (nodes == nullptr) {
    return Status(Code::kInvalidArgument, "get_nodes: null output");
  }
  Snapshot snap;
  Status s = read_snapshot(context, &snap);
  if (!s.ok()) {
    return s;
  }
  std::sort(
    snap.nodes.begin(), snap.nodes.end(), [](const NodeInfo & a, const NodeInfo & b) {
      return a.namespace_ != b.namespace_ ? a.namespace_ < b.namespace_ : a.name < b.name;
    });
  *nodes = std::move(snap.nodes);
  return Status::Ok();
}

Status get_topic_names_and_types(const Context & context, std::vector<NameAndTypes> * topics)
{
  if (topics == nullptr) {
    return Status(Code::kInvalidArgument, "get_topic_names_and_types: null output");
  }
  Snapshot snap;
  Status s = read_snapshot(context, &snap);
  if (s.ok()) {
    collect(snap.endpoints, true, nullptr, nullptr, EndpointKind::kPublisher, topics);
  }
  return s;
}

Status get_service_names_and_types(const Context & context, std::vector<NameAndTypes> * services)
{
  if (services == nullptr) {
    return Status(Code::kInvalidArgument, "get_service_names_and_types: null output");
  }
  Snapshot snap;
  Status s = read_snapshot(context, &snap);
  if (s.ok()) {
    collect(snap.endpoints, false, nullptr, nullptr, EndpointKind::kService, services);
  }
  return s;
}

Status get_endpoints(
  const Context & context, const std::string & name, EndpointKind kind,
  std::vector<EndpointInfo> * endpoints)
{
  if (endpoints == nullptr) {
    return Status(Code::kInvalidArgument, "get_endpoints: null output");
  }
  Snapshot snap;
  Status s = read_snapshot(context, &snap);
  if (!s.ok()) {
    return s;
  }
  endpoints->clear();
  for (EndpointInfo & e : snap.endpoints) {
    if (e.kind == kind && e.name == name) {
      endpoints->push_back(std::move(e));
    }
  }
  return Status::Ok();
}

Status count_endpoints(
  const Context & context, const std::string & name, EndpointKind kind, size_t * count)
{
  if (count == nullptr) {
    return Status(Code::kInvalidArgument, "count_endpoints: null output");
  }
  std::vector<EndpointInfo> endpoints;
  Status s = get_endpoints(context, name, kind, &endpoints);
  *count = s.ok() ? endpoints.size() : 0;
  return s;
}

Status get_names_and_types_by_node(
  const Context & context, const std::string & node_name, const std::string & node_namespace,
  EndpointKind kind, std::vector<NameAndTypes> * names_and_types)
{
  if (names_and_types == nullptr) {
    return Status(Code::kInvalidArgument, "get_names_and_types_by_node: null output");
  }
  Snapshot snap;
  Status s = read_snapshot(context, &snap);
  if (!s.ok()) {
    return s;
  }
  bool found = false;
  for (const NodeInfo & n : snap.nodes) {
    if (n.name == node_name && n.namespace_ == node_namespace) {
      found = true;
      break;
    }
  }
  if (!found) {
    return Status(
      Code::kNodeNameNonExistent, "node '" + node_name + "' in namespace '" + node_namespace +
      "' does not exist in domain " + std::to_string(context.domain_id()));
  }
  collect(snap.endpoints, true, &node_name, &node_namespace, kind, names_and_types);
  return Status::Ok();
}

uint32_t version()
{
  return static_cast<uint32_t>(wasm_bus_graph_version());
}

}  // namespace graph
}  // namespace wasm_cpp
