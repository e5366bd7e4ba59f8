// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Drives the launcher page's 3D tab as a ROS user would (tests/test_page_3d.py):
// robot_state_publisher runs with a URDF, an .rviz file is opened by hand,
// joint states, markers, a laser scan and a 100k-point cloud are published
// from the page, and the canvas' pixels are read where the robot and the
// markers must be. Debian's Chromium through playwright-core; WebGL is
// SwiftShader's. Prints one JSON line: {ok, error, checks, stats, logs, pageErrors}.
//
//   node page_3d.mjs '<json: {url, chromium, urdf, rviz, screenshots, userDataDir}>'

import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { launchChromiumProfile } from './chromium.mjs';

const options = JSON.parse(process.argv[2]);
const timeoutMs = options.timeoutMs || 90000;
const browser = await launchChromiumProfile(options.chromium, options.userDataDir,
  { viewport: { width: 1440, height: 900 } });
const pageErrors = [];
const checks = {};
const stats = {};
let error = null;
let page = null;

async function until(fn, arg, what, ms = timeoutMs) {
  try {
    return await page.waitForFunction(fn, arg, { timeout: ms, polling: 100 });
  } catch (e) {
    throw new Error(`timed out waiting for ${what}`);
  }
}

/** The RGB under ROS points (fixed frame) of the 3D view, after a fresh render. */
function colorsAt(points) {
  return page.evaluate((pts) => {
    const view = window.colconWasm.views['3d'];
    const { scene } = view;
    for (const d of view.displays) d.update();
    scene.renderer.render(scene.scene, scene.camera);
    const canvas = scene.canvas;
    const copy = document.createElement('canvas');
    copy.width = canvas.width; copy.height = canvas.height;
    const ctx = copy.getContext('2d');
    ctx.drawImage(canvas, 0, 0);
    return pts.map(([x, y, z]) => {
      const v = new scene.THREE.Vector3(x, z, -y).project(scene.camera);
      const px = Math.round((v.x + 1) / 2 * canvas.width);
      const py = Math.round((1 - v.y) / 2 * canvas.height);
      const d = ctx.getImageData(px, py, 1, 1).data;
      return { px, py, rgb: [d[0], d[1], d[2]] };
    });
  }, points);
}

const dominant = (rgb, channel) => rgb[channel] > 60 && rgb[channel] > 1.8 * Math.max(...rgb.filter((_, i) => i !== channel));

function statusOf(name) {
  return page.evaluate((n) => {
    const d = window.colconWasm.views['3d'].displays.find((x) => x.name === n);
    return d ? d.status() : null;
  }, name);
}

try {
  page = browser.pages()[0] || await browser.newPage();
  page.on('pageerror', (e) => pageErrors.push(String(e && e.stack ? e.stack : e)));
  await page.goto(`${options.url}#3d`);
  await until(() => document.body.dataset.state === 'ready', null, 'the page to be ready');
  const urdf = readFileSync(options.urdf, 'utf-8').replace(/<!--[\s\S]*?-->/g, '').replace(/<\?xml[^>]*\?>/, '').replace(/\s*\n\s*/g, ' ').trim();
  stats.rsp = await page.evaluate((u) => window.colconWasm.session.startProcess('robot_state_publisher', 'robot_state_publisher',
    ['--ros-args', '-p', `robot_description:=${u}`]).id, urdf);
  await page.setInputFiles('.scene-view input[type=file]', options.rviz);
  await until(() => window.colconWasm.views['3d'].element.dataset.ready === 'true'
    && window.colconWasm.views['3d'].displays.length >= 5, null, 'the .rviz file\'s displays');
  checks.rviz = await page.evaluate(() => {
    const v = window.colconWasm.views['3d'];
    return { fixedFrame: v.fixedFrame, displays: v.displays.map((d) => `${d.constructor.kind}:${d.name}:${d.topic}`),
      unsupported: v.unsupported, notes: v.notes.textContent };
  });
  // the robot arrives; its arm has no transform before a joint state
  await until(() => { const d = window.colconWasm.views['3d'].displays.find((x) => x.name === 'RobotModel'); return d && d.description; }, null, 'the robot description');
  checks.beforeJointStates = await statusOf('RobotModel');
  stats.firstFrameMs = await page.evaluate(() => {
    const d = window.colconWasm.views['3d'].displays.find((x) => x.name === 'RobotModel');
    return d.loadedAt;
  });
  // a joint state publisher of the page's own, at 20 Hz
  await page.evaluate(() => {
    const { session } = window.colconWasm;
    const type = 'sensor_msgs/msg/JointState';
    const pub = session.publisher('/joint_states', type);
    window.joint = 0;
    window.jointTimer = setInterval(() => {
      const v = session.registry.create(type);
      // robot_state_publisher publishes a joint's transform only for a newer stamp
      const now = Date.now();
      v.header.stamp = { sec: Math.floor(now / 1000), nanosec: (now % 1000) * 1e6 };
      v.name = ['shoulder'];
      v.position = Float64Array.of(window.joint);
      pub.publish(session.registry.encode(type, v)).catch(() => {});
    }, 50);
  });
  await until(() => window.colconWasm.views['3d'].tf.frames.has('arm'), null, 'the arm\'s transform from robot_state_publisher');
  await new Promise((r) => setTimeout(r, 300));
  checks.robotStatus = await statusOf('RobotModel');
  const armAt0 = [0.55, 0, 0.3]; const armAt90 = [0, 0.55, 0.3]; const base = [-0.15, 0.05, 0.2];
  checks.at0 = await colorsAt([armAt0, armAt90, base]);
  await page.evaluate(() => { window.joint = Math.PI / 2; });
  await until(() => { const f = window.colconWasm.views['3d'].tf.frames.get('arm'); return f && Math.abs(f.pose.q[2] - Math.SQRT1_2) < 1e-3; }, null, 'the arm turned by 90 degrees');
  checks.at90 = await colorsAt([armAt0, armAt90, base]);
  // the table is redrawn twice a second
  await until(() => document.querySelectorAll('.tf-tree tbody tr').length >= 2, null, 'the TF tree table', 5000).catch(() => {});
  checks.tfTree = await page.evaluate(() => [...document.querySelectorAll('.tf-tree tbody tr')].map((r) => r.dataset.frame));

  // markers: a green cube, then DELETEALL
  const marker = (action) => page.evaluate((act) => {
    const { session } = window.colconWasm;
    const type = 'visualization_msgs/msg/MarkerArray';
    const array = session.registry.create(type);
    const m = session.registry.create('visualization_msgs/msg/Marker');
    m.header.frame_id = 'base_link';
    m.ns = 'demo'; m.id = 1; m.type = 1; m.action = act;
    m.pose.position = { x: -0.7, y: 0.7, z: 0.1 }; m.pose.orientation = { x: 0, y: 0, z: 0, w: 1 };
    m.scale = { x: 0.3, y: 0.3, z: 0.3 }; m.color = { r: 0, g: 1, b: 0, a: 1 };
    array.markers = [m];
    window.markerPub ||= session.publisher('/demo_markers', type);
    return window.markerPub.publish(session.registry.encode(type, array));
  }, action);
  const cube = [-0.7, 0.7, 0.25];
  for (let i = 0; i < 30 && !(await statusOf('Markers')).text.startsWith('1 markers'); i++) {
    await marker(0);
    await new Promise((r) => setTimeout(r, 200));
  }
  checks.markerStatus = await statusOf('Markers');
  checks.markerAdded = await colorsAt([cube]);
  await marker(3);
  await until(() => window.colconWasm.views['3d'].displays.find((x) => x.name === 'Markers').markers.size === 0, null, 'DELETEALL');
  checks.markerDeleted = await colorsAt([cube]);

  // a laser scan: 181 ranges of 1 m over the front half, yellow
  await page.evaluate(() => {
    const { session } = window.colconWasm;
    const type = 'sensor_msgs/msg/LaserScan';
    const pub = session.publisher('/scan', type);
    window.scanTimer = setInterval(() => {
      const s = session.registry.create(type);
      s.header.frame_id = 'base_link';
      s.angle_min = -Math.PI / 2; s.angle_max = Math.PI / 2; s.angle_increment = Math.PI / 180;
      s.range_min = 0.1; s.range_max = 10;
      s.ranges = new Float32Array(181).fill(1.2);
      pub.publish(session.registry.encode(type, s)).catch(() => {});
    }, 100);
  });
  await until(() => { const d = window.colconWasm.views['3d'].displays.find((x) => x.name === 'Scan'); return d && d.count === 181; }, null, 'the scan\'s 181 points');
  checks.scan = await colorsAt([[0, -1.2, 0]]);
  checks.scanStatus = await statusOf('Scan');

  // 100k points at 10 Hz for 4 s; the page must go on answering clicks
  stats.cloud = await page.evaluate(async () => {
    const { session } = window.colconWasm;
    const view = window.colconWasm.views['3d'];
    const type = 'sensor_msgs/msg/PointCloud2';
    const pub = session.publisher('/points', type);
    const n = 100000;
    const c = session.registry.create(type);
    c.header.frame_id = 'base_link';
    c.height = 1; c.width = n; c.point_step = 16; c.row_step = 16 * n; c.is_dense = true;
    c.fields = ['x', 'y', 'z'].map((name, i) => ({ name, offset: 4 * i, datatype: 7, count: 1 }));
    const data = new Float32Array(n * 4);
    let k = 0;
    const longTasks = [];
    const observer = new PerformanceObserver((list) => { for (const e of list.getEntries()) longTasks.push(e.duration); });
    observer.observe({ type: 'longtask', buffered: false });
    const frames0 = view.scene.frames;
    const t0 = performance.now();
    const clicks = [];
    const checkbox = view.list.element.querySelector('[data-kind="TF"] input[type=checkbox]');
    await new Promise((resolve) => {
      const timer = setInterval(() => {
        k++;
        for (let i = 0; i < n; i++) {
          const a = i * 0.001 + k * 0.05;
          data[i * 4] = Math.cos(a) * (1 + i / n); data[i * 4 + 1] = Math.sin(a) * (1 + i / n); data[i * 4 + 2] = (i % 100) / 100;
        }
        c.data = new Uint8Array(data.buffer);
        pub.publish(session.registry.encode(type, c)).catch(() => {});
        if (k % 10 === 5) {
          // a click on a display's checkbox, timed from the event to its handler's render request
          const start = performance.now();
          checkbox.click();
          clicks.push(performance.now() - start);
        }
        if (performance.now() - t0 > 4000) { clearInterval(timer); resolve(); }
      }, 100);
    });
    // keep the scene drawing every frame meanwhile: the cloud moves, so each message asks for one
    observer.disconnect();
    const seconds = (performance.now() - t0) / 1000;
    const cloud = view.displays.find((x) => x.name === 'Cloud');
    return { published: k, seconds, fps: (view.scene.frames - frames0) / seconds, clicks, longTasks,
      points: cloud.count, status: cloud.status() };
  });

  // the log dock's splitter: dragged down, the 3D canvas grows; the height is kept on reload
  const before = await page.evaluate(() => ({ dock: document.querySelector('section.logs').getBoundingClientRect().height,
    canvas: window.colconWasm.views['3d'].scene.canvas.getBoundingClientRect().height }));
  const handle = await page.locator('.dock-splitter').boundingBox();
  await page.mouse.move(handle.x + handle.width / 2, handle.y + 3);
  await page.mouse.down();
  await page.mouse.move(handle.x + handle.width / 2, handle.y + 120, { steps: 5 });
  await page.mouse.up();
  await new Promise((r) => setTimeout(r, 300));
  const after = await page.evaluate(() => ({ dock: document.querySelector('section.logs').getBoundingClientRect().height,
    canvas: window.colconWasm.views['3d'].scene.canvas.getBoundingClientRect().height }));
  checks.splitter = { before, after };

  // screenshots at three widths
  stats.widths = {};
  for (const width of [1024, 1440, 2560]) {
    await page.setViewportSize({ width, height: width === 2560 ? 1300 : 900 });
    await new Promise((r) => setTimeout(r, 500));
    stats.widths[width] = await page.evaluate(() => ({ scrollWidth: document.documentElement.scrollWidth, innerWidth: window.innerWidth,
      canvas: window.colconWasm.views['3d'].scene.canvas.getBoundingClientRect().toJSON() }));
    await page.screenshot({ path: join(options.screenshots, `page_3d_${width}.png`) });
  }
  await page.evaluate(() => { clearInterval(window.jointTimer); clearInterval(window.scanTimer); });
} catch (e) {
  error = String(e && e.message ? e.message : e);
}
let logs = {};
try {
  logs = await page.evaluate(() => Object.fromEntries([...window.colconWasm.session.processes.values()].map((p) => [p.exe, p.log.map((e) => e.text).slice(-30)])));
} catch { /* the page is gone */ }
await browser.close();
process.stdout.write(`${JSON.stringify({ ok: !error, error, checks, stats, logs, pageErrors })}\n`);
