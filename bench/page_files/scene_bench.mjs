// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// bench/page's 3D measures in headless Chromium (SwiftShader WebGL), on
// the robot demo's page link: the robot's first frame after
// /robot_description arrives, then frames per second and main-thread long
// tasks while the view orbits: the robot alone (the baseline), a 100k-point
// cloud published once (what drawing it costs), and the same cloud
// published at 10 Hz by the page (same page, same run).
// Prints one JSON line.
//
//   node scene_bench.mjs '<json: {url, chromium, seconds}>'

// tests/js's Chromium launcher (its playwright-core: npm ci there; it downloads no browser)
const { launchChromium } = await import(new URL('../../tests/js/chromium.mjs', import.meta.url).href);

const options = JSON.parse(process.argv[2]);
const browser = await launchChromium(options.chromium);
const out = {};
try {
  const page = await browser.newPage({ viewport: { width: 1440, height: 900 } });
  await page.goto(options.url);
  await page.waitForFunction(() => {
    const v = window.colconWasm && window.colconWasm.views && window.colconWasm.views['3d'];
    const d = v && v.displays.find((x) => x.name === 'RobotModel');
    return d && d.firstFrameAt;
  }, null, { timeout: 120000, polling: 50 });
  out.robotFirstFrameMs = await page.evaluate(() => {
    const d = window.colconWasm.views['3d'].displays.find((x) => x.name === 'RobotModel');
    return d.firstFrameAt - d.receivedAt;
  });
  const measure = (withCloud, once = false) => page.evaluate(async ({ seconds, withCloud, once }) => {
    const { session } = window.colconWasm;
    const view = window.colconWasm.views['3d'];
    const { scene } = view;
    let timer = null;
    if (withCloud) {
      if (!view.displays.some((d) => d.name === 'Bench cloud')) {
        view.addDisplay('PointCloud2', { name: 'Bench cloud', topic: '/bench_points', colorMode: 'AxisColor', size: 0.01 });
      }
      const type = 'sensor_msgs/msg/PointCloud2';
      const pub = session.publisher('/bench_points', type);
      const n = 100000;
      const c = session.registry.create(type);
      c.header.frame_id = 'base_link'; c.height = 1; c.width = n; c.point_step = 16; c.row_step = 16 * n; c.is_dense = true;
      c.fields = ['x', 'y', 'z'].map((name, i) => ({ name, offset: 4 * i, datatype: 7, count: 1 }));
      const data = new Float32Array(n * 4);
      let k = 0;
      const send = () => {
        k++;
        for (let i = 0; i < n; i++) { const a = i * 0.001 + k * 0.05; data[i * 4] = Math.cos(a) * 1.5; data[i * 4 + 1] = Math.sin(a) * 1.5; data[i * 4 + 2] = (i % 100) / 100; }
        c.data = new Uint8Array(data.buffer);
        pub.publish(session.registry.encode(type, c)).catch(() => {});
      };
      // once: one cloud, then only the drawing (the renderer's own floor)
      if (once) send(); else timer = setInterval(send, 100);
      await new Promise((r) => setTimeout(r, 1000));
    }
    const longTasks = [];
    const observer = new PerformanceObserver((list) => { for (const e of list.getEntries()) longTasks.push(e.duration); });
    observer.observe({ type: 'longtask' });
    // orbit: a frame asked for at every animation frame, as a user dragging the view
    scene.controls.autoRotate = true;
    let running = true;
    const spin = () => { if (!running) return; scene.controls.update(); scene.requestRender(); requestAnimationFrame(spin); };
    requestAnimationFrame(spin);
    const f0 = scene.frames;
    const t0 = performance.now();
    await new Promise((r) => setTimeout(r, seconds * 1000));
    running = false;
    scene.controls.autoRotate = false;
    const fps = (scene.frames - f0) / ((performance.now() - t0) / 1000);
    observer.disconnect();
    if (timer) clearInterval(timer);
    const cloud = view.displays.find((d) => d.name === 'Bench cloud');
    return { fps, longTasks: longTasks.length, longestTaskMs: longTasks.length ? Math.max(...longTasks) : 0,
      points: cloud ? cloud.count : 0, software: scene.software };
  }, { seconds: options.seconds, withCloud, once });
  out.robot = await measure(false);
  out.cloudStatic = await measure(true, true);
  out.cloud = await measure(true);
} catch (e) {
  out.error = String(e && e.message ? e.message : e);
}
await browser.close();
process.stdout.write(`${JSON.stringify(out)}\n`);
