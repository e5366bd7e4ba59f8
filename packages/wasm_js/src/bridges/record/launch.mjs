// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Record and replay in `colcon-wasm run|launch|play` (launch/run_plan.mjs):
 * `plan.record` ({fd, topics}) and `plan.play` ({fd, rate, clock,
 * stop_after}), the Node.js side's ends of the launcher's pipes
 * (colcon_wasm/record/session.py).
 *
 * @module bridges/record/launch
 */

import { createReadStream, createWriteStream } from 'node:fs';

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
  const tools = await runtime.tools();
  let recorder = null;
  let player = null;
  if (plan.record) {
    const { Recorder } = await import('./recorder.mjs');
    const sink = createWriteStream(null, { fd: plan.record.fd, highWaterMark: 1 << 20 });
    recorder = new Recorder({ runtime, tools, sink, topics: plan.record.topics, log });
    await recorder.start();
  }
  let play = null;
  if (plan.play) {
    const { Player } = await import('./player.mjs');
    const source = createReadStream(null, { fd: plan.play.fd, highWaterMark: 1 << 20 });
    // the first message waits (3 s at most) for the launched nodes' subscriptions and
    // the recorder's, so that they get it
    const nodes = !!(plan.processes && plan.processes.length);
    const ready = (graph, name) => {
      const t = graph.topics.find((x) => x.name === name && x.domain === 0);
      const subscriptions = t ? t.subscriptions : [];
      return (!nodes || subscriptions.some((e) => e.pid !== tools.pid))
        && (!recorder || !recorder.wants(name) || recorder.subscribed.has(name));
    };
    player = new Player({
      runtime, tools, source, rate: plan.play.rate || 1, clockHz: plan.play.clock || null,
      waitMs: nodes || recorder ? 3000 : 0, ready, log,
    });
    play = async () => {
      const n = await player.run();
      log('info', `played ${n} messages`);
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
