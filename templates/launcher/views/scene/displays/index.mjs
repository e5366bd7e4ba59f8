// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The displays of the 3D view, by kind (the names rviz gives them).

import { TfDisplay } from './tf_display.mjs';
import { RobotModelDisplay } from './robot_model_display.mjs';
import { LaserScanDisplay, PointCloud2Display } from './points_display.mjs';
import { MarkerDisplay } from './marker_display.mjs';
import { MapDisplay, OdometryDisplay, PathDisplay, PoseArrayDisplay, PoseDisplay } from './nav_displays.mjs';

export const DISPLAYS = Object.fromEntries([
  TfDisplay, RobotModelDisplay, LaserScanDisplay, PointCloud2Display, MarkerDisplay,
  MapDisplay, PathDisplay, OdometryDisplay, PoseDisplay, PoseArrayDisplay,
].map((cls) => [cls.kind, cls]));
