// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The memory layout of the bus: one SharedArrayBuffer shared by every thread
 * of every node of a page (or Node.js process). Pure constants, no logic.
 *
 * All offsets are in 32-bit words unless named *_BYTES. Records are fixed
 * size; a record becomes visible when its STATE word is stored last, and
 * disappears when STATE is cleared first, so a thread killed mid-mutation
 * leaves nothing half-visible.
 *
 *   header | process table | node table | endpoint table | link table | arena
 *
 * The arena holds rings, message blocks and strings, in blocks with a
 * 32-byte header, allocated from power-of-two size classes.
 *
 * @module layout
 */

import { ENDPOINT_FLAG_IGNORE_LOCAL, EndpointKind, QOS, QOS_FLAG_AVOID_ROS_NAMESPACE } from './abi/bus_abi.mjs';

export const MAGIC = 0x53554257; // 'WBUS'
export const LAYOUT_VERSION = 2;

/** Header words. */
export const HEADER = Object.freeze({
  MAGIC: 0,
  VERSION: 1,
  BUS_ID: 2,
  /** Registry lock: 0 free, else owner pid, | LOCK_CONTENDED when waiters may sleep. */
  LOCK: 3,
  /** Bumped after every committed registry change; also the graph doorbell. */
  GRAPH_VERSION: 4,
  GRAPH_SLEEPERS: 5,
  /** Counter for gids and context ids (never reused while the bus lives). */
  SERIAL: 6,
  ARENA_TOP: 7,
  ARENA_BASE: 8,
  MAX_MESSAGE: 9,
  MAX_BYTES_MB: 10,
  PROC_CAP: 11,
  NODE_CAP: 12,
  EP_CAP: 13,
  LINK_CAP: 14,
  PROC_OFF: 15,
  NODE_OFF: 16,
  EP_OFF: 17,
  LINK_OFF: 18,
  /** High-water marks: no record at or above this index was ever used. */
  PROC_HWM: 19,
  NODE_HWM: 20,
  EP_HWM: 21,
  LINK_HWM: 22,
  /** Quarantine list (freed blocks wait GRACE_MS before reuse). */
  QUAR_HEAD: 23,
  QUAR_TAIL: 24,
  /** Bytes currently allocated (for diagnostics). */
  ARENA_USED: 25,
  /** Where the search for a free record of each table starts next. */
  NODE_HINT: 26,
  EP_HINT: 27,
  LINK_HINT: 28,
  PROC_HINT: 29,
  /** Free list heads, one per size class. */
  FREE_BASE: 32,
});

export const HEADER_WORDS = 128;
export const SIZE_CLASSES = 32;
export const LOCK_CONTENDED = 0x40000000;
export const LOCK_OWNER_MASK = 0x3fffffff;

/** How long a freed block waits before reuse (a reader may still be copying from it). */
export const GRACE_MS = 2000;

/** Process record: one per bus process (one executable and its pthreads). */
export const PROCESS = Object.freeze({
  STATE: 0,
  /** Doorbell: incremented by every publish to one of this process' readers. */
  BELL: 1,
  SLEEPERS: 2,
  GEN: 3,
  KIND: 4,
  WORDS: 16,
});
export const PROC_FREE = 0;
export const PROC_ALIVE = 1;
export const PROC_DEAD = 2;
export const PROC_KIND_RUNTIME = 1;
export const PROC_KIND_NODE = 2;
export const PROC_KIND_TOOLS = 3;

/** Node record. */
export const NODE = Object.freeze({
  STATE: 0,
  PID: 1,
  DOMAIN: 2,
  CONTEXT: 3,
  SERIAL: 4,
  /** One arena block: name, namespace, enclave (UTF-8, back to back). */
  STR_OFF: 5,
  NAME_LEN: 6,
  NS_LEN: 7,
  ENCLAVE_LEN: 8,
  WORDS: 16,
});
export const REC_FREE = 0;
export const REC_ALIVE = 1;
/** Being removed, under the registry lock (readers still drain a writer's ring). */
export const REC_DYING = 2;
/** A removed writer whose ring is kept until its readers drained it. */
export const REC_ZOMBIE = 3;

/** Endpoint kinds (abi/bus_abi.mjs EndpointKind), and nodes' kind in gids. */
export const KIND_PUBLISHER = EndpointKind.PUBLISHER;
export const KIND_SUBSCRIPTION = EndpointKind.SUBSCRIPTION;
export const KIND_SERVICE = EndpointKind.SERVICE;
export const KIND_CLIENT = EndpointKind.CLIENT;
export const KIND_NODE = 5;

/** Endpoint record (publisher, subscription, service server or client). */
export const ENDPOINT = Object.freeze({
  STATE: 0,
  KIND: 1,
  PID: 2,
  NODE: 3,
  DOMAIN: 4,
  CONTEXT: 5,
  SERIAL: 6,
  FLAGS: 7,
  /** One arena block: name then type name (UTF-8). */
  STR_OFF: 8,
  NAME_LEN: 9,
  TYPE_LEN: 10,
  /** FNV-1a hash of the name, compared before the names themselves. */
  NAME_HASH: 11,
  /** QoS, 12 words in wasm_bus_qos layout (see QOS below). */
  QOS: 12,
  /** Derived durations in milliseconds (Infinity when none), float64 at word/2. */
  DEADLINE_MS_F64: 24,
  LIFESPAN_MS_F64: 26,
  LEASE_MS_F64: 28,
  /** Writer side (publishers, clients' requests, services' responses). */
  RING_OFF: 30,
  RING_SLOTS: 31,
  /** Messages committed so far (u32, wraps) and the wrap count. */
  HEAD: 32,
  HEAD_HI: 33,
  /** Writer lock among the threads of the owning process. */
  WLOCK: 34,
  /** Threads waiting for readers to take (publish on a full ring, wait_for_all_acked). */
  ACK_WAITERS: 35,
  LAST_PUB_F64: 36,
  LAST_ASSERT_F64: 38,
  CREATED_F64: 40,
  /** Reader side. */
  RECV_SEQ_LO: 42,
  RECV_SEQ_HI: 43,
  /** Event state, guarded by EVLOCK. */
  EVLOCK: 44,
  INCOMPAT_TOTAL: 45,
  INCOMPAT_POLICY: 46,
  INCOMPAT_SEEN: 47,
  LOST_TOTAL: 48,
  LOST_SEEN: 49,
  DEADLINE_TOTAL: 50,
  DEADLINE_SEEN: 51,
  DEADLINE_ACCT_N: 52,
  DEADLINE_ACCT_BASE_F64: 54,
  LIVE_LOST_TOTAL: 56,
  LIVE_LOST_SEEN: 57,
  LIVE_LOST_BASE_F64: 58,
  ALIVE_SEEN: 60,
  NOT_ALIVE_SEEN: 61,
  WORDS: 64,
});
export const EP_FLAG_IGNORE_LOCAL = ENDPOINT_FLAG_IGNORE_LOCAL;

/** QoS words: abi/bus_abi.mjs QOS (shared with wasm_cpp). */
export { QOS, QOS_FLAG_AVOID_ROS_NAMESPACE };

/** Link record: one matched (writer ring, reader) pair with the reader's cursor. */
export const LINK = Object.freeze({
  STATE: 0,
  WRITER: 1,
  READER: 2,
  /** Index of the next message this reader has not taken (u32, wraps). */
  CURSOR: 3,
  FLAGS: 4,
  /** Reader history depth for KEEP_LAST, 0 for KEEP_ALL. */
  DEPTH: 5,
  WRITER_SERIAL: 6,
  READER_SERIAL: 7,
  /** A cache line (64 bytes) each: a reader's cursor shares no line with another link's. */
  WORDS: 16,
});
/** The writer must not overwrite a message this reader has not taken. */
export const LINK_BLOCKING = 1;
/** Response link: the reader takes only slots addressed to it. */
export const LINK_TARGETED = 2;
/** The reader is BEST_EFFORT: every skipped message counts as lost. */
export const LINK_BEST_EFFORT = 4;

/** Ring slot. */
export const SLOT = Object.freeze({
  /** n+1 when message n is committed, ~(n+1) while it is being written. */
  COMMIT: 0,
  SEQ_HI: 1,
  BLOCK: 2,
  CAP: 3,
  LEN: 4,
  /** Response slots: target reader endpoint index + 1 and its serial. */
  TARGET: 5,
  TARGET_SERIAL: 6,
  REQ_LO: 7,
  TIME_F64: 8,
  REQ_HI: 10,
  WORDS: 16,
});

/** Arena block header. */
export const BLOCK = Object.freeze({
  CLASS: 0,
  STATE: 1,
  OWNER: 2,
  NEXT: 3,
  FREED_F64: 4,
  WORDS: 8,
});
export const BLOCK_HEADER_BYTES = 32;
export const BLOCK_USED = 1;
export const BLOCK_FREE = 2;
export const BLOCK_QUARANTINE = 3;
/** Smallest block payload: 2^MIN_CLASS_SHIFT bytes. */
export const MIN_CLASS_SHIFT = 5;

/** Defaults of Runtime.create() / Bus.create(). */
export const DEFAULTS = Object.freeze({
  maxMessageBytes: 64 * 1024 * 1024,
  initialBytes: 16 * 1024 * 1024,
  maxBytes: 1024 * 1024 * 1024,
  maxProcesses: 256,
  maxNodes: 1024,
  maxEndpoints: 8192,
  maxLinks: 32768,
});
