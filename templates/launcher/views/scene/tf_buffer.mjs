// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The 3D view's TF buffer: the latest transform of every frame from /tf and
// /tf_static (tf2_msgs/TFMessage), lookups between any two frames of one
// tree, and the tree as a list with each transform's age — what rviz's TF
// display and fixed frame use. Plain JS, no three.js: poses are
// {t: [x, y, z], q: [x, y, z, w]}.

/** The identity pose. */
export const IDENTITY = Object.freeze({ t: [0, 0, 0], q: [0, 0, 0, 1] });

/** A frame id as tf2 keys it (no leading slash). */
export function frameKey(id) {
  return String(id || '').replace(/^\/+/, '');
}

function qmul(a, b) {
  return [
    a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
    a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
    a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
    a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2],
  ];
}

function rotate(q, v) {
  const p = qmul(qmul(q, [v[0], v[1], v[2], 0]), [-q[0], -q[1], -q[2], q[3]]);
  return [p[0], p[1], p[2]];
}

/** Normalize a quaternion; a zero one (an unset rotation) is the identity. */
export function normalizeQuaternion(q) {
  const n = Math.hypot(q[0], q[1], q[2], q[3]);
  return n > 1e-12 ? [q[0] / n, q[1] / n, q[2] / n, q[3] / n] : [0, 0, 0, 1];
}

/** a ∘ b: the pose b expressed in a's parent frame. */
export function compose(a, b) {
  const t = rotate(a.q, b.t);
  return { t: [a.t[0] + t[0], a.t[1] + t[1], a.t[2] + t[2]], q: normalizeQuaternion(qmul(a.q, b.q)) };
}

/** The inverse pose. */
export function invert(a) {
  const q = [-a.q[0], -a.q[1], -a.q[2], a.q[3]];
  const t = rotate(q, a.t);
  return { t: [-t[0], -t[1], -t[2]], q };
}

/** A geometry_msgs Pose or Transform as {t, q}. */
export function poseOf(msg) {
  const p = msg.position || msg.translation || { x: 0, y: 0, z: 0 };
  const o = msg.orientation || msg.rotation || { x: 0, y: 0, z: 0, w: 1 };
  return { t: [p.x, p.y, p.z], q: normalizeQuaternion([o.x, o.y, o.z, o.w]) };
}

export class TfBuffer {
  constructor(now = () => performance.now()) {
    this.now = now;
    // child frame -> {parent, pose, stamp, received, isStatic}
    this.frames = new Map();
    this.version = 0;
  }

  /** Add the transforms of one tf2_msgs/TFMessage. */
  add(message, isStatic) {
    const received = this.now();
    for (const tr of message.transforms || []) {
      const child = frameKey(tr.child_frame_id);
      const parent = frameKey(tr.header.frame_id);
      if (!child || !parent || child === parent) continue;
      const stamp = tr.header.stamp ? tr.header.stamp.sec + tr.header.stamp.nanosec * 1e-9 : 0;
      this.frames.set(child, { parent, pose: poseOf(tr.transform), stamp, received, isStatic });
    }
    this.version++;
  }

  /** Every frame the buffer knows, parents and children, sorted. */
  frameIds() {
    const ids = new Set();
    for (const [child, entry] of this.frames) { ids.add(child); ids.add(entry.parent); }
    return [...ids].sort();
  }

  /** The chain of a frame up to its root: [{frame, pose}] (pose: frame in its parent). */
  chain(frame) {
    const out = [];
    const seen = new Set();
    let current = frameKey(frame);
    while (this.frames.has(current) && !seen.has(current)) {
      seen.add(current);
      const entry = this.frames.get(current);
      out.push({ frame: current, pose: entry.pose, parent: entry.parent });
      current = entry.parent;
    }
    return { links: out, root: current };
  }

  /**
   * The pose of `source` in `target`: {pose} or {error} with rviz's wording.
   */
  lookup(target, source) {
    target = frameKey(target);
    source = frameKey(source);
    if (target === source) return { pose: IDENTITY };
    const up = this.chain(source);
    const down = this.chain(target);
    if (up.root !== down.root) {
      return { error: `No transform from [${source}] to [${target}]` };
    }
    // pose of each in the common root, then target⁻¹ ∘ source
    const inRoot = (c) => c.links.reduceRight((acc, l) => compose(acc, l.pose), IDENTITY);
    return { pose: compose(invert(inRoot(down)), inRoot(up)) };
  }

  /** Whether a frame is known (as a child or a parent). */
  has(frame) {
    const key = frameKey(frame);
    if (this.frames.has(key)) return true;
    for (const entry of this.frames.values()) if (entry.parent === key) return true;
    return false;
  }

  /** The tree as rows {frame, parent, depth, age (s), isStatic}, depth-first from the roots. */
  tree() {
    const children = new Map();
    for (const [child, entry] of this.frames) {
      if (!children.has(entry.parent)) children.set(entry.parent, []);
      children.get(entry.parent).push(child);
    }
    const roots = [...children.keys()].filter((p) => !this.frames.has(p)).sort();
    const rows = [];
    const now = this.now();
    const visit = (frame, depth, seen) => {
      if (seen.has(frame)) return;
      seen.add(frame);
      const entry = this.frames.get(frame);
      rows.push({ frame, parent: entry ? entry.parent : null, depth,
        age: entry ? (now - entry.received) / 1000 : null, isStatic: entry ? entry.isStatic : false });
      for (const c of (children.get(frame) || []).sort()) visit(c, depth + 1, seen);
    };
    const seen = new Set();
    for (const root of roots) visit(root, 0, seen);
    return rows;
  }
}
