// Copyright 2026 The colcon-wasm authors
// Licensed under the Apache License, Version 2.0

#include <gmock/gmock.h>

#include <string>

#include "wasm_test_cases/calculator.hpp"

using ::testing::StrEq;

class MockJournal : public wasm_test_cases::Journal
{
public:
  MOCK_METHOD(void, record, (const std::string & operation, long result), (override));
};

TEST(CalculatorJournal, records_each_operation)
{
  MockJournal journal;
  ::testing::InSequence in_order;
  EXPECT_CALL(journal, record(StrEq("add"), 5)).Times(1);
  EXPECT_CALL(journal, record(StrEq("multiply"), 12)).Times(1);
  wasm_test_cases::Calculator calculator(&journal);
  calculator.add(2, 3);
  calculator.multiply(3, 4);
}
