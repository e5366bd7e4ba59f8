// Copyright 2026 The colcon-wasm authors
// Licensed under the Apache License, Version 2.0

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "ament_index_cpp/get_package_share_directory.hpp"

static std::string read_file(const std::string & path)
{
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

TEST(Data, next_to_the_test)
{
  // the working directory is the test's build folder, where CMake copied it
  EXPECT_EQ("hello from a data file\n", read_file("greeting.txt"));
}

TEST(Data, named_by_the_environment)
{
  const char * path = std::getenv("WASM_TEST_CASES_DATA");
  ASSERT_NE(nullptr, path) << "ament_add_gtest(ENV ...) did not reach the test";
  EXPECT_EQ("hello from a data file\n", read_file(path));
}

TEST(Data, installed)
{
  std::string share = ament_index_cpp::get_package_share_directory("wasm_test_cases");
  EXPECT_EQ("hello from a data file\n", read_file(share + "/greeting.txt"));
}

TEST(Data, written_by_the_test)
{
  {
    std::ofstream out("written_by_test_data.txt");
    out << "written in WebAssembly\n";
  }
  EXPECT_EQ("written in WebAssembly\n", read_file("written_by_test_data.txt"));
}
