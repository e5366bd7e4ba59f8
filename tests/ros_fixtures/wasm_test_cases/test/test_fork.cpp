// Copyright 2026 The colcon-wasm authors
// Licensed under the Apache License, Version 2.0

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

TEST(Fork, child_exits)
{
  pid_t pid = fork();
  ASSERT_NE(-1, pid) << "fork: " << std::strerror(errno);
  if (pid == 0) {
    _exit(3);
  }
  int status = 0;
  ASSERT_EQ(pid, waitpid(pid, &status, 0));
  EXPECT_EQ(3, WEXITSTATUS(status));
}
