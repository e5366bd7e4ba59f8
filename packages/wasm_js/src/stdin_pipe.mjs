// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * A process' standard input: a byte ring in a SharedArrayBuffer, written by
 * the Runtime (page main thread or Node.js main thread) and read by the
 * executable's worker, which blocks while it is empty, like a terminal.
 *
 * Layout: three Int32 words (bytes written, bytes read, closed), then the
 * data. Counters grow forever and wrap at 2^32; one writer, one reader.
 *
 * @module stdin_pipe
 */

const WRITTEN = 0;
const READ = 1;
const CLOSED = 2;
const HEADER_BYTES = 16;

/** Default capacity of a pipe (bytes); writes larger than that wait for the reader. */
export const DEFAULT_STDIN_CAPACITY = 64 * 1024;

export class StdinPipe {
  /**
   * Make a new, empty pipe.
   * @param {number} [capacity] bytes it holds before a write waits
   * @returns {StdinPipe}
   */
  static create(capacity = DEFAULT_STDIN_CAPACITY) {
    // a power of two, so that positions stay continuous when the counters wrap
    let bytes = 1;
    while (bytes < capacity) bytes *= 2;
    return new StdinPipe(new SharedArrayBuffer(HEADER_BYTES + bytes));
  }

  /**
   * Attach to a pipe's memory (the other side's `sab`).
   * @param {SharedArrayBuffer} sab
   */
  constructor(sab) {
    this.sab = sab;
    this.i32 = new Int32Array(sab, 0, HEADER_BYTES / 4);
    this.data = new Uint8Array(sab, HEADER_BYTES);
    this.capacity = this.data.length;
  }

  /** Bytes written and not yet read. */
  available() {
    return (Atomics.load(this.i32, WRITTEN) - Atomics.load(this.i32, READ)) >>> 0;
  }

  /** Whether the writer has closed the pipe (end of file once drained). */
  closed() {
    return Atomics.load(this.i32, CLOSED) !== 0;
  }

  /**
   * Write as many bytes as fit (writer side).
   * @param {Uint8Array} bytes
   * @returns {number} bytes written (0 when full)
   * @throws {Error} when the pipe is closed
   */
  write(bytes) {
    if (this.closed()) throw new Error('standard input is closed');
    const written = Atomics.load(this.i32, WRITTEN);
    const n = Math.min(bytes.length, this.capacity - this.available());
    const start = (written >>> 0) % this.capacity;
    const first = Math.min(n, this.capacity - start);
    this.data.set(bytes.subarray(0, first), start);
    this.data.set(bytes.subarray(first, n), 0);
    Atomics.store(this.i32, WRITTEN, (written + n) | 0);
    Atomics.notify(this.i32, WRITTEN);
    return n;
  }

  /** Close the pipe (writer side): the reader gets end of file once it drained it. */
  close() {
    Atomics.store(this.i32, CLOSED, 1);
    Atomics.notify(this.i32, WRITTEN);
  }

  /**
   * Take up to `length` bytes without blocking (reader side).
   * @param {Uint8Array} buffer
   * @param {number} offset
   * @param {number} length
   * @returns {number} bytes taken; 0 at end of file; -1 when empty but still open
   */
  take(buffer, offset, length) {
    if (length <= 0) return 0; // readv() asks for empty parts too
    // closed is read first: whatever was written before the close is then visible
    const closed = this.closed();
    const read = Atomics.load(this.i32, READ);
    const n = Math.min(length, this.available());
    if (n === 0) return closed ? 0 : -1;
    const start = (read >>> 0) % this.capacity;
    const first = Math.min(n, this.capacity - start);
    buffer.set(this.data.subarray(start, start + first), offset);
    buffer.set(this.data.subarray(0, n - first), offset + first);
    Atomics.store(this.i32, READ, (read + n) | 0);
    Atomics.notify(this.i32, READ);
    return n;
  }

  /** The read counter (reader side moves it), for a writer that waits for room. */
  readCount() {
    return Atomics.load(this.i32, READ);
  }

  /** Index of the read counter in `i32`, for Atomics.waitAsync. */
  static get READ_INDEX() {
    return READ;
  }
}
