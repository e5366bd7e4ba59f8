// Copyright 2026 The colcon-wasm authors
// Licensed under the Apache License, Version 2.0

#include "wasm_test_cases/calculator.hpp"

namespace wasm_test_cases
{

Calculator::Calculator(Journal * journal)
: journal_(journal)
{
}

long Calculator::add(long a, long b)
{
  long result = a + b;
  if (journal_) {
    journal_->record("add", result);
  }
  return result;
}

long Calculator::multiply(long a, long b)
{
  long result = a * b;
  if (journal_) {
    journal_->record("multiply", result);
  }
  return result;
}

}  // namespace wasm_test_cases
