// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The robot demo's one link (docs/launcher.md), opened as a user opens it
// (tests/test_page_3d.py): ?run= starts robot_state_publisher and
// demo_robot's arm_motion, ?rviz= opens demo_robot's .rviz file. Waits for
// the robot with its meshes, the laser cloud and the markers, and checks
// that the arm moves. Prints one JSON line: {ok, error, checks, logs, pageErrors}.
//
//   node page_robot_demo.mjs '<json: {url, chromium, screenshot}>'

import { launchChromium } from './chromium.mjs';

const options = JSON.parse(process.argv[2]);
const browser = await launchChromium(options.chromium);
const pageErrors = [];
const checks = {};
let error = null;
let page = null;
const display = (name) => `(window.colconWasm && window.colconWasm.views && window.colconWasm.views['3d'].displays.find((d) => d.name === '${name}'))`;

try {
  page = await browser.newPage({ viewport: { width: 1440, height: 900 } });
  page.on('pageerror', (e) => pageErrors.push(String(e && e.stack ? e.stack : e)));
  const t0 = Date.now();
  await page.goto(options.url);
  await page.waitForFunction(`(() => { const d = ${display('RobotModel')}; return d && d.status().level === 'ok'
    && d.links.size === 6 && d.meshErrors.length === 0; })()`, null, { timeout: 90000, polling: 100 });
  checks.robotMs = Date.now() - t0;
  await page.waitForFunction(`(() => { const d = ${display('Laser')}; return d && d.count === 2160; })()`, null, { timeout: 30000, polling: 100 });
  await page.waitForFunction(`(() => { const d = ${display('Markers')}; return d && d.markers.size >= 2; })()`, null, { timeout: 30000, polling: 100 });
  checks.status = await page.evaluate(() => Object.fromEntries(window.colconWasm.views['3d'].displays.map((d) => [d.name, d.status()])));
  checks.meshes = await page.evaluate(() => {
    const d = window.colconWasm.views['3d'].displays.find((x) => x.name === 'RobotModel');
    let meshes = 0;
    for (const name of ['upper_arm', 'gripper']) d.links.get(name).traverse((o) => { if (o.isMesh && o.geometry.attributes.position.count > 12) meshes++; });
    return meshes;
  });
  const gripper = () => page.evaluate(() => window.colconWasm.views['3d'].tf.lookup('base_link', 'gripper').pose.t);
  checks.gripperBefore = await gripper();
  await new Promise((r) => setTimeout(r, 1500));
  checks.gripperAfter = await gripper();
  checks.frames = await page.evaluate(() => window.colconWasm.views['3d'].tf.frameIds());
  await page.screenshot({ path: options.screenshot });
  // the column of displays folds away for a wider view, and the choice is kept
  const canvasWidth = () => page.evaluate(() => document.querySelector('.scene-stage').getBoundingClientRect().width);
  checks.fold = { before: await canvasWidth() };
  await page.click('#scene-fold');
  await page.waitForTimeout(300);
  checks.fold.folded = await canvasWidth();
  await page.reload();
  await page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 60000 });
  checks.fold.afterReload = await page.evaluate(() => document.querySelector('section[data-view="3d"]').classList.contains('side-folded'));
  await page.click('#scene-fold');
  checks.fold.unfolded = await page.evaluate(() => !document.querySelector('section[data-view="3d"]').classList.contains('side-folded'));
} catch (e) {
  error = String(e && e.message ? e.message : e);
  try { checks.statusAtError = await page.evaluate(() => Object.fromEntries(window.colconWasm.views['3d'].displays.map((d) => [d.name, d.status()]))); } catch { /* gone */ }
}
let logs = {};
try {
  logs = await page.evaluate(() => Object.fromEntries([...window.colconWasm.session.processes.values()].map((p) => [p.exe, p.log.map((e) => e.text).slice(-20)])));
} catch { /* the page is gone */ }
await browser.close();
process.stdout.write(`${JSON.stringify({ ok: !error, error, checks, logs, pageErrors })}\n`);
