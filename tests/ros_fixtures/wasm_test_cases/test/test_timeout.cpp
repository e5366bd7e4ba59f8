// Copyright 2026 The colcon-wasm authors
// Licensed under the Apache License, Version 2.0

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>

TEST(Timeout, waits_forever)
{
  // nobody ever notifies: only the test's time limit ends this
  std::mutex mutex;
  std::condition_variable never;
  std::unique_lock<std::mutex> lock(mutex);
  never.wait(lock, []() {return false;});
}
