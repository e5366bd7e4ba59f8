// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// What every display of the 3D view shares: a group under the fixed frame,
// shown or hidden, placed by TF at each frame, and a status line with rviz's
// errors ("No transform from [base_link] to [map]"). Displays that read a
// topic hold a TopicFeed.

import * as THREE from 'three';
import { TopicFeed } from './topic_feed.mjs';

/** A colour from '#rrggbb', [r, g, b] (0-1) or 'r; g; b' (0-255, as .rviz files write it). */
export function parseColor(value, fallback = '#ffffff') {
  if (Array.isArray(value)) return new THREE.Color(value[0], value[1], value[2]);
  if (typeof value === 'string' && /^\s*\d+\s*;\s*\d+\s*;\s*\d+\s*$/.test(value)) {
    const [r, g, b] = value.split(';').map((x) => Number(x) / 255);
    return new THREE.Color(r, g, b);
  }
  try { return new THREE.Color(value || fallback); } catch { return new THREE.Color(fallback); }
}

/** Set an Object3D's pose from {t, q}. */
export function applyPose(object, pose) {
  object.position.set(pose.t[0], pose.t[1], pose.t[2]);
  object.quaternion.set(pose.q[0], pose.q[1], pose.q[2], pose.q[3]);
}

export class Display {
  /**
   * @param ctx {THREE, root, tf, session, requestRender, fixedFrame()} of the view
   * @param options {name, topic, color, size, visible}
   */
  constructor(ctx, options = {}) {
    this.ctx = ctx;
    this.name = options.name || this.constructor.kind;
    this.topic = options.topic || this.constructor.defaultTopic || null;
    this.color = options.color || this.constructor.defaultColor || '#ffffff';
    this.size = Number(options.size || this.constructor.defaultSize || 0.05);
    this.visible = options.visible !== false;
    this.group = new THREE.Group();
    this.group.visible = this.visible;
    ctx.root.add(this.group);
    this.feed = null;
    this.frameError = null;
  }

  /** The setting fields the display list shows: topic, colour, size. */
  get settings() { return ['topic', 'color', 'size']; }

  /** Subscribe to the display's topic (again, after a change of it). */
  listen(type) {
    if (this.feed) this.feed.close();
    this.feed = this.topic ? new TopicFeed(this.ctx.session, this.topic, type, (values) => {
      this.onMessages(values);
      this.ctx.requestRender();
    }) : null;
  }

  /** Decoded messages of the topic, oldest first. */
  onMessages() {}

  /** Apply a changed setting. */
  set(field, value) {
    if (field === 'size') this.size = Number(value);
    else this[field] = value;
    if (field === 'topic') this.listen(this.constructor.types);
    this.refresh();
    this.ctx.requestRender();
  }

  /** Rebuild what depends on colour and size (displays override it). */
  refresh() {}

  setVisible(visible) {
    this.visible = visible;
    this.group.visible = visible;
    this.ctx.requestRender();
  }

  /** Place an object at a frame of the fixed frame's tree; false (and frameError) if there is none. */
  place(object, frameId) {
    const found = this.ctx.tf.lookup(this.ctx.fixedFrame(), frameId);
    if (found.error) {
      this.frameError = found.error;
      object.visible = false;
      return false;
    }
    object.visible = true;
    applyPose(object, found.pose);
    return true;
  }

  /** Called before each frame is drawn: place the objects by TF. */
  update() {}

  /** {level: ok|warn|error, text}: a transform error first, then the topic's. */
  status() {
    if (this.frameError) return { level: 'error', text: this.frameError };
    if (this.feed) return this.feed.status();
    return { level: 'ok', text: 'OK' };
  }

  dispose() {
    if (this.feed) this.feed.close();
    this.ctx.root.remove(this.group);
    this.group.traverse((o) => {
      if (o.geometry) o.geometry.dispose();
      if (o.material) [].concat(o.material).forEach((m) => m.dispose());
    });
  }
}
