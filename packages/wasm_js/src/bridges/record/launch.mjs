// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Record and replay in `colcon-wasm run|launch|play` (launch/run_plan.mjs):
 * `plan.record` ({fd, replies, file: {fd, offset} or null, topics}) and
 * `plan.play` ({fd, rate, clock, stop_after}), the Node.js side's ends of the
 * launcher's pipes and, when the recording worker writes the bag itself, the
 * bag's descriptor (colcon_wasm/record/session.py).
 *
 * @module bridges/record/launch
 */

import { createReadStream, createWriteStream } from 'node:fs';

/** Once the bag has played, how long the subscriptions may take to take its last messages, */
const SETTLE_MS = 2000;
/** and how long their callbacks then get before `play` stops the nodes. */
const CALLBACK_GRACE_MS = 200;

/**
 * Start recording (now) and get ready to play.
 * @param {object} plan the launch plan
 * @param {import('../../runtime.mjs').Runtime} runtime
 * @param {{out: function(string): void, err: function(string): void}} io
 * @returns {Promise<{play: ?function(): Promise<number>, close: function(): Promise<void>}>}
 */
export async function startBags(plan, runtime, { out, err }) {
  const log = (level, text) => {
    const tag = { info: 'INFO', warning: 'WARNING', error: 'ERROR' }[level] || 'INFO';
    (level === 'info' ? out : err)(`[${tag}] [rosbag2]: ${text}`);
  };
  let recorder = null;
  let player = null;
  if (plan.record) {
    const { Recorder } = await import('./recorder.mjs');
    const sink = createWriteStream(null, { fd: plan.record.fd, highWaterMark: 1 << 20 });
    const replies = createReadStream(null, { fd: plan.record.replies });
    // past a file size limit (ulimit -f) a write fails with EFBIG, which the
    // recorder reports, rather than the signal ending the host and its nodes
    if (plan.record.file) process.on('SIGXFSZ', () => {});
    recorder = new Recorder({
      runtime, sink, replies, file: plan.record.file || null, topics: plan.record.topics,
      regex: plan.record.regex || null, exclude: plan.record.exclude || null, log,
    });
    await recorder.start();
  }
  let play = null;
  if (plan.play) {
    const tools = await runtime.tools();
    const { Player } = await import('./player.mjs');
    const source = createReadStream(null, { fd: plan.play.fd, highWaterMark: 1 << 20 });
    // the first message waits (3 s at most) for the launched nodes' subscriptions and
    // the recorder's, so that they get it
    const nodes = !!(plan.processes && plan.processes.length);
    const ready = (graph, name) => {
      const t = graph.topics.find((x) => x.name === name && x.domain === 0);
      const subscriptions = t ? t.subscriptions : [];
      const ours = (e) => e.pid === tools.pid || (recorder && e.pid === recorder.process.pid);
      return (!nodes || subscriptions.some((e) => !ours(e)))
        && (!recorder || !recorder.wants(name) || recorder.subscribed.has(name));
    };
    player = new Player({
      runtime, tools, source, rate: plan.play.rate || 1, clockHz: plan.play.clock || null,
      waitMs: nodes || recorder ? 3000 : 0, ready, log,
    });
    play = async () => {
      const n = await player.run();
      log('info', `played ${n} messages`);
      if (plan.play.stop_after) {
        // the launch stops the nodes next: they take what was played last, and
        // their callbacks get a moment to run
        if (!(await player.settle(SETTLE_MS))) {
          log('warning', `some subscriptions had not taken every message played ${SETTLE_MS / 1000} s after the last`);
        }
        await new Promise((resolve) => setTimeout(resolve, CALLBACK_GRACE_MS));
      }
      return n;
    };
  }
  return {
    play,
    close: async () => {
      if (player) player.close();
      if (recorder) await recorder.close();
    },
  };
}
