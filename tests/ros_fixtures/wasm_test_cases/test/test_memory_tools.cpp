// Copyright 2026 The colcon-wasm authors
// Licensed under the Apache License, Version 2.0

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdlib>

#include "osrf_testing_tools_cpp/memory_tools/memory_tools.hpp"

namespace memory_tools = osrf_testing_tools_cpp::memory_tools;

// where allocations escape to: clang removes a malloc/free pair whose memory
// does not escape (osrf's own guaranteed_malloc() included)
static void * volatile g_sink = nullptr;

static void allocate_and_free(std::size_t size)
{
  g_sink = std::malloc(size);
  std::free(g_sink);
}

// osrf_testing_tools_cpp's memory tools hook malloc and free in WebAssembly
// too (through Emscripten's emscripten_builtin_malloc, as LD_PRELOAD does
// natively): EXPECT_NO_MEMORY_OPERATIONS checks what it says.
TEST(MemoryTools, see_unexpected_allocations)
{
  memory_tools::initialize();
  int unexpected = 0;
  memory_tools::on_unexpected_malloc([&unexpected]() {++unexpected;});
  memory_tools::on_unexpected_free([&unexpected]() {++unexpected;});
  memory_tools::enable_monitoring();

  allocate_and_free(64);  // expected: not inside expect_no_*
  EXPECT_EQ(0, unexpected);
  memory_tools::expect_no_malloc_begin();
  memory_tools::expect_no_free_begin();
  allocate_and_free(16);
  memory_tools::expect_no_free_end();
  memory_tools::expect_no_malloc_end();

  memory_tools::disable_monitoring();
  memory_tools::uninitialize();
  EXPECT_EQ(2, unexpected) << "the malloc and the free inside expect_no_* were not seen";
}
