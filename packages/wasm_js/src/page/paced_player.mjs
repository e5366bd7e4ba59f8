// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Play a bag's messages in their recorded timing, with pause, step, seek,
 * rate and a /clock tick: the page's player for a bag read in the page
 * (./mcap_reader.mjs). It keeps the rules of serve's player
 * (colcon_wasm/record/paced_player.py), which the page drives over `/bag`
 * under `colcon-wasm serve`: message *i* goes at `wall0 + (t_i - bag0) /
 * rate`, and the clock is rebased (`wall0` now, `bag0` the next message's
 * time) at every resume, seek and rate change, so a pause never makes the
 * next messages burst out; step pauses and sends the next message at once;
 * seek sends nothing between; once it ended, play starts again from the
 * start. Timers are the page's (`setTimeout`): a hidden tab's timers are
 * slowed by the browser, and its messages then go in bursts.
 *
 * @module page/paced_player
 */

/** How often the state is reported while playing (ms), as serve's player. */
export const REPORT_INTERVAL_MS = 200;

/**
 * A message to play.
 * @typedef {object} PlayedMessage
 * @property {number} channel the id its publisher is known by
 * @property {bigint} logTime nanoseconds
 * @property {Uint8Array} data
 */

/** A bag being played: `play`, `pause`, `step`, `seek`, `setRate`, `setClock`, `close`. */
export class PacedPlayer {
  /**
   * A paused player at the start.
   * @param {PlayedMessage[]} messages in log-time order
   * @param {object} hooks
   * @param {function(number, number, Uint8Array): void} hooks.send (channel, position ms, data) when due
   * @param {function(object): void} hooks.report `{state, position_ms, sent, rate}` (and `error` at
   *   the end of a damaged file) on each change and every `REPORT_INTERVAL_MS` while playing
   * @param {function(bigint): void} [hooks.tick] the bag time (ns) for /clock, `setClock(hz)` times
   *   a second while playing, and at each step and seek
   * @param {?string} [hooks.error] where the file stopped being readable: told at the end
   * @param {function(): number} [hooks.now] a clock in ms
   */
  constructor(messages, { send, report, tick = () => {}, error = null, now = () => performance.now() }) {
    this.messages = messages;
    this.start = messages.length ? messages[0].logTime : 0n;
    Object.assign(this, { send, report, tick, error, now });
    this.state = 'paused';
    this.rate = 1;
    this.clockHz = 0;
    this.sent = 0;
    this.position = 0;
    this.next = 0;
    this._timer = null;
    this._closed = false;
    this._rebase();
  }

  /** Play from where it stands (from the start again once it ended). */
  play() {
    if (this.state === 'ended') this._seekTo(0);
    this.state = 'playing';
    this._changed();
  }

  /** Stop sending; the position stays. */
  pause() {
    if (this.state === 'playing') this.state = 'paused';
    this._changed();
  }

  /** Pause, and send the next message at once. */
  step() {
    if (this.state === 'playing') this.state = 'paused';
    if (this.next < this.messages.length) {
      if (this.clockHz > 0) this.tick(this.messages[this.next].logTime);
      this._emit();
    }
    this._changed();
  }

  /** Go to `positionMs` from the first message; nothing before it is sent. */
  seek(positionMs) {
    this._seekTo(Math.max(0, Number(positionMs) || 0));
    if (this.state === 'ended') this.state = 'paused';
    if (this.clockHz > 0 && this.next < this.messages.length) this.tick(this.messages[this.next].logTime);
    this._changed();
  }

  /** Play `rate` times as fast as recorded (> 0). */
  setRate(rate) {
    if (!(rate > 0)) throw new RangeError(`the rate must be > 0, not ${rate}`);
    this.rate = Number(rate);
    this._changed();
  }

  /** Publish the bag time `hz` times a second while playing (0: no clock). */
  setClock(hz) {
    if (!(hz >= 0)) throw new RangeError(`the clock rate must be >= 0, not ${hz}`);
    this.clockHz = Number(hz);
    this._changed();
  }

  /** Stop for good. */
  close() {
    this._closed = true;
    clearTimeout(this._timer);
    this._timer = null;
  }

  /** `{state, position_ms, sent, rate}` as serve's player reports it. */
  get status() {
    const s = { state: this.state, position_ms: this.position, sent: this.sent, rate: this.rate };
    if (this.state === 'ended' && this.error) s.error = this.error;
    return s;
  }

  _seekTo(positionMs) {
    const target = this.start + BigInt(Math.round(positionMs * 1e6));
    let lo = 0;
    let hi = this.messages.length;
    while (lo < hi) {
      const mid = (lo + hi) >>> 1;
      if (this.messages[mid].logTime < target) lo = mid + 1;
      else hi = mid;
    }
    this.next = lo;
    this.position = positionMs;
  }

  _rebase() {
    this._wall0 = this.now();
    this._bag0 = this.next < this.messages.length ? this.messages[this.next].logTime : 0n;
    this._nextTick = this._wall0;
  }

  _emit() {
    const m = this.messages[this.next++];
    this.position = Number(m.logTime - this.start) / 1e6;
    this.sent++;
    this.send(m.channel, this.position, m.data);
  }

  /** A control changed something: rebase, report, and run the timer again. */
  _changed() {
    if (this._closed) return;
    this._rebase();
    if (this.state === 'playing' && this.next >= this.messages.length) this.state = 'ended';
    this.report(this.status);
    this._lastReport = this.now();
    this._run();
  }

  _due(i) {
    return this._wall0 + Number(this.messages[i].logTime - this._bag0) / 1e6 / this.rate;
  }

  /** Send what is due, then sleep until the next message, tick or report. */
  _run() {
    clearTimeout(this._timer);
    this._timer = null;
    if (this._closed || this.state !== 'playing') return;
    let now = this.now();
    while (this.next < this.messages.length && this._due(this.next) <= now) {
      this._emit();
      now = this.now();
    }
    if (this.clockHz > 0 && now >= this._nextTick) {
      this.tick(this._bag0 + BigInt(Math.round((now - this._wall0) * this.rate * 1e6)));
      this._nextTick = now + 1000 / this.clockHz;
    }
    if (this.next >= this.messages.length) {
      this.state = 'ended';
      this.report(this.status);
      return;
    }
    if (now - this._lastReport >= REPORT_INTERVAL_MS) {
      this.report(this.status);
      this._lastReport = now;
    }
    let wake = Math.min(this._due(this.next), this._lastReport + REPORT_INTERVAL_MS);
    if (this.clockHz > 0) wake = Math.min(wake, this._nextTick);
    this._timer = setTimeout(() => this._run(), Math.max(0, wake - now));
  }
}
