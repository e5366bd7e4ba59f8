// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Per-subscription send queues of one Foxglove client, so that a big topic
 * never starves a small one. While the socket takes what is written
 * (its unwritten bytes under a high-water mark), a message goes out at
 * once. Past the mark, each subscription's messages wait in their own
 * queue of at most `maxMessages` (the oldest is dropped and counted), and
 * when the socket drains the queues are served in turn, one message each:
 * a 10 Hz status topic waits for at most one image of every other topic,
 * not for a backlog of images.
 *
 * @module bridges/foxglove/send_queue
 */

/** One subscription's queue. */
class Queue {
  constructor(owner, id, topic) {
    this.owner = owner;
    this.id = id;
    this.topic = topic;
    this.items = [];
    this.sent = 0;
    this.dropped = 0;
  }

  /** Send a frame now, or queue it. */
  push(frame) {
    const o = this.owner;
    if (o.closed) return;
    if (o.waiting === 0 && !o.backedUp()) {
      this.sent++;
      o.conn.send(frame);
      return;
    }
    this.items.push(frame);
    o.waiting++;
    if (this.items.length > o.maxMessages) {
      this.items.shift();
      o.waiting--;
      this.dropped++;
      o.dropped++;
      o.onDrop(this.topic, this.dropped);
    }
    o.schedule();
  }
}

/** The queues of one connection. */
export class SendQueues {
  /**
   * @param {import('../rosbridge/ws_node.mjs').WebSocketConnection} conn
   * @param {object} options
   * @param {number} [options.maxMessages=10] per queue
   * @param {number} [options.highWater=4 MiB] unwritten bytes past which messages queue
   * @param {function(string, number): void} [options.onDrop] (topic, dropped so far)
   */
  constructor(conn, { maxMessages = 10, highWater = 4 << 20, onDrop = () => {} } = {}) {
    this.conn = conn;
    this.maxMessages = maxMessages;
    this.highWater = highWater;
    this.onDrop = onDrop;
    this.queues = new Map();
    this.waiting = 0;
    this.dropped = 0;
    this.closed = false;
    this._scheduled = false;
    const previous = conn.ondrain;
    conn.ondrain = () => {
      if (previous) previous();
      this.pump();
    };
  }

  /** Is the socket holding more than the high-water mark? */
  backedUp() {
    return this.conn.bufferedAmount > this.highWater;
  }

  /** The queue of a subscription. */
  open(id, topic) {
    const q = new Queue(this, id, topic);
    this.queues.set(id, q);
    return q;
  }

  /** Drop a subscription's queue. */
  close(id) {
    const q = this.queues.get(id);
    if (!q) return;
    this.waiting -= q.items.length;
    this.queues.delete(id);
  }

  /** Drop every queue. */
  closeAll() {
    this.closed = true;
    this.queues.clear();
    this.waiting = 0;
  }

  /** Pump on the next turn (the socket may drain before it says so). */
  schedule() {
    if (this._scheduled) return;
    this._scheduled = true;
    setImmediate(() => {
      this._scheduled = false;
      this.pump();
    });
  }

  /** Send queued messages in turn, one per queue a round, while the socket takes them. */
  pump() {
    while (this.waiting > 0 && !this.closed && !this.backedUp()) {
      for (const q of this.queues.values()) {
        if (!q.items.length) continue;
        const frame = q.items.shift();
        this.waiting--;
        q.sent++;
        this.conn.send(frame);
        if (this.backedUp()) break;
      }
    }
  }

  /** Counters per topic: {topic: {sent, dropped}}. */
  stats() {
    const out = {};
    for (const q of this.queues.values()) out[q.topic] = { sent: q.sent, dropped: q.dropped };
    return out;
  }
}
