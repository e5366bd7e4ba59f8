// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// rviz's "2D Pose Estimate" and "2D Goal Pose" tools: press on the ground
// where the robot is (or should go), drag towards where it faces, release.
// They publish geometry_msgs/PoseWithCovarianceStamped on /initialpose and
// geometry_msgs/PoseStamped on /goal_pose, in the fixed frame, with rviz's
// covariance (0.25 m² in x and y, (π/12)² in yaw).

export const POSE_TOOLS = [
  { id: 'initialpose', label: '2D Pose Estimate', topic: '/initialpose', type: 'geometry_msgs/msg/PoseWithCovarianceStamped',
    help: 'press where the robot is, drag the way it faces: publishes /initialpose' },
  { id: 'goal', label: '2D Goal Pose', topic: '/goal_pose', type: 'geometry_msgs/msg/PoseStamped',
    help: 'press where the robot should go, drag the way it should face: publishes /goal_pose' },
];

/** The message a tool publishes for a pose on the ground (x, y, yaw) in a frame. */
export function poseMessage(tool, registry, frameId, x, y, yaw, nowMs = Date.now()) {
  const value = registry.create(tool.type);
  const header = { stamp: { sec: Math.floor(nowMs / 1000), nanosec: (nowMs % 1000) * 1e6 }, frame_id: frameId };
  const pose = { position: { x, y, z: 0 }, orientation: { x: 0, y: 0, z: Math.sin(yaw / 2), w: Math.cos(yaw / 2) } };
  value.header = header;
  if (tool.id === 'initialpose') {
    value.pose.pose = pose;
    const c = new Float64Array(36);
    c[0] = 0.25; c[7] = 0.25; c[35] = (Math.PI / 12) ** 2;
    value.pose.covariance = c;
  } else {
    value.pose = pose;
  }
  return value;
}

export class PoseTool {
  constructor(view, note) {
    this.view = view;
    this.note = note;
    this.tool = null;
    this.start = null;
    this.publishers = new Map();
    const canvas = view.scene.canvas;
    canvas.addEventListener('pointerdown', (e) => this.down(e));
    canvas.addEventListener('pointerup', (e) => this.up(e));
  }

  arm(tool) {
    if (this.tool === tool) { this.disarm(); return; }
    if (!this.view.session.registry.has(tool.type)) {
      this.note(`${tool.label}: the install space has no description of ${tool.type} (build geometry_msgs)`);
      return;
    }
    this.tool = tool;
    this.view.scene.controls.enabled = false;
    this.note(`${tool.label}: ${tool.help}`);
  }

  disarm() {
    this.tool = null;
    this.start = null;
    this.view.scene.controls.enabled = true;
  }

  down(e) {
    if (!this.tool) return;
    this.start = this.view.scene.groundPoint(e.clientX, e.clientY);
  }

  async up(e) {
    if (!this.tool || !this.start) return;
    const end = this.view.scene.groundPoint(e.clientX, e.clientY) || this.start;
    const tool = this.tool;
    const [x, y] = this.start;
    const yaw = Math.atan2(end[1] - y, end[0] - x);
    this.disarm();
    for (const b of this.view.toolbar.querySelectorAll('[data-tool]')) b.classList.remove('active');
    const { session } = this.view;
    if (!this.publishers.has(tool.id)) this.publishers.set(tool.id, session.publisher(tool.topic, tool.type));
    const value = poseMessage(tool, session.registry, this.view.fixedFrame, x, y, yaw);
    try {
      await this.publishers.get(tool.id).publish(session.registry.encode(tool.type, value));
      this.note(`${tool.label}: published on ${tool.topic}: x ${x.toFixed(2)}, y ${y.toFixed(2)}, yaw ${yaw.toFixed(2)} in ${this.view.fixedFrame}`);
    } catch (err) {
      this.note(`${tool.label}: publishing on ${tool.topic} failed: ${err.message}`);
    }
  }
}
