// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * QoS events: deadlines, liveliness, lost messages and incompatible QoS,
 * counted on the endpoint record under its event lock and computed lazily
 * when a wait or a take asks.
 *
 * Each function takes the thread's BusClient `c` first (bus_client.mjs is
 * the face callers use).
 *
 * @module client/events
 */

import { ENDPOINT, KIND_PUBLISHER, KIND_SUBSCRIPTION, LINK, QOS, REC_ALIVE } from '../layout.mjs';
import { EventType } from '../abi/bus_abi.mjs';
import { BusError, Code, now } from '../bus.mjs';
import { lock, unlock } from '../bus/lock.mjs';
import { Liveliness } from '../qos.mjs';
import { readerLinks, refresh } from './links.mjs';
import { checkEndpoint, KIND_NAMES } from './registry.mjs';

/** Advance the deadline accounting of endpoint record b; returns the next expiry. */
export function accountDeadline(c, b, base) {
  const bus = c.bus;
  const i32 = bus.i32;
  const f64 = bus.f64;
  const period = f64[(b + ENDPOINT.DEADLINE_MS_F64) >> 1];
  if (period === Infinity || base <= 0) return Infinity;
  if (f64[(b + ENDPOINT.DEADLINE_ACCT_BASE_F64) >> 1] !== base) {
    f64[(b + ENDPOINT.DEADLINE_ACCT_BASE_F64) >> 1] = base;
    i32[b + ENDPOINT.DEADLINE_ACCT_N] = 0;
  }
  const k = Math.floor((now() - base) / period);
  const counted = i32[b + ENDPOINT.DEADLINE_ACCT_N];
  if (k > counted) {
    i32[b + ENDPOINT.DEADLINE_TOTAL] += k - counted;
    i32[b + ENDPOINT.DEADLINE_ACCT_N] = k;
  }
  return base + (Math.max(k, counted) + 1) * period;
}

/** Liveliness of the writers matched to reader ep: [alive, notAlive, nextExpiry]. */
export function liveliness(c, ep) {
  const bus = c.bus;
  const i32 = bus.i32;
  const f64 = bus.f64;
  const links = readerLinks(c, ep);
  let alive = 0;
  let notAlive = 0;
  let next = Infinity;
  const t = now();
  for (let i = 0; i < links.length; i++) {
    const lb = bus.link(links[i]);
    if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
    const wb = bus.ep(i32[lb + LINK.WRITER]);
    if (Atomics.load(i32, wb + ENDPOINT.STATE) !== REC_ALIVE || !bus.processAlive(i32[wb + ENDPOINT.PID])) continue;
    const lease = f64[(wb + ENDPOINT.LEASE_MS_F64) >> 1];
    if (i32[wb + ENDPOINT.QOS + QOS.LIVELINESS] === Liveliness.MANUAL_BY_TOPIC && lease !== Infinity) {
      const until = f64[(wb + ENDPOINT.LAST_ASSERT_F64) >> 1] + lease;
      if (t <= until) {
        alive++;
        next = Math.min(next, until);
      } else notAlive++;
    } else alive++;
  }
  return [alive, notAlive, next];
}

/**
 * Compute (and with `take`, consume) the status of one event of endpoint ep.
 * @param {number} ep
 * @param {number} type EventType
 * @param {boolean} take reset the "change" fields
 * @returns {{changed: boolean, total: number, change: number, alive: number, notAlive: number,
 *            aliveChange: number, notAliveChange: number, policy: number, next: number}}
 */
export function eventStatus(c, ep, type, take) {
  const bus = c.bus;
  const b = checkEndpoint(c, ep, 0, 'event');
  const i32 = bus.i32;
  const f64 = bus.f64;
  const kind = i32[b + ENDPOINT.KIND];
  const isWriter = kind === KIND_PUBLISHER;
  const isReader = kind === KIND_SUBSCRIPTION;
  const ok = isReader ? type <= 3 : (isWriter && type >= 4 && type <= 6);
  if (!ok) {
    throw new BusError(Code.INVALID_ARGUMENT, `event type ${type} does not apply to a ${KIND_NAMES[kind]}`);
  }
  refresh(c);
  const r = {
    changed: false, total: 0, change: 0, alive: 0, notAlive: 0, aliveChange: 0, notAliveChange: 0,
    policy: 0, next: Infinity,
  };
  lock(c.bus.i32, b + ENDPOINT.EVLOCK, c.pid);
  try {
    if (bus.faultPoint !== null) bus.faultPoint('event.locked');
    let totalW = 0;
    let seenW = 0;
    switch (type) {
      case EventType.REQUESTED_QOS_INCOMPATIBLE:
      case EventType.OFFERED_QOS_INCOMPATIBLE:
        totalW = ENDPOINT.INCOMPAT_TOTAL; seenW = ENDPOINT.INCOMPAT_SEEN;
        break;
      case EventType.MESSAGE_LOST:
        totalW = ENDPOINT.LOST_TOTAL; seenW = ENDPOINT.LOST_SEEN;
        break;
      case EventType.OFFERED_DEADLINE_MISSED:
        r.next = accountDeadline(c, b, f64[(b + ENDPOINT.LAST_PUB_F64) >> 1] * (i32[b + ENDPOINT.HEAD] !== 0 || i32[b + ENDPOINT.HEAD_HI] !== 0 ? 1 : 0));
        totalW = ENDPOINT.DEADLINE_TOTAL; seenW = ENDPOINT.DEADLINE_SEEN;
        break;
      case EventType.REQUESTED_DEADLINE_MISSED: {
        let base = 0;
        const links = readerLinks(c, ep);
        for (let i = 0; i < links.length; i++) {
          const lb = bus.link(links[i]);
          if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
          const wb = bus.ep(i32[lb + LINK.WRITER]);
          if (i32[wb + ENDPOINT.HEAD] === 0 && i32[wb + ENDPOINT.HEAD_HI] === 0) continue;
          base = Math.max(base, f64[(wb + ENDPOINT.LAST_PUB_F64) >> 1]);
        }
        r.next = accountDeadline(c, b, base);
        totalW = ENDPOINT.DEADLINE_TOTAL; seenW = ENDPOINT.DEADLINE_SEEN;
        break;
      }
      case EventType.LIVELINESS_LOST: {
        const lease = f64[(b + ENDPOINT.LEASE_MS_F64) >> 1];
        if (i32[b + ENDPOINT.QOS + QOS.LIVELINESS] === Liveliness.MANUAL_BY_TOPIC && lease !== Infinity) {
          const base = f64[(b + ENDPOINT.LAST_ASSERT_F64) >> 1];
          if (now() > base + lease) {
            if (f64[(b + ENDPOINT.LIVE_LOST_BASE_F64) >> 1] !== base) {
              f64[(b + ENDPOINT.LIVE_LOST_BASE_F64) >> 1] = base;
              i32[b + ENDPOINT.LIVE_LOST_TOTAL] += 1;
            }
          } else r.next = base + lease;
        }
        totalW = ENDPOINT.LIVE_LOST_TOTAL; seenW = ENDPOINT.LIVE_LOST_SEEN;
        break;
      }
      case EventType.LIVELINESS_CHANGED: {
        const [alive, notAlive, next] = liveliness(c, ep);
        r.alive = alive;
        r.notAlive = notAlive;
        r.next = next;
        r.aliveChange = alive - i32[b + ENDPOINT.ALIVE_SEEN];
        r.notAliveChange = notAlive - i32[b + ENDPOINT.NOT_ALIVE_SEEN];
        r.changed = r.aliveChange !== 0 || r.notAliveChange !== 0;
        if (take) {
          i32[b + ENDPOINT.ALIVE_SEEN] = alive;
          i32[b + ENDPOINT.NOT_ALIVE_SEEN] = notAlive;
        }
        return r;
      }
      default:
        throw new BusError(Code.INVALID_ARGUMENT, `unknown event type ${type}`);
    }
    r.total = Atomics.load(i32, b + totalW);
    // After the total: matching stores the policy before it counts, so a
    // total that counts an incompatibility always comes with its policy.
    if (totalW === ENDPOINT.INCOMPAT_TOTAL) r.policy = Atomics.load(i32, b + ENDPOINT.INCOMPAT_POLICY);
    r.change = r.total - i32[b + seenW];
    r.changed = r.change !== 0;
    if (take) i32[b + seenW] = r.total;
    return r;
  } finally {
    unlock(c.bus.i32, b + ENDPOINT.EVLOCK, c.pid);
  }
}
