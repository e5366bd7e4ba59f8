// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The numbers wasm_cpp (C++) and wasm_js (JS) share: status codes, endpoint
 * kinds, take modes, wait item kinds, event types, the QoS words and
 * policies, and the word layouts of the structs library_wasm_bus.js fills.
 * Pure constants, no logic.
 *
 * The C++ side writes the same numbers in packages/wasm_cpp
 * (src/bus_abi.hpp, include/wasm_cpp/{status,graph,events,wait_set,qos}.hpp,
 * src/bus_abi.cpp's qos_to_wire, src/events.cpp's event status);
 * tests/test_bus_abi.py fails when the two disagree, or when
 * library_wasm_bus.js' tables differ from these.
 *
 * @module abi/bus_abi
 */

/** Status codes (wasm_cpp::Code). */
export const Code = Object.freeze({
  OK: 0, ERROR: 1, TIMEOUT: 2, UNSUPPORTED: 3, BAD_ALLOC: 10, INVALID_ARGUMENT: 11,
  NODE_NAME_NON_EXISTENT: 203,
});

/** Endpoint kinds (wasm_cpp::EndpointKind, wasm_cpp::detail::BusKind). */
export const EndpointKind = Object.freeze({
  PUBLISHER: 1, SUBSCRIPTION: 2, SERVICE: 3, CLIENT: 4,
});

/** Take modes: what an endpoint reads (wasm_cpp::detail::BusTakeMode). */
export const TakeMode = Object.freeze({ MESSAGE: 0, REQUEST: 1, RESPONSE: 2 });

/** Wait item kinds (wasm_cpp::WaitItem::Kind). */
export const WaitKind = Object.freeze({
  SUBSCRIPTION: 0, SERVICE: 1, CLIENT: 2, GUARD_CONDITION: 3, EVENT: 4,
});

/** Words per wait item: kind, handle, aux, result. */
export const WAIT_ITEM_WORDS = 4;

/** Event kinds (rmw_event_type_t, wasm_cpp::EventType). */
export const EventType = Object.freeze({
  LIVELINESS_CHANGED: 0,
  REQUESTED_DEADLINE_MISSED: 1,
  REQUESTED_QOS_INCOMPATIBLE: 2,
  MESSAGE_LOST: 3,
  LIVELINESS_LOST: 4,
  OFFERED_DEADLINE_MISSED: 5,
  OFFERED_QOS_INCOMPATIBLE: 6,
});

/** QoS words (the 12-word wire form, wasm_cpp::detail::qos_to_wire). */
export const QOS = Object.freeze({
  HISTORY: 0,
  DEPTH: 1,
  RELIABILITY: 2,
  DURABILITY: 3,
  LIVELINESS: 4,
  FLAGS: 5,
  DEADLINE_LO: 6,
  DEADLINE_HI: 7,
  LIFESPAN_LO: 8,
  LIFESPAN_HI: 9,
  LEASE_LO: 10,
  LEASE_HI: 11,
  WORDS: 12,
});
/** QoS FLAGS bit: avoid_ros_namespace_conventions. */
export const QOS_FLAG_AVOID_ROS_NAMESPACE = 1;

/** QoS policy values (rmw's enums, wasm_cpp::History etc.). */
export const History = Object.freeze({ SYSTEM_DEFAULT: 0, KEEP_LAST: 1, KEEP_ALL: 2 });
export const Reliability = Object.freeze({ SYSTEM_DEFAULT: 0, RELIABLE: 1, BEST_EFFORT: 2 });
export const Durability = Object.freeze({ SYSTEM_DEFAULT: 0, TRANSIENT_LOCAL: 1, VOLATILE: 2 });
export const Liveliness = Object.freeze({
  SYSTEM_DEFAULT: 0, AUTOMATIC: 1, MANUAL_BY_NODE: 2, MANUAL_BY_TOPIC: 3,
});
/** rmw_qos_policy_kind_t bits (wasm_cpp::QosPolicyKind). */
export const PolicyKind = Object.freeze({
  INVALID: 1, DURABILITY: 2, DEADLINE: 4, LIVELINESS: 8, RELIABILITY: 16,
  HISTORY: 32, LIFESPAN: 64, DEPTH: 128, LIVELINESS_LEASE_DURATION: 256,
});

/** wasm_bus_endpoint_create() flags: a subscription skips publishers of its own context. */
export const ENDPOINT_FLAG_IGNORE_LOCAL = 1;

/**
 * struct wasm_bus_take_info, in 32-bit words (*_F64: a double at word/2).
 * library_wasm_bus.js' WasmBus.TAKE_INFO repeats it.
 */
export const TAKE_INFO = Object.freeze({
  SOURCE_MS_F64: 0,
  RECEIVED_MS_F64: 2,
  PUB_SEQ_LO: 4,
  PUB_SEQ_HI: 5,
  RECV_SEQ_LO: 6,
  RECV_SEQ_HI: 7,
  GID: 8,
  REQ_SEQ_LO: 12,
  REQ_SEQ_HI: 13,
  SAME_PROCESS: 14,
  LENGTH: 15,
  DATA: 16,
  CAPACITY: 17,
  WORDS: 18,
});

/**
 * The status words wasm_bus_event_status() writes (wasm_cpp::Event::take).
 * library_wasm_bus.js' WasmBus.EVENT_STATUS repeats it.
 */
export const EVENT_STATUS = Object.freeze({
  CHANGED: 0,
  TOTAL: 1,
  CHANGE: 2,
  ALIVE: 3,
  NOT_ALIVE: 4,
  ALIVE_CHANGE: 5,
  NOT_ALIVE_CHANGE: 6,
  POLICY: 7,
  WORDS: 8,
});
