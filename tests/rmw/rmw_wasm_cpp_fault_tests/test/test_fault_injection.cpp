// Copyright 2026 The colcon-wasm authors
// Licensed under the Apache License, Version 2.0

// rmw_wasm_cpp after injected failures. Each case runs one rmw operation
// under RCUTILS_FAULT_INJECTION_TEST: the operation runs again and again,
// and each time the next fault point on its path (an rcutils allocation, a
// string copy, ...) fails. Whatever fails must be undone: the heap is where
// it was, the bus holds no endpoint of a failed creation, and messages still
// go through afterwards.

#include <gtest/gtest.h>
#include <malloc.h>

#include <chrono>
#include <cstring>
#include <functional>
#include <string>

#include "rcutils/allocator.h"
#include "rcutils/strdup.h"
#include "rcutils/testing/fault_injection.h"
#include "rcutils/types/string_array.h"
#include "rmw/error_handling.h"
#include "rmw/get_topic_names_and_types.h"
#include "rmw/names_and_types.h"
#include "rmw/rmw.h"
#include "rosidl_runtime_c/message_type_support_struct.h"
#include "rosidl_runtime_c/service_type_support_struct.h"
#include "rosidl_runtime_c/string_functions.h"
#include "test_msgs/msg/strings.h"
#include "test_msgs/srv/basic_types.h"

#ifndef RCUTILS_ENABLE_FAULT_INJECTION
#error "build with --wasm-fault-injection (RCUTILS_ENABLE_FAULT_INJECTION)"
#endif

namespace
{

size_t heap_in_use()
{
  return mallinfo().uordblks;
}

const rosidl_message_type_support_t * strings_type()
{
  return ROSIDL_GET_MSG_TYPE_SUPPORT(test_msgs, msg, Strings);
}

class FaultInjection : public ::testing::Test
{
protected:
  void SetUp() override
  {
    options_ = rmw_get_zero_initialized_init_options();
    ASSERT_EQ(RMW_RET_OK, rmw_init_options_init(&options_, rcutils_get_default_allocator()));
    options_.enclave = rcutils_strdup("/", rcutils_get_default_allocator());
    context_ = rmw_get_zero_initialized_context();
    ASSERT_EQ(RMW_RET_OK, rmw_init(&options_, &context_)) << rmw_get_error_string().str;
    node_ = rmw_create_node(&context_, "fault_injection", "/");
    ASSERT_NE(nullptr, node_) << rmw_get_error_string().str;
  }

  void TearDown() override
  {
    EXPECT_EQ(RMW_RET_OK, rmw_destroy_node(node_));
    EXPECT_EQ(RMW_RET_OK, rmw_shutdown(&context_));
    EXPECT_EQ(RMW_RET_OK, rmw_context_fini(&context_));
    EXPECT_EQ(RMW_RET_OK, rmw_init_options_fini(&options_));
  }

  // Run `operation` (true: it succeeded, and undid itself without faults)
  // under fault injection; returns how many runs failed.
  static int under_fault_injection(const std::function<bool()> & operation)
  {
    int failed = 0;
    RCUTILS_FAULT_INJECTION_TEST(
    {
      if (!operation()) {
        ++failed;
        rmw_reset_error();
      }
    });
    return failed;
  }

  // Check that failed runs leave nothing behind: the heap after a second
  // round of injected failures is the heap after the first (which may fill
  // caches once), and at least `min_failures` runs failed.
  void expect_no_leak(const char * what, int min_failures, const std::function<bool()> & op)
  {
    int first = under_fault_injection(op);
    size_t before = heap_in_use();
    int second = under_fault_injection(op);
    size_t after = heap_in_use();
    EXPECT_GE(first, min_failures) << what << ": the fault points did not fail";
    EXPECT_EQ(first, second) << what;
    EXPECT_EQ(before, after) << what << ": " << (after - before) <<
      " bytes left behind by " << second << " failed runs";
  }

  size_t count(bool publishers, const char * topic)
  {
    size_t n = 0;
    rmw_ret_t ret = publishers ? rmw_count_publishers(node_, topic, &n) :
      rmw_count_subscribers(node_, topic, &n);
    EXPECT_EQ(RMW_RET_OK, ret) << rmw_get_error_string().str;
    return n;
  }

  rmw_init_options_t options_;
  rmw_context_t context_;
  rmw_node_t * node_ = nullptr;
};

TEST_F(FaultInjection, init_and_shutdown)
{
  expect_no_leak("rmw_init", 1, [this]() {
      rmw_context_t context = rmw_get_zero_initialized_context();
      if (rmw_init(&options_, &context) != RMW_RET_OK) {
        return false;
      }
      RCUTILS_NO_FAULT_INJECTION(
      {
        EXPECT_EQ(RMW_RET_OK, rmw_shutdown(&context));
        EXPECT_EQ(RMW_RET_OK, rmw_context_fini(&context));
      });
      return true;
    });
}

TEST_F(FaultInjection, nodes)
{
  expect_no_leak("rmw_create_node", 1, [this]() {
      rmw_node_t * node = rmw_create_node(&context_, "faulty", "/ns");
      if (node == nullptr) {
        return false;
      }
      RCUTILS_NO_FAULT_INJECTION({EXPECT_EQ(RMW_RET_OK, rmw_destroy_node(node));});
      return true;
    });
}

TEST_F(FaultInjection, publishers_and_subscriptions)
{
  rmw_publisher_options_t pub_options = rmw_get_default_publisher_options();
  expect_no_leak("rmw_create_publisher", 1, [&]() {
      rmw_publisher_t * pub = rmw_create_publisher(
        node_, strings_type(), "/faulty", &rmw_qos_profile_default, &pub_options);
      if (pub == nullptr) {
        return false;
      }
      RCUTILS_NO_FAULT_INJECTION({EXPECT_EQ(RMW_RET_OK, rmw_destroy_publisher(node_, pub));});
      return true;
    });
  rmw_subscription_options_t sub_options = rmw_get_default_subscription_options();
  expect_no_leak("rmw_create_subscription", 1, [&]() {
      rmw_subscription_t * sub = rmw_create_subscription(
        node_, strings_type(), "/faulty", &rmw_qos_profile_default, &sub_options);
      if (sub == nullptr) {
        return false;
      }
      RCUTILS_NO_FAULT_INJECTION({EXPECT_EQ(RMW_RET_OK, rmw_destroy_subscription(node_, sub));});
      return true;
    });
  // no endpoint of a failed creation is left on the bus
  EXPECT_EQ(0u, count(true, "/faulty"));
  EXPECT_EQ(0u, count(false, "/faulty"));
}

TEST_F(FaultInjection, services_and_clients)
{
  const rosidl_service_type_support_t * ts =
    ROSIDL_GET_SRV_TYPE_SUPPORT(test_msgs, srv, BasicTypes);
  expect_no_leak("rmw_create_service", 1, [&]() {
      rmw_service_t * service = rmw_create_service(
        node_, ts, "/faulty_service", &rmw_qos_profile_services_default);
      if (service == nullptr) {
        return false;
      }
      RCUTILS_NO_FAULT_INJECTION({EXPECT_EQ(RMW_RET_OK, rmw_destroy_service(node_, service));});
      return true;
    });
  expect_no_leak("rmw_create_client", 1, [&]() {
      rmw_client_t * client = rmw_create_client(
        node_, ts, "/faulty_service", &rmw_qos_profile_services_default);
      if (client == nullptr) {
        return false;
      }
      RCUTILS_NO_FAULT_INJECTION({EXPECT_EQ(RMW_RET_OK, rmw_destroy_client(node_, client));});
      return true;
    });
}

TEST_F(FaultInjection, wait_sets_and_guard_conditions)
{
  expect_no_leak("rmw_create_wait_set", 0, [&]() {
      rmw_wait_set_t * wait_set = rmw_create_wait_set(&context_, 4);
      if (wait_set == nullptr) {
        return false;
      }
      RCUTILS_NO_FAULT_INJECTION({EXPECT_EQ(RMW_RET_OK, rmw_destroy_wait_set(wait_set));});
      return true;
    });
  expect_no_leak("rmw_create_guard_condition", 0, [&]() {
      rmw_guard_condition_t * guard = rmw_create_guard_condition(&context_);
      if (guard == nullptr) {
        return false;
      }
      RCUTILS_NO_FAULT_INJECTION({EXPECT_EQ(RMW_RET_OK, rmw_destroy_guard_condition(guard));});
      return true;
    });
}

TEST_F(FaultInjection, graph_queries)
{
  rmw_publisher_options_t pub_options = rmw_get_default_publisher_options();
  rmw_publisher_t * pub = rmw_create_publisher(
    node_, strings_type(), "/graph_topic", &rmw_qos_profile_default, &pub_options);
  ASSERT_NE(nullptr, pub) << rmw_get_error_string().str;
  rcutils_allocator_t allocator = rcutils_get_default_allocator();
  expect_no_leak("rmw_get_topic_names_and_types", 1, [&]() {
      rmw_names_and_types_t names = rmw_get_zero_initialized_names_and_types();
      if (rmw_get_topic_names_and_types(node_, &allocator, false, &names) != RMW_RET_OK) {
        return false;
      }
      RCUTILS_NO_FAULT_INJECTION({EXPECT_EQ(RMW_RET_OK, rmw_names_and_types_fini(&names));});
      return true;
    });
  expect_no_leak("rmw_get_node_names", 1, [&]() {
      rcutils_string_array_t names = rcutils_get_zero_initialized_string_array();
      rcutils_string_array_t namespaces = rcutils_get_zero_initialized_string_array();
      if (rmw_get_node_names(node_, &names, &namespaces) != RMW_RET_OK) {
        return false;
      }
      RCUTILS_NO_FAULT_INJECTION(
      {
        EXPECT_EQ(RCUTILS_RET_OK, rcutils_string_array_fini(&names));
        EXPECT_EQ(RCUTILS_RET_OK, rcutils_string_array_fini(&namespaces));
      });
      return true;
    });
  EXPECT_EQ(RMW_RET_OK, rmw_destroy_publisher(node_, pub));
}

TEST_F(FaultInjection, the_bus_still_carries_messages)
{
  // after failed creations of every kind, in this process and on this bus
  under_fault_injection([this]() {
      rmw_publisher_options_t options = rmw_get_default_publisher_options();
      rmw_publisher_t * pub = rmw_create_publisher(
        node_, strings_type(), "/after_faults", &rmw_qos_profile_default, &options);
      if (pub == nullptr) {
        return false;
      }
      RCUTILS_NO_FAULT_INJECTION({EXPECT_EQ(RMW_RET_OK, rmw_destroy_publisher(node_, pub));});
      return true;
    });
  rmw_qos_profile_t qos = rmw_qos_profile_default;
  qos.reliability = RMW_QOS_POLICY_RELIABILITY_RELIABLE;
  qos.durability = RMW_QOS_POLICY_DURABILITY_TRANSIENT_LOCAL;
  rmw_publisher_options_t pub_options = rmw_get_default_publisher_options();
  rmw_publisher_t * pub = rmw_create_publisher(
    node_, strings_type(), "/after_faults", &qos, &pub_options);
  ASSERT_NE(nullptr, pub) << rmw_get_error_string().str;
  rmw_subscription_options_t sub_options = rmw_get_default_subscription_options();
  rmw_subscription_t * sub = rmw_create_subscription(
    node_, strings_type(), "/after_faults", &qos, &sub_options);
  ASSERT_NE(nullptr, sub) << rmw_get_error_string().str;
  EXPECT_EQ(1u, count(true, "/after_faults"));

  test_msgs__msg__Strings sent;
  ASSERT_TRUE(test_msgs__msg__Strings__init(&sent));
  ASSERT_TRUE(rosidl_runtime_c__String__assign(&sent.string_value, "still here"));
  ASSERT_EQ(RMW_RET_OK, rmw_publish(pub, &sent, nullptr)) << rmw_get_error_string().str;

  test_msgs__msg__Strings received;
  ASSERT_TRUE(test_msgs__msg__Strings__init(&received));
  bool taken = false;
  auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!taken && std::chrono::steady_clock::now() < deadline) {
    ASSERT_EQ(RMW_RET_OK, rmw_take(sub, &received, &taken, nullptr));
  }
  ASSERT_TRUE(taken) << "no message after the injected failures";
  EXPECT_STREQ("still here", received.string_value.data);
  test_msgs__msg__Strings__fini(&sent);
  test_msgs__msg__Strings__fini(&received);
  EXPECT_EQ(RMW_RET_OK, rmw_destroy_subscription(node_, sub));
  EXPECT_EQ(RMW_RET_OK, rmw_destroy_publisher(node_, pub));
}

}  // namespace
