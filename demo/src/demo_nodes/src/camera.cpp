// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Publishes demo_interfaces/msg/Frame (an rgb8 image) on /camera/image: a
// colour gradient with a bright square that moves, -p rate:=HZ frames per
// second (default 10), -p width:=W -p height:=H (default 160 x 120).

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "demo_nodes/support.hpp"

int main(int argc, char ** argv)
{
  auto args = demo_nodes::parse_arguments(argc, argv, "camera");
  const std::string & name = args.node_name;
  double rate = demo_nodes::parameter(args, "rate", 10.0);
  auto width = static_cast<uint32_t>(demo_nodes::parameter(args, "width", 160.0));
  auto height = static_cast<uint32_t>(demo_nodes::parameter(args, "height", 120.0));
  auto context = demo_nodes::unwrap(wasm_cpp::Context::make({}), name, "creating the context");
  auto node = demo_nodes::unwrap(
    wasm_cpp::Node::make(context, name, args.node_namespace), name, "creating the node");
  std::string topic = demo_nodes::resolve_name(args, "camera/image");
  auto publisher = demo_nodes::unwrap(
    wasm_cpp::Publisher::make(node, topic, "demo_interfaces/msg/Frame", wasm_cpp::QoS{}),
    name, "creating the publisher");
  demo_nodes::log("INFO", name, "Publishing %ux%u rgb8 frames on %s at %.1f Hz",
    width, height, topic.c_str(), rate);
  auto start = std::chrono::steady_clock::now();
  auto period = std::chrono::duration<double>(1.0 / (rate > 0 ? rate : 10.0));
  std::vector<uint8_t> pixels(static_cast<size_t>(width) * height * 3);
  for (uint32_t frame = 0;; ++frame) {
    uint32_t side = height / 4;
    uint32_t x0 = (frame * 4) % (width > side ? width - side : 1);
    uint32_t y0 = height / 2 - side / 2;
    for (uint32_t y = 0; y < height; ++y) {
      for (uint32_t x = 0; x < width; ++x) {
        uint8_t * p = &pixels[(static_cast<size_t>(y) * width + x) * 3];
        bool square = x >= x0 && x < x0 + side && y >= y0 && y < y0 + side;
        p[0] = square ? 255 : static_cast<uint8_t>(255 * x / width);
        p[1] = square ? 255 : static_cast<uint8_t>(255 * y / height);
        p[2] = square ? 255 : 96;
      }
    }
    demo_nodes::CdrWriter cdr;
    cdr.put<uint32_t>(height);
    cdr.put<uint32_t>(width);
    cdr.put_string("rgb8");
    cdr.put<uint8_t>(0);
    cdr.put<uint32_t>(width * 3);
    cdr.put_bytes(pixels);
    demo_nodes::check(
      publisher->publish(cdr.bytes().data(), cdr.bytes().size()), name, "publishing");
    std::this_thread::sleep_until(start + (frame + 1) * period);
  }
}
