// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// rviz's RobotModel display: the URDF of /robot_description (what
// robot_state_publisher publishes, transient local) read by urdf-loader,
// each link's visuals placed by TF as rviz places them — so the robot moves
// with whatever publishes its transforms. Meshes come from the share
// folders (package://); a link without a transform, a mesh that does not
// load, a URDF that does not parse: each is said on the display.

import * as THREE from 'three';
import URDFLoader from 'urdf-loader';
import { Display } from '../display.mjs';
import { loadMeshUrl } from '../mesh_loader.mjs';
import { siteUrl } from '../../../site_url.mjs';

export class RobotModelDisplay extends Display {
  static kind = 'RobotModel';
  static defaultTopic = '/robot_description';
  static types = ['std_msgs/msg/String'];

  constructor(ctx, options) {
    super(ctx, options);
    this.alpha = options.alpha === undefined ? 1 : Number(options.alpha);
    this.links = new Map();
    this.meshErrors = [];
    this.parseError = null;
    this.description = null;
    this.loadedAt = null;
    this.listen(RobotModelDisplay.types);
  }

  get settings() { return ['topic']; }

  onMessages(values) {
    const text = values[values.length - 1].data;
    if (text === this.description) return;
    // for bench/page: from the description's arrival to the first frame drawn with every mesh
    this.receivedAt = performance.now();
    this.firstFrameAt = null;
    this.description = text;
    this.build(text);
  }

  build(text) {
    for (const frame of this.links.values()) this.group.remove(frame);
    this.links.clear();
    this.meshErrors = [];
    this.parseError = null;
    const loader = new URDFLoader();
    loader.packages = (pkg) => siteUrl(`package/${pkg}`);
    this.pendingMeshes = 0;
    loader.loadMeshCb = (url, manager, material, done) => {
      this.pendingMeshes++;
      loadMeshUrl(url, material).then((obj) => { this.pendingMeshes--; done(obj); this.ctx.requestRender(); },
        (e) => { this.pendingMeshes--; this.meshErrors.push(e.message); done(null, e); this.ctx.requestRender(); });
    };
    let robot;
    try {
      if (!/<robot[\s>]/.test(text)) throw new Error('the message is not a URDF (no <robot> element)');
      robot = loader.parse(text);
      if (!robot || !robot.links || Object.keys(robot.links).length === 0) throw new Error('the URDF has no link');
    } catch (e) {
      this.parseError = `the robot description does not parse: ${e.message}`;
      return;
    }
    this.robotName = robot.robotName || robot.name;
    // each link's visuals, out of urdf-loader's joint tree, into a frame TF places
    for (const [name, link] of Object.entries(robot.links)) {
      const frame = new THREE.Group();
      frame.name = name;
      for (const child of [...link.children]) {
        if (child.isURDFVisual) frame.add(child);
      }
      if (this.alpha < 1) {
        frame.traverse((o) => {
          if (o.material) { o.material.transparent = true; o.material.opacity = this.alpha; }
        });
      }
      this.links.set(name, frame);
      this.group.add(frame);
    }
    this.loadedAt = performance.now();
  }

  update() {
    this.frameError = null;
    const missing = [];
    for (const [name, frame] of this.links) {
      if (!this.place(frame, name)) missing.push(name);
    }
    this.missing = missing;
    this.frameError = null;
    if (this.links.size && !this.firstFrameAt && !this.pendingMeshes && !missing.length) {
      this.firstFrameAt = performance.now();
    }
  }

  status() {
    if (this.parseError) return { level: 'error', text: this.parseError };
    const feed = this.feed.status();
    if (!this.description) return feed.level === 'ok' ? { level: 'warn', text: 'waiting for the robot description' } : feed;
    if (this.missing && this.missing.length) {
      const fixed = this.ctx.fixedFrame();
      return { level: 'error', text: `No transform from [${this.missing[0]}] to [${fixed}]${this.missing.length > 1 ? ` (and ${this.missing.length - 1} more links)` : ''}` };
    }
    if (this.meshErrors.length) return { level: 'warn', text: this.meshErrors[0] };
    return { level: 'ok', text: `${this.robotName || 'robot'}: ${this.links.size} links` };
  }
}
