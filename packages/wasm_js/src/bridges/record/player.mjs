// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The replay side of `colcon-wasm play` / `launch --play` in the Node.js launcher:
 * the launcher reads the bag and streams its messages down a pipe
 * (./frames.mjs); this publishes each one on the bus at its time, the
 * recorded gaps divided by the rate, with a publisher per topic of the
 * QoS the launcher derived from the recorded offers. The timing is kept
 * here, next to the bus, so the pipe adds no jitter. With a clock rate,
 * `/clock` (rosgraph_msgs/msg/Clock) carries the bag time.
 *
 * @module bridges/record/player
 */

import { performance } from 'node:perf_hooks';

import { CLOCK_QOS, clockMessage } from './clock.mjs';
import { FrameReader, Kind } from './frames.mjs';

/** Messages read ahead of their time; the pipe is paused beyond this. */
const HIGH_WATER = 4000;
const LOW_WATER = 1000;
/** Publish calls to the tools worker in flight before waiting for the oldest. */
const IN_FLIGHT = 64;
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

export class Player {
  /**
   * @param {object} options
   * @param {import('../../runtime.mjs').Runtime} options.runtime
   * @param {import('../../tools_process/main_thread.mjs').Tools} options.tools
   * @param {import('node:stream').Readable} options.source the pipe from the launcher
   * @param {number} [options.rate=1]
   * @param {?number} [options.clockHz] publish /clock at this rate
   * @param {number} [options.waitMs=0] before the first message, wait this long at most
   *   until `ready(graph, topic)` holds for every topic announced so far
   * @param {function(object, string): boolean} [options.ready]
   * @param {function(string, string): void} options.log (level, text)
   */
  constructor({ runtime, tools, source, rate = 1, clockHz = null, waitMs = 0, ready = () => true, log }) {
    Object.assign(this, { runtime, tools, source, rate, clockHz, waitMs, ready, log });
    this.queue = [];
    this.head = 0;
    this.channels = new Map();
    this.ended = false;
    this.stopped = false;
    this.published = 0;
    this._wake = null;
    this._reader = new FrameReader();
    this.node = tools.createNode('rosbag2_player', { namespace: '/' });
    source.on('data', (chunk) => this._onData(chunk));
    source.on('end', () => { this.ended = true; this._poke(); });
    source.on('error', (e) => { this.log('error', `the replay pipe failed: ${e.message}`); this.ended = true; this._poke(); });
  }

  get _queued() {
    return this.queue.length - this.head;
  }

  _onData(chunk) {
    for (const f of this._reader.push(chunk)) {
      if (f.kind === Kind.CHANNEL) {
        const { id, topic, type, qos } = f.json;
        const publisher = this.node.then((node) => this.tools.advertise({ topic, type, qos, node }));
        publisher.catch((e) => this.log('error', `cannot publish on '${topic}' (${type}): ${e.message}`));
        this.channels.set(id, { topic, type, publisher });
      } else if (f.kind === Kind.MESSAGE) {
        this.queue.push(f);
      } else if (f.kind === Kind.END) {
        this.ended = true;
      }
    }
    if (this._queued > HIGH_WATER) this.source.pause();
    this._poke();
  }

  _poke() {
    if (this._wake) {
      const w = this._wake;
      this._wake = null;
      w();
    }
  }

  _next() {
    if (this._queued > 0 || this.ended || this.stopped) return Promise.resolve();
    return new Promise((resolve) => { this._wake = resolve; });
  }

  async _waitForSubscribers() {
    if (!this.waitMs) return;
    const until = performance.now() + this.waitMs;
    const topics = [...this.channels.values()].map((c) => c.topic);
    while (!this.stopped && performance.now() < until) {
      const graph = this.runtime.graph();
      if (topics.every((name) => this.ready(graph, name))) return;
      await sleep(20);
    }
  }

  /**
   * Play until the launcher's END and every message is published, or close().
   * @returns {Promise<number>} the messages published
   */
  async run() {
    const inFlight = [];
    let start = null;
    let bagStart = 0n;
    let clockTimer = null;
    let clock = null;
    const bagNow = () => bagStart + BigInt(Math.round((performance.now() - start) * 1e6 * this.rate));
    try {
      while (!this.stopped) {
        await this._next();
        if (this._queued === 0) {
          if (this.ended || this.stopped) break;
          continue;
        }
        const first = this.queue[this.head];
        if (start === null) {
          await this._waitForSubscribers();
          start = performance.now() - first.offsetNs / 1e6 / this.rate;
          bagStart = BigInt(first.sec) * 1000000000n + BigInt(first.nanosec) - BigInt(Math.round(first.offsetNs));
          if (this.clockHz) {
            const node = await this.node;
            clock = await this.tools.advertise({ topic: '/clock', type: 'rosgraph_msgs/msg/Clock', qos: CLOCK_QOS, node });
            const tick = () => clock.publish(clockMessage(bagNow())).catch(() => {});
            tick();
            clockTimer = setInterval(tick, 1000 / this.clockHz);
          }
        }
        const wait = start + first.offsetNs / 1e6 / this.rate - performance.now();
        if (wait > 0.5) {
          await sleep(wait);
          continue;
        }
        // every message that is due, in order; a run on one topic goes in one call
        const now = performance.now();
        while (this._queued > 0 && start + this.queue[this.head].offsetNs / 1e6 / this.rate - now <= 0.5) {
          const channel = this.queue[this.head].channel;
          const run = [];
          while (this._queued > 0 && this.queue[this.head].channel === channel
            && start + this.queue[this.head].offsetNs / 1e6 / this.rate - now <= 0.5) {
            run.push(this.queue[this.head++].data);
          }
          const c = this.channels.get(channel);
          if (!c) continue;
          const publisher = await c.publisher.catch(() => null);
          if (!publisher) continue;
          inFlight.push(publisher.publishMany(run).then(() => { this.published += run.length; }, (e) => {
            this.log('error', `publishing on '${c.topic}' failed: ${e.message}`);
          }));
          if (inFlight.length > IN_FLIGHT) await inFlight.shift();
        }
        if (this.head > 4096) {
          this.queue = this.queue.slice(this.head);
          this.head = 0;
        }
        if (this._queued < LOW_WATER && this.source.isPaused()) this.source.resume();
      }
      await Promise.all(inFlight);
    } finally {
      if (clockTimer) clearInterval(clockTimer);
    }
    return this.published;
  }

  /**
   * Wait until the subscriptions took what was played (`timeoutMs` at most
   * in all): before the launch stops them, once the bag has played.
   * @returns {Promise<boolean>} false when some had not taken it all in time
   */
  async settle(timeoutMs) {
    const until = performance.now() + timeoutMs;
    let all = true;
    for (const c of this.channels.values()) {
      const publisher = await c.publisher.catch(() => null);
      if (!publisher) continue;
      const left = Math.max(0, until - performance.now());
      if (!(await publisher.waitForAllAcked(left).catch(() => false))) all = false;
    }
    return all;
  }

  /** Stop playing (what is in flight is still published). */
  close() {
    this.stopped = true;
    this.source.destroy();
    this._poke();
  }
}
