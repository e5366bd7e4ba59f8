// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// rviz's navigation displays: Map (nav_msgs/OccupancyGrid as a texture on
// the ground), Path (a line), Odometry (arrows, the last `keep`),
// Pose (geometry_msgs/PoseStamped) and PoseArray (arrows).

import * as THREE from 'three';
import { Display, applyPose, parseColor } from '../display.mjs';
import { poseOf } from '../tf_buffer.mjs';

function arrow(color, length) {
  return new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(0, 0, 0), length,
    parseColor(color), length * 0.3, length * 0.15);
}

/** RGBA bytes of an occupancy grid with rviz's "map" colour scheme. */
export function occupancyColors(data) {
  const out = new Uint8Array(data.length * 4);
  for (let i = 0; i < data.length; i++) {
    const v = data[i];
    let c;
    if (v < 0 || v > 100) c = [112, 137, 134];
    else { const g = Math.round(255 - v * 2.55); c = [g, g, g]; }
    out[i * 4] = c[0]; out[i * 4 + 1] = c[1]; out[i * 4 + 2] = c[2]; out[i * 4 + 3] = 255;
  }
  return out;
}

class FramedDisplay extends Display {
  constructor(ctx, options) {
    super(ctx, options);
    this.frame = new THREE.Group();
    this.group.add(this.frame);
    this.frameId = null;
    this.listen(this.constructor.types);
  }

  update() {
    this.frameError = null;
    if (this.frameId !== null) this.place(this.frame, this.frameId);
  }

  /** Replace what is drawn by one arrow per pose, in a frame. */
  showArrows(frameId, poses) {
    this.clear();
    this.frameId = frameId;
    for (const p of poses) {
      const a = arrow(this.color, this.size);
      applyPose(a, poseOf(p));
      this.frame.add(a);
    }
  }

  clear() {
    for (const c of [...this.frame.children]) {
      this.frame.remove(c);
      c.traverse((o) => { if (o.geometry) o.geometry.dispose(); if (o.material && o.material.map) o.material.map.dispose(); });
    }
  }
}

export class MapDisplay extends FramedDisplay {
  static kind = 'Map';
  static defaultTopic = '/map';
  static types = ['nav_msgs/msg/OccupancyGrid'];

  get settings() { return ['topic']; }

  onMessages(values) {
    const grid = values[values.length - 1];
    const { width, height, resolution } = grid.info;
    this.clear();
    this.frameId = grid.header.frame_id;
    if (!width || !height || width * height !== grid.data.length) {
      this.mapError = `the map is ${width}x${height} cells but has ${grid.data.length} values`;
      return;
    }
    this.mapError = null;
    const texture = new THREE.DataTexture(occupancyColors(grid.data), width, height, THREE.RGBAFormat);
    texture.magFilter = THREE.NearestFilter;
    texture.needsUpdate = true;
    const geometry = new THREE.PlaneGeometry(width * resolution, height * resolution);
    geometry.translate(width * resolution / 2, height * resolution / 2, 0);
    const plane = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ map: texture, side: THREE.DoubleSide, transparent: true, opacity: 0.85 }));
    const origin = new THREE.Group();
    applyPose(origin, poseOf(grid.info.origin));
    origin.add(plane);
    this.frame.add(origin);
    this.cells = `${width}x${height} at ${resolution} m`;
  }

  status() {
    if (this.mapError) return { level: 'error', text: this.mapError };
    const s = super.status();
    return s.level === 'ok' ? { level: 'ok', text: `map ${this.cells}` } : s;
  }
}

export class PathDisplay extends FramedDisplay {
  static kind = 'Path';
  static defaultTopic = '/plan';
  static defaultColor = '#19ff00';
  static types = ['nav_msgs/msg/Path'];

  get settings() { return ['topic', 'color']; }

  onMessages(values) {
    const path = values[values.length - 1];
    this.clear();
    this.frameId = path.header.frame_id;
    const points = new Float32Array(path.poses.length * 3);
    path.poses.forEach((p, i) => { const q = p.pose.position; points[i * 3] = q.x; points[i * 3 + 1] = q.y; points[i * 3 + 2] = q.z; });
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(points, 3));
    this.frame.add(new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: parseColor(this.color) })));
  }
}

export class PoseDisplay extends FramedDisplay {
  static kind = 'Pose';
  static defaultTopic = '/goal_pose';
  static defaultColor = '#ff1900';
  static defaultSize = 1;
  static types = ['geometry_msgs/msg/PoseStamped'];

  onMessages(values) {
    const msg = values[values.length - 1];
    this.showArrows(msg.header.frame_id, [msg.pose]);
  }
}

export class PoseArrayDisplay extends FramedDisplay {
  static kind = 'PoseArray';
  static defaultTopic = '/particlecloud';
  static defaultColor = '#ff1900';
  static defaultSize = 0.3;
  static types = ['geometry_msgs/msg/PoseArray'];

  onMessages(values) {
    const msg = values[values.length - 1];
    this.showArrows(msg.header.frame_id, msg.poses);
  }
}

export class OdometryDisplay extends FramedDisplay {
  static kind = 'Odometry';
  static defaultTopic = '/odom';
  static defaultColor = '#ff1900';
  static defaultSize = 0.5;
  static types = ['nav_msgs/msg/Odometry'];

  constructor(ctx, options) {
    super(ctx, options);
    this.keep = Number(options.keep || 100);
  }

  onMessages(values) {
    for (const msg of values) {
      this.frameId = msg.header.frame_id;
      const a = arrow(this.color, this.size);
      applyPose(a, poseOf(msg.pose.pose));
      this.frame.add(a);
      while (this.frame.children.length > this.keep) this.frame.remove(this.frame.children[0]);
    }
  }
}
