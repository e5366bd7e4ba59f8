// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

#ifndef DEMO_NODES__SUPPORT_HPP_
#define DEMO_NODES__SUPPORT_HPP_

/// \file
/// What the demo nodes share: ROS command line arguments (`--ros-args -r
/// from:=to -r __node:=name -r __ns:=/ns -p name:=value`), ROS-style log
/// lines, and a small CDR writer/reader (XCDR1, little endian, the 4-byte
/// encapsulation header) for the demo_interfaces messages.  The demo uses
/// wasm_cpp directly and needs no ROS package.

#include <chrono>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "wasm_cpp/wasm_cpp.hpp"

namespace demo_nodes
{

/// The ROS arguments of a demo node.
struct Arguments
{
  std::string node_name;                         ///< after __node:=, else the default
  std::string node_namespace = "/";              ///< after __ns:=
  std::map<std::string, std::string> remaps;     ///< from -> to
  std::map<std::string, std::string> parameters;  ///< -p name:=value
  std::vector<std::string> others;               ///< non-ROS arguments
};

/// Parse argv as rcl does for the subset the demo needs; exits on bad input.
inline Arguments parse_arguments(int argc, char ** argv, const std::string & default_name)
{
  Arguments args;
  args.node_name = default_name;
  bool ros = false;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--ros-args") {ros = true; continue;}
    if (a == "--") {ros = false; continue;}
    if (!ros) {args.others.push_back(a); continue;}
    if ((a == "-r" || a == "--remap" || a == "-p" || a == "--param" || a == "--log-level") &&
      i + 1 < argc)
    {
      std::string rule = argv[++i];
      if (a == "--log-level") {continue;}
      size_t sep = rule.find(":=");
      if (sep == std::string::npos) {
        std::fprintf(stderr, "[ERROR] [%s]: argument '%s %s' is not name:=value\n",
          default_name.c_str(), a.c_str(), rule.c_str());
        std::exit(2);
      }
      std::string from = rule.substr(0, sep), to = rule.substr(sep + 2);
      if (a == "-p" || a == "--param") {
        size_t colon = from.find(':');  // node_name:param applies to one node only
        if (colon != std::string::npos) {
          if (from.substr(0, colon) != args.node_name && from.substr(0, colon) != default_name) {
            continue;
          }
          from = from.substr(colon + 1);
        }
        args.parameters[from] = to;
      } else if (from == "__node" || from == "__name") {
        args.node_name = to;
      } else if (from == "__ns") {
        args.node_namespace = to.empty() || to[0] != '/' ? "/" + to : to;
      } else {
        args.remaps[from] = to;
      }
      continue;
    }
    std::fprintf(stderr, "[WARN] [%s]: ignoring the ROS argument '%s'\n",
      default_name.c_str(), a.c_str());
  }
  return args;
}

/// A parameter as a double, or the default.
inline double parameter(const Arguments & args, const std::string & name, double fallback)
{
  auto it = args.parameters.find(name);
  if (it == args.parameters.end()) {return fallback;}
  char * end = nullptr;
  double v = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || *end != '\0') {
    std::fprintf(stderr, "[ERROR] [%s]: parameter %s:=%s is not a number\n",
      args.node_name.c_str(), name.c_str(), it->second.c_str());
    std::exit(2);
  }
  return v;
}

/// A parameter as a string, or the default.
inline std::string parameter(
  const Arguments & args, const std::string & name, const std::string & fallback)
{
  auto it = args.parameters.find(name);
  return it == args.parameters.end() ? fallback : it->second;
}

/// The fully qualified name of a topic or service after remapping.
inline std::string resolve_name(const Arguments & args, const std::string & name)
{
  std::string resolved = name;
  auto it = args.remaps.find(name);
  if (it != args.remaps.end()) {resolved = it->second;}
  if (!resolved.empty() && resolved[0] == '/') {return resolved;}
  return (args.node_namespace == "/" ? "" : args.node_namespace) + "/" + resolved;
}

/// Print a log line as rcutils formats it: [SEVERITY] [time] [node]: message.
inline void log(const char * severity, const std::string & node, const char * format, ...)
{
  auto now = std::chrono::system_clock::now().time_since_epoch();
  double seconds = std::chrono::duration<double>(now).count();
  char message[1024];
  va_list list;
  va_start(list, format);
  std::vsnprintf(message, sizeof(message), format, list);
  va_end(list);
  bool error = std::strcmp(severity, "ERROR") == 0 || std::strcmp(severity, "FATAL") == 0 ||
    std::strcmp(severity, "WARN") == 0;
  std::fprintf(error ? stderr : stdout, "[%s] [%.6f] [%s]: %s\n",
    severity, seconds, node.c_str(), message);
  std::fflush(error ? stderr : stdout);
}

/// The value of a wasm_cpp result, or exit with its message.
template<typename T>
T unwrap(wasm_cpp::Result<T> result, const std::string & node, const char * what)
{
  if (!result.ok()) {
    log("FATAL", node, "%s failed: %s", what, result.status().message().c_str());
    std::exit(1);
  }
  return std::move(result.value());
}

/// Exit with the message when a wasm_cpp call failed.
inline void check(const wasm_cpp::Status & status, const std::string & node, const char * what)
{
  if (!status.ok()) {
    log("FATAL", node, "%s failed: %s", what, status.message().c_str());
    std::exit(1);
  }
}

/// Writes CDR: XCDR1 little endian, aligned from the byte after the header.
class CdrWriter final
{
public:
  CdrWriter() : bytes_{0x00, 0x01, 0x00, 0x00} {}

  template<typename T>
  void put(T value)
  {
    align(sizeof(T));
    const auto * p = reinterpret_cast<const uint8_t *>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }

  void put_string(const std::string & s)
  {
    put<uint32_t>(static_cast<uint32_t>(s.size() + 1));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
  }

  /// A uint8[] sequence: uint32 count, then the bytes.
  void put_bytes(const std::vector<uint8_t> & data)
  {
    put<uint32_t>(static_cast<uint32_t>(data.size()));
    bytes_.insert(bytes_.end(), data.begin(), data.end());
  }

  const std::vector<uint8_t> & bytes() const {return bytes_;}

private:
  void align(size_t n)
  {
    while ((bytes_.size() - 4) % n != 0) {bytes_.push_back(0);}
  }

  std::vector<uint8_t> bytes_;
};

/// Reads CDR written by CdrWriter or any ROS 2 CDR serializer; throws on short input.
class CdrReader final
{
public:
  CdrReader(const uint8_t * data, size_t size) : data_(data), size_(size), pos_(4)
  {
    if (size < 4 || data[0] != 0x00 || data[1] != 0x01) {
      throw std::runtime_error("not little-endian CDR (bad encapsulation header)");
    }
  }

  template<typename T>
  T get()
  {
    pos_ += (sizeof(T) - (pos_ - 4) % sizeof(T)) % sizeof(T);
    need(sizeof(T));
    T value;
    std::memcpy(&value, data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }

  std::string get_string()
  {
    uint32_t length = get<uint32_t>();
    need(length);
    std::string s(reinterpret_cast<const char *>(data_ + pos_), length ? length - 1 : 0);
    pos_ += length;
    return s;
  }

private:
  void need(size_t n)
  {
    if (pos_ + n > size_) {throw std::runtime_error("the message is too short");}
  }

  const uint8_t * data_;
  size_t size_;
  size_t pos_;
};

}  // namespace demo_nodes

#endif  // DEMO_NODES__SUPPORT_HPP_
