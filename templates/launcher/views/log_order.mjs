// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The order of the log dock's "all output" view: the lines of every process
// merged by the time they were logged. Lines reach the page in batches, one
// worker after another, so the order they arrive in is not the order they
// were printed in. A ROS log line carries its time ("[INFO] [1712.345678]
// [talker]: ..."); a line without one (a plain print, the page's own lines)
// takes the time it reached the page. One process' lines keep their order.
// No DOM here: tests/js/test_page_tools.mjs tests it under Node.js.

const STAMP = /^\s*\[[A-Z]+\]\s*\[(\d+(?:\.\d+)?)\]/;
/** A stamp further than this before the line reached the page is not trusted. */
const MAX_DELAY_MS = 10000;

/**
 * When a log entry ({text, time}: time is performance.now() when it reached
 * the page) was logged, in ms since the epoch.
 * @param {{text: string, time: number}} entry
 * @param {number} [origin] performance.timeOrigin
 * @returns {number}
 */
export function logStamp(entry, origin = performance.timeOrigin) {
  const arrived = origin + entry.time;
  const m = STAMP.exec(entry.text);
  if (!m) return arrived;
  const stamped = Number(m[1]) * 1000;
  // a stamp of another clock (sim time, a wrong clock) would misplace the line
  return stamped <= arrived + 1000 && stamped >= arrived - MAX_DELAY_MS ? stamped : arrived;
}

/**
 * The entries of several processes in one list by their stamp, each process'
 * own entries in their order (a merge, stable: equal stamps keep `seq` order).
 * @param {Array<Array<object>>} lists of entries, each in its process' order
 * @param {function(object): number} stampOf
 * @param {function(object): number} [seqOf] the order the entries reached the page
 * @returns {Array<object>}
 */
export function mergeByStamp(lists, stampOf, seqOf = (item) => item.seq) {
  const heads = lists.filter((l) => l.length).map((list) => ({ list, at: 0, stamp: stampOf(list[0]) }));
  const out = [];
  while (heads.length) {
    let best = 0;
    for (let i = 1; i < heads.length; i++) {
      const a = heads[i];
      const b = heads[best];
      if (a.stamp < b.stamp || (a.stamp === b.stamp && seqOf(a.list[a.at]) < seqOf(b.list[b.at]))) best = i;
    }
    const head = heads[best];
    out.push(head.list[head.at]);
    head.at += 1;
    if (head.at < head.list.length) head.stamp = stampOf(head.list[head.at]);
    else heads.splice(best, 1);
  }
  return out;
}

/**
 * Where a new line goes among the `count` shown ones (`lineAt(i)`: the stamp
 * and process of the i-th): after the last one logged at or before it, and
 * never before a line of its own process. Looks back `limit` lines at most.
 * @param {number} count
 * @param {function(number): {stamp: number, proc: *}} lineAt
 * @param {{stamp: number, proc: *}} line
 * @param {number} [limit]
 * @returns {number} the index to insert at (count: at the end)
 */
export function insertionIndex(count, lineAt, line, limit = 500) {
  let i = count;
  while (i > 0 && count - i < limit) {
    const before = lineAt(i - 1);
    if (!before || before.proc === line.proc || before.stamp <= line.stamp) break;
    i--;
  }
  return i;
}
