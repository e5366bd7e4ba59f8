// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// rviz's TF display: every frame of the fixed frame's tree drawn as axes
// (x red, y green, z blue), with a line to its parent.

import * as THREE from 'three';
import { Display, applyPose } from '../display.mjs';

export class TfDisplay extends Display {
  static kind = 'TF';
  static defaultSize = 0.3;

  constructor(ctx, options) {
    super(ctx, options);
    this.axes = new Map();
    this.links = new THREE.LineSegments(new THREE.BufferGeometry(),
      new THREE.LineBasicMaterial({ color: 0xf0d040 }));
    this.group.add(this.links);
  }

  get settings() { return ['size']; }

  refresh() {
    for (const a of this.axes.values()) { this.group.remove(a); a.geometry.dispose(); }
    this.axes.clear();
  }

  update() {
    const { tf } = this.ctx;
    const fixed = this.ctx.fixedFrame();
    const points = [];
    let unconnected = 0;
    for (const frame of tf.frameIds()) {
      let axes = this.axes.get(frame);
      if (!axes) {
        axes = new THREE.AxesHelper(this.size);
        axes.name = frame;
        this.axes.set(frame, axes);
        this.group.add(axes);
      }
      const found = tf.lookup(fixed, frame);
      axes.visible = !found.error;
      if (found.error) { unconnected++; continue; }
      applyPose(axes, found.pose);
      const entry = tf.frames.get(frame);
      const parent = entry && tf.lookup(fixed, entry.parent);
      if (parent && !parent.error) points.push(...found.pose.t, ...parent.pose.t);
    }
    this.links.geometry.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
    this.frameCount = this.axes.size;
    this.unconnected = unconnected;
  }

  status() {
    if (!this.frameCount) return { level: 'warn', text: 'No transforms on /tf or /tf_static' };
    if (this.unconnected) return { level: 'warn', text: `${this.unconnected} of ${this.frameCount} frames have no transform to ${this.ctx.fixedFrame()}` };
    return { level: 'ok', text: `${this.frameCount} frames` };
  }
}
