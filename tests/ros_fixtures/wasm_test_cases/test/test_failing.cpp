// Copyright 2026 The colcon-wasm authors
// Licensed under the Apache License, Version 2.0

#include <gtest/gtest.h>

#include "wasm_test_cases/calculator.hpp"

TEST(Failing, passes_first)
{
  wasm_test_cases::Calculator calculator;
  EXPECT_EQ(4, calculator.add(2, 2));
}

TEST(Failing, on_purpose)
{
  wasm_test_cases::Calculator calculator;
  EXPECT_EQ(5, calculator.add(2, 2)) << "this test fails on purpose: 2 + 2 is not 5";
}
