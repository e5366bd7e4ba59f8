// Copyright 2026 The colcon-wasm authors
// Licensed under the Apache License, Version 2.0

#ifndef WASM_TEST_CASES__CALCULATOR_HPP_
#define WASM_TEST_CASES__CALCULATOR_HPP_

#include <string>

namespace wasm_test_cases
{

/// Where the calculator logs what it does (mocked by test_mock).
class Journal
{
public:
  virtual ~Journal() = default;
  virtual void record(const std::string & operation, long result) = 0;
};

/// Adds and multiplies, and tells its journal.
class Calculator
{
public:
  explicit Calculator(Journal * journal = nullptr);
  long add(long a, long b);
  long multiply(long a, long b);

private:
  Journal * journal_;
};

}  // namespace wasm_test_cases

#endif  // WASM_TEST_CASES__CALCULATOR_HPP_
