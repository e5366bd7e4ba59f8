// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// rviz's PointCloud2 and LaserScan displays: the latest message's points
// (point_fields.mjs) as one three.js Points object in the message's frame,
// its buffers reused while the point count fits.

import * as THREE from 'three';
import { Display, parseColor } from '../display.mjs';
import { decodeCloud, decodeScan } from '../point_fields.mjs';

class PointsDisplay extends Display {
  static defaultSize = 0.03;

  constructor(ctx, options) {
    super(ctx, options);
    this.colorMode = options.colorMode || this.constructor.defaultMode;
    this.geometry = new THREE.BufferGeometry();
    this.material = new THREE.PointsMaterial({ size: this.size, vertexColors: true, sizeAttenuation: true });
    this.points = new THREE.Points(this.geometry, this.material);
    this.points.frustumCulled = false;
    this.group.add(this.points);
    this.frameId = null;
    this.decodeError = null;
    this.count = 0;
    this.listen(this.constructor.types);
  }

  get settings() { return ['topic', 'color', 'size', 'colorMode']; }

  refresh() {
    this.material.size = this.size;
    if (this.last) this.show(this.last);
  }

  onMessages(values) {
    // like rviz with a queue of one: draw the newest
    this.last = values[values.length - 1];
    this.show(this.last);
  }

  show(message) {
    const flat = parseColor(this.color).toArray();
    const decoded = this.decode(message, flat);
    this.decodeError = decoded.error || null;
    this.frameId = message.header.frame_id;
    this.count = decoded.count;
    let colors = decoded.colors;
    if (!colors || this.colorMode === 'FlatColor') {
      colors = new Float32Array(decoded.count * 3);
      for (let i = 0; i < decoded.count * 3; i += 3) colors.set(flat, i);
    }
    const position = this.geometry.getAttribute('position');
    if (position && position.array.length >= decoded.positions.length) {
      position.array.set(decoded.positions);
      this.geometry.getAttribute('color').array.set(colors.subarray(0, decoded.count * 3));
      position.needsUpdate = true;
      this.geometry.getAttribute('color').needsUpdate = true;
    } else {
      this.geometry.setAttribute('position', new THREE.BufferAttribute(decoded.positions, 3));
      this.geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3));
    }
    this.geometry.setDrawRange(0, decoded.count);
  }

  update() {
    this.frameError = null;
    if (this.frameId !== null) this.place(this.points, this.frameId);
  }

  status() {
    if (this.decodeError) return { level: 'error', text: this.decodeError };
    const s = super.status();
    return s.level === 'ok' ? { level: 'ok', text: `${this.count} points` } : s;
  }
}

export class PointCloud2Display extends PointsDisplay {
  static kind = 'PointCloud2';
  static defaultTopic = '/points';
  static defaultMode = 'RGB8';
  static types = ['sensor_msgs/msg/PointCloud2'];

  decode(cloud, flat) {
    return decodeCloud(cloud, { mode: this.colorMode, flat });
  }
}

export class LaserScanDisplay extends PointsDisplay {
  static kind = 'LaserScan';
  static defaultTopic = '/scan';
  static defaultMode = 'Intensity';
  static defaultColor = '#ff3030';
  static types = ['sensor_msgs/msg/LaserScan'];

  decode(scan) {
    return decodeScan(scan, { byIntensity: this.colorMode === 'Intensity' });
  }
}
