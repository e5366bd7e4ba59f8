// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Topic statistics as `ros2 topic hz` and `ros2 topic bw` report them: the
 * average rate with min/max/std dev of the intervals, and the bandwidth,
 * over a sliding window of the last `window` messages.
 */
export class TopicStats {
  constructor({ window = 1000 } = {}) {
    this.window = window;
    this.times = new Float64Array(window);
    this.sizes = new Float64Array(window);
    this.count = 0;     // messages in the window
    this.next = 0;      // ring index of the next message
    this.total = 0;     // messages ever
    this.totalBytes = 0;
  }

  /** Record one message received at `timeMs` (performance.now()) of `bytes`. */
  add(timeMs, bytes) {
    this.times[this.next] = timeMs;
    this.sizes[this.next] = bytes;
    this.next = (this.next + 1) % this.window;
    if (this.count < this.window) this.count++;
    this.total++;
    this.totalBytes += bytes;
  }

  /** Forget the window (e.g. after a pause). */
  reset() {
    this.count = 0;
    this.next = 0;
  }

  /**
   * The statistics of the window, or null with fewer than two messages.
   * @param {number} nowMs the current time, to notice a topic that stopped
   */
  summary(nowMs) {
    if (this.count < 2) return null;
    const n = this.count;
    const first = (this.next - n + this.window) % this.window;
    let min = Infinity;
    let max = 0;
    let sum = 0;
    let sumSq = 0;
    let bytes = 0;
    let prev = this.times[first];
    for (let k = 1; k < n; k++) {
      const i = (first + k) % this.window;
      const dt = (this.times[i] - prev) / 1000;
      prev = this.times[i];
      if (dt < min) min = dt;
      if (dt > max) max = dt;
      sum += dt;
      sumSq += dt * dt;
      bytes += this.sizes[i];
    }
    const intervals = n - 1;
    const mean = sum / intervals;
    const std = Math.sqrt(Math.max(0, sumSq / intervals - mean * mean));
    const last = this.times[(this.next - 1 + this.window) % this.window];
    const span = (last - this.times[first]) / 1000;
    return {
      rate: mean > 0 ? 1 / mean : Infinity,
      min,
      max,
      std,
      window: n,
      bytesPerSecond: span > 0 ? bytes / span : 0,
      meanBytes: bytes / intervals,
      sinceLastMs: nowMs === undefined ? 0 : nowMs - last,
    };
  }
}

/** Format a byte rate as `ros2 topic bw` does: B/s, KB/s, MB/s. */
export function formatBandwidth(bytesPerSecond) {
  if (bytesPerSecond >= 1e6) return `${(bytesPerSecond / 1e6).toFixed(2)} MB/s`;
  if (bytesPerSecond >= 1e3) return `${(bytesPerSecond / 1e3).toFixed(2)} KB/s`;
  return `${bytesPerSecond.toFixed(2)} B/s`;
}
