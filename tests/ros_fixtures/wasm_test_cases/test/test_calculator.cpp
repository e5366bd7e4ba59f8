// Copyright 2026 The colcon-wasm authors
// Licensed under the Apache License, Version 2.0

#include <gtest/gtest.h>

#include <stdexcept>
#include <thread>

#include "wasm_test_cases/calculator.hpp"

TEST(Calculator, adds)
{
  wasm_test_cases::Calculator calculator;
  EXPECT_EQ(5, calculator.add(2, 3));
  EXPECT_EQ(-1, calculator.add(2, -3));
}

TEST(Calculator, multiplies)
{
  wasm_test_cases::Calculator calculator;
  EXPECT_EQ(6, calculator.multiply(2, 3));
}

TEST(Calculator, exceptions_and_threads)
{
  EXPECT_THROW(throw std::runtime_error("thrown"), std::runtime_error);
  long result = 0;
  std::thread worker([&result]() {
      wasm_test_cases::Calculator calculator;
      result = calculator.multiply(7, 6);
    });
  worker.join();
  EXPECT_EQ(42, result);
}
