// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Drives the real launcher page (colcon-wasm serve, the demo built by real
// Emscripten) in Debian's Chromium with playwright-core, step by step, with a
// screenshot per step. Run by tests/test_page.py:
//
//   node page_flow.mjs '<json: {url, screenshots, chromium, flow}>'
//
// Prints one JSON line per step ({step, ok, ms, error?, ...}) and exits 1 at
// the first failed step.

import { mkdirSync } from 'node:fs';
import { join } from 'node:path';

import { launchChromium } from './chromium.mjs';

const options = JSON.parse(process.argv[2]);
const STEP_TIMEOUT = options.timeoutMs || 20000;
mkdirSync(options.screenshots, { recursive: true });

// playwright-core gives the browser a fresh temporary profile (user data dir)
const browser = await launchChromium(options.chromium);

let shot = 0;
let failed = false;
const pageErrors = [];

function report(entry) {
  process.stdout.write(`${JSON.stringify(entry)}\n`);
}

async function screenshot(page, name) {
  shot += 1;
  const file = join(options.screenshots, `${String(shot).padStart(2, '0')}-${name}.png`);
  await page.screenshot({ path: file });
  return file;
}

async function step(page, name, fn) {
  if (failed) return null;
  const started = Date.now();
  try {
    const extra = (await fn()) || {};
    const file = await screenshot(page, name);
    report({ step: name, ok: true, ms: Date.now() - started, screenshot: file, ...extra });
    return extra;
  } catch (e) {
    failed = true;
    let file = null;
    try { file = await screenshot(page, `${name}-FAILED`); } catch (ignored) { /* the page is gone */ }
    report({ step: name, ok: false, ms: Date.now() - started, error: String(e && e.stack ? e.stack : e), screenshot: file, pageErrors });
    return null;
  }
}

const logPane = (page) => page.locator('.logpane');
const tab = (page, name) => page.locator(`nav.tabs button[data-tab="${name}"]`).click();

async function waitForLog(page, procLabelPrefix, pattern, timeout = STEP_TIMEOUT) {
  await page.waitForFunction(([prefix, source]) => {
    const re = new RegExp(source);
    const procs = window.__launcherLogs || [];
    return procs.some((l) => l.label.startsWith(prefix) && re.test(l.text));
  }, [procLabelPrefix, pattern.source], { timeout });
}

async function startFromSidebar(page, exe, args = '') {
  const row = page.locator(`.exe[data-exe="${exe}"]`);
  if (args) {
    await row.locator('button.icon').click();
    await row.locator('.args input').fill(args);
  }
  await row.locator('button.run').click();
}

// Records every log line the page shows, with its process label and the time
// (performance.now(), ms since navigation) it appeared.
const RECORD_LOGS = `
  window.__launcherLogs = [];
  const seen = new Set();
  new MutationObserver((records) => {
    for (const r of records) for (const n of r.addedNodes) {
      if (!(n instanceof HTMLElement)) continue;
      const lines = n.matches('.logline, .crash') ? [n] : [...n.querySelectorAll('.logline, .crash')];
      for (const line of lines) {
        if (seen.has(line.dataset.seq)) continue;
        seen.add(line.dataset.seq);
        window.__launcherLogs.push({ label: line.dataset.proc, text: line.textContent,
          time: performance.now(), crash: line.matches('.crash') });
      }
    }
  }).observe(document, { childList: true, subtree: true });
`;

// Records the labels the plot draws on its canvas (its axes).
const RECORD_PLOT_LABELS = `
  window.__plotLabels = new Set();
  const fillText = CanvasRenderingContext2D.prototype.fillText;
  CanvasRenderingContext2D.prototype.fillText = function (text, ...rest) {
    if (this.canvas.classList && this.canvas.classList.contains('plot')) window.__plotLabels.add(String(text));
    return fillText.call(this, text, ...rest);
  };
`;

/**
 * The line breaks inside an element's text, as 'ab' pairs: the character
 * that ends a line and the one that starts the next.
 */
function lineBreaks(page, selector) {
  return page.evaluate((sel) => {
    const el = document.querySelector(sel);
    if (!el) throw new Error(`no ${sel}`);
    const range = document.createRange();
    const walker = document.createTreeWalker(el, NodeFilter.SHOW_TEXT);
    const breaks = [];
    let previous = null;
    for (let node = walker.nextNode(); node; node = walker.nextNode()) {
      for (let i = 0; i < node.length; i++) {
        range.setStart(node, i);
        range.setEnd(node, i + 1);
        const rect = range.getClientRects()[0];
        if (!rect || rect.width === 0) continue;
        if (previous && rect.top > previous.top + rect.height / 2) breaks.push(previous.char + node.data[i]);
        previous = { top: rect.top, char: node.data[i] };
      }
    }
    return breaks;
  }, selector);
}

/** The page fits its window: no sideways scrolling, the header and its chips inside it. */
async function checkLayout(page, width) {
  await page.setViewportSize({ width, height: 900 });
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const m = await page.evaluate(() => {
    const header = document.querySelector('header.top');
    const right = (sel) => document.querySelector(sel).getBoundingClientRect().right;
    const bar = document.querySelector('#playback-bar');
    return {
      scrollWidth: document.documentElement.scrollWidth, innerWidth: window.innerWidth,
      headerRight: header.getBoundingClientRect().right, headerOverflow: header.scrollWidth - header.clientWidth,
      chips: [...header.querySelectorAll('.chip:not([hidden])')].map((c) => [c.textContent, c.getBoundingClientRect().right]),
      runningRight: right('#running-chip'), headerHeight: header.getBoundingClientRect().height,
      barRight: bar.getBoundingClientRect().right, barBottom: bar.getBoundingClientRect().bottom,
      barOverflow: bar.scrollWidth - bar.clientWidth, innerHeight: window.innerHeight,
      connections: !!document.querySelector('aside.side #connections #rosbridge-url'),
      headerFields: document.querySelectorAll('header.top input[type=text], header.top #bag-play').length,
    };
  });
  const problems = [];
  if (m.scrollWidth > m.innerWidth) problems.push(`the page is ${m.scrollWidth} px wide in a ${m.innerWidth} px window`);
  if (m.headerRight > m.innerWidth || m.headerOverflow > 0) problems.push(`the header ends at ${m.headerRight} px, ${m.headerOverflow} px overflow`);
  for (const [text, right] of m.chips) if (right > m.innerWidth) problems.push(`the chip '${text}' ends at ${right} px`);
  if (m.headerHeight > 60) problems.push(`the header is ${m.headerHeight} px tall: it wrapped`);
  if (m.barRight > m.innerWidth || m.barOverflow > 0 || m.barBottom > m.innerHeight) problems.push(`the playback bar does not fit: ${JSON.stringify(m)}`);
  if (!m.connections) problems.push('the rosbridge field is not in the sidebar\'s connections panel');
  if (m.headerFields) problems.push('connection fields or the bag player are still in the header');
  if (problems.length) throw new Error(problems.join('; '));
  return { scroll_width: m.scrollWidth, header_right: Math.round(m.headerRight) };
}

async function demoFlow() {
  const context = await browser.newContext({ viewport: { width: 1440, height: 900 } });
  const page = await context.newPage();
  page.on('pageerror', (e) => pageErrors.push(e.message));
  await page.addInitScript(RECORD_LOGS);
  await page.addInitScript(RECORD_PLOT_LABELS);

  await step(page, 'open-with-run-talker-listener', async () => {
    await page.goto(`${options.url}?run=demo_nodes/talker&run=demo_nodes/listener`);
    await page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: STEP_TIMEOUT });
    await waitForLog(page, 'talker', /Publishing: 'Hello World: 1'/);
    const firstPublish = await page.evaluate(() => window.__launcherLogs.find((l) => /Publishing:/.test(l.text)).time);
    await waitForLog(page, 'listener', /I heard: \[Hello World: \d+\]/);
    return { first_publish_ms: Math.round(firstPublish) };
  });

  await step(page, 'nodes-and-topics-listed', async () => {
    await tab(page, 'nodes');
    await page.locator('tr[data-node="/talker"]').waitFor({ timeout: STEP_TIMEOUT });
    await page.locator('tr[data-node="/listener"]').waitFor({ timeout: STEP_TIMEOUT });
    await tab(page, 'topics');
    const row = page.locator('tr[data-topic="/chatter"]');
    await row.waitFor({ timeout: STEP_TIMEOUT });
    const cells = await row.locator('td').allTextContents();
    if (cells[1] !== 'demo_interfaces/msg/Chatter' || cells[2] !== '1' || cells[3] !== '1') {
      throw new Error(`/chatter row is ${JSON.stringify(cells)}, expected type demo_interfaces/msg/Chatter, 1 publisher, 1 subscriber`);
    }
  });

  await step(page, 'echo-decodes-messages', async () => {
    await page.locator('tr[data-topic="/chatter"]').click();
    const echo = page.locator('[data-echo="/chatter"] .echo-msg pre').first();
    await echo.waitFor({ timeout: STEP_TIMEOUT });
    await page.waitForFunction(() => /data: 'Hello World: \d+'\ncount: \d+/.test(
      document.querySelector('[data-echo="/chatter"] .echo-msg pre')?.textContent || ''), null, { timeout: STEP_TIMEOUT });
  });

  await step(page, 'publish-form-reaches-the-listener', async () => {
    await page.locator('.topic-inspector button[data-subtab="publish"]').click();
    await page.locator('[data-publish="/chatter"] input[data-field="data"]').fill('Hello from the page');
    await page.locator('[data-publish="/chatter"] input[data-field="count"]').fill('7');
    await page.locator('[data-publish="/chatter"] button.primary').click();
    await waitForLog(page, 'listener', /I heard: \[Hello from the page\]/);
  });

  await step(page, 'service-call-returns', async () => {
    await startFromSidebar(page, 'demo_nodes/add_two_ints_server');
    await tab(page, 'services');
    const row = page.locator('tr[data-service="/add_two_ints"]');
    await row.waitFor({ timeout: STEP_TIMEOUT });
    await row.click();
    await page.locator('[data-call="/add_two_ints"] input[data-field="a"]').fill('2');
    await page.locator('[data-call="/add_two_ints"] input[data-field="b"]').fill('40');
    await page.locator('[data-call="/add_two_ints"] button.primary').click();
    await page.waitForFunction(() => /sum: 42/.test(document.querySelector('[data-response="/add_two_ints"]')?.textContent || ''),
      null, { timeout: STEP_TIMEOUT });
    await waitForLog(page, 'add_two_ints_server', /Incoming request: a: 2 b: 40/);
  });

  // talker, listener and the service run: the page at a laptop's, a desktop's and a wide screen's width
  for (const width of [1024, 1440, 2560]) {
    await step(page, `layout-fits-${width}-px`, async () => {
      const fits = await checkLayout(page, width);
      // names wrap at / _ . only: /add_two_ints is short enough not to wrap at all
      const name = await lineBreaks(page, 'tr[data-service="/add_two_ints"] td.name');
      if (name.length) throw new Error(`/add_two_ints wraps at ${JSON.stringify(name)}`);
      const pieces = await page.locator('tr[data-service="/add_two_ints"] td.type')
        .evaluate((td) => td.innerHTML.split('<wbr>'));
      if (pieces.join('|') !== 'demo_|interfaces/|srv/|AddTwoInts') {
        throw new Error(`the type's <wbr> are not after each / and _: ${pieces.join('|')}`);
      }
      const type = await lineBreaks(page, 'tr[data-service="/add_two_ints"] td.type');
      const inWord = type.filter((pair) => !/^[/_. ,]/.test(pair));
      if (inWord.length) throw new Error(`demo_interfaces/srv/AddTwoInts wraps inside a word: ${JSON.stringify(type)}`);
      return { ...fits, type_breaks: type };
    });
  }
  await page.setViewportSize({ width: 1440, height: 900 });

  await step(page, 'stopping-a-node-updates-the-graph', async () => {
    await page.locator('.proc[data-proc^="talker"] button.stop').click();
    await tab(page, 'nodes');
    await page.locator('tr[data-node="/talker"]').waitFor({ state: 'detached', timeout: STEP_TIMEOUT });
    await tab(page, 'topics');
    await page.waitForFunction(() => {
      const cells = [...document.querySelectorAll('tr[data-topic="/chatter"] td')].map((td) => td.textContent);
      return cells[2] === '0' && cells[3] === '1';
    }, null, { timeout: STEP_TIMEOUT });
    await page.locator('.proc[data-proc^="talker"][data-state="stopped"]').waitFor({ timeout: STEP_TIMEOUT });
  });

  await step(page, 'a-crash-is-reported-and-the-others-go-on', async () => {
    await startFromSidebar(page, 'demo_nodes/crasher', '--ros-args -p delay:=0.5');
    await page.locator('.proc[data-proc^="crasher"][data-state="crashed"]').waitFor({ timeout: STEP_TIMEOUT });
    await page.locator('.logpane .crash').first().waitFor({ timeout: STEP_TIMEOUT });
    const heardBefore = await page.evaluate(() => window.__launcherLogs.filter((l) => /I heard/.test(l.text)).length);
    await startFromSidebar(page, 'demo_nodes/talker');
    await page.waitForFunction((n) => window.__launcherLogs.filter((l) => /I heard: \[Hello World/.test(l.text)).length > n,
      heardBefore, { timeout: STEP_TIMEOUT });
    const states = await page.locator('.proc').evaluateAll((els) => els.map((e) => `${e.dataset.proc}:${e.dataset.state}`));
    if (!states.some((s) => s.startsWith('listener') && s.endsWith(':running'))) {
      throw new Error(`the listener is not running after the crash: ${states.join(', ')}`);
    }
  });

  await step(page, 'plot-of-a-numeric-topic', async () => {
    await startFromSidebar(page, 'demo_nodes/oscillator');
    await tab(page, 'topics');
    const row = page.locator('tr[data-topic="/wave"]');
    await row.waitFor({ timeout: STEP_TIMEOUT });
    await row.click();
    await page.locator('.topic-inspector button[data-subtab="plot"]').click();
    await page.locator('.plot-fields input[data-path="sine"]').waitFor({ timeout: STEP_TIMEOUT });
    await page.waitForTimeout(2500);
    const inked = await page.evaluate(() => {
      const c = document.querySelector('canvas.plot');
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let coloured = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i + 2] > 150 && d[i] < 120) coloured++;
      return coloured;
    });
    if (inked < 100) throw new Error(`the plot drew ${inked} blue pixels: no sine line`);
    const labels = await page.evaluate(() => [...window.__plotLabels].filter((l) => /s$/.test(l)));
    if (!labels.includes('0s') || !labels.includes('-10s')) throw new Error(`the time axis reads ${JSON.stringify(labels)}`);
    if (labels.some((l) => /^-0(\.0*)?s$/.test(l))) throw new Error(`the time axis has -0s: ${JSON.stringify(labels)}`);
    return { plotted_pixels: inked, time_axis: labels };
  });

  await step(page, 'image-view-of-a-camera-topic', async () => {
    await startFromSidebar(page, 'demo_nodes/camera');
    await tab(page, 'topics');
    const row = page.locator('tr[data-topic="/camera/image"]');
    await row.waitFor({ timeout: STEP_TIMEOUT });
    await row.click();
    await page.locator('.topic-inspector button[data-subtab="image"].active').waitFor({ timeout: STEP_TIMEOUT });
    await page.locator('.image-view .note', { hasText: '160×120 rgb8' }).waitFor({ timeout: STEP_TIMEOUT });
    const pixels = await page.evaluate(() => {
      const c = document.querySelector('canvas.image');
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      const at = (x, y) => Array.from(d.slice((y * c.width + x) * 4, (y * c.width + x) * 4 + 4));
      let white = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i] === 255 && d[i + 1] === 255 && d[i + 2] === 255) white++;
      return { size: [c.width, c.height], corner: at(0, 0), bottomRight: at(c.width - 1, c.height - 1), white };
    });
    // the gradient: red grows to the right, green downwards, blue 96; a 30x30 white square
    if (pixels.size.join('x') !== '160x120') throw new Error(`canvas is ${pixels.size}`);
    if (pixels.corner.join(',') !== '0,0,96,255') throw new Error(`top-left pixel is ${pixels.corner}`);
    if (pixels.bottomRight.join(',') !== '253,252,96,255') throw new Error(`bottom-right pixel is ${pixels.bottomRight}`);
    if (pixels.white !== 30 * 30) throw new Error(`${pixels.white} white pixels, expected the 30x30 square`);
    return { white_pixels: pixels.white };
  });

  await step(page, 'echo-keeps-up-with-1-kHz', async () => {
    await startFromSidebar(page, 'demo_nodes/oscillator', '--ros-args -r __node:=fast -r wave:=fast_wave -p rate:=1000');
    await tab(page, 'topics');
    const row = page.locator('tr[data-topic="/fast_wave"]');
    await row.waitFor({ timeout: STEP_TIMEOUT });
    await row.click();
    await page.locator('[data-echo="/fast_wave"] .echo-msg').first().waitFor({ timeout: STEP_TIMEOUT });
    const result = await page.evaluate(async () => {
      const counter = () => Number(document.querySelector('.topic-inspector .echo-bar strong').textContent);
      const gaps = [];
      let last = performance.now();
      let running = true;
      const frame = (t) => { gaps.push(t - last); last = t; if (running) requestAnimationFrame(frame); };
      requestAnimationFrame(frame);
      const c0 = counter();
      const t0 = performance.now();
      await new Promise((r) => setTimeout(r, 3000));
      running = false;
      const c1 = counter();
      const seconds = (performance.now() - t0) / 1000;
      gaps.sort((a, b) => a - b);
      return { rate: (c1 - c0) / seconds, max_frame_gap_ms: gaps[gaps.length - 1], frames: gaps.length };
    });
    if (result.rate < 800) throw new Error(`echo received ${result.rate.toFixed(0)} msg/s of a 1 kHz topic`);
    if (result.max_frame_gap_ms > 250) throw new Error(`the page froze for ${result.max_frame_gap_ms.toFixed(0)} ms`);
    return { echo_rate_hz: Math.round(result.rate), max_frame_gap_ms: Math.round(result.max_frame_gap_ms) };
  });

  await step(page, 'all-output-in-the-order-logged', async () => {
    // the lines of every process, by their ROS time stamps ([INFO] [seconds] [node]: ...);
    // first as the tab draws them, then as they come in
    const outOfOrder = () => page.evaluate(() => {
      const bad = [];
      let previous = null;
      for (const line of document.querySelectorAll('.logpane > *')) {
        const m = /^\s*\[[A-Z]+\]\s*\[(\d+\.\d+)\]/.exec(line.querySelector('.who') ? line.lastChild.textContent : line.textContent);
        if (!m) { previous = null; continue; }  // a line without a stamp took the time it came in
        const stamp = Number(m[1]);
        if (previous && stamp < previous.stamp) bad.push(`${previous.text} | ${line.textContent}`);
        previous = { stamp, text: line.textContent };
      }
      return { bad, lines: document.querySelectorAll('.logpane .logline').length };
    });
    await page.locator('.logtabs button[data-log="all"]').click();
    const drawn = await outOfOrder();
    await page.waitForTimeout(2500);
    const live = await outOfOrder();
    if (drawn.bad.length || live.bad.length) throw new Error(`lines out of time order: ${JSON.stringify([...drawn.bad, ...live.bad].slice(0, 5))}`);
    if (drawn.lines < 10) throw new Error(`only ${drawn.lines} lines in all output`);
    return { lines: live.lines };
  });

  await step(page, 'logs-of-one-process', async () => {
    await page.locator('.logtabs button[data-log^="listener"]').click();
    await page.locator('.logpane .logline', { hasText: 'I heard' }).first().waitFor({ timeout: STEP_TIMEOUT });
  });
  await page.close();

  // the same page again in this browser (HTTP and code caches warm)
  const again = await context.newPage();
  again.on('pageerror', (e) => pageErrors.push(e.message));
  await again.addInitScript(RECORD_LOGS);
  await step(again, 'reopen-warm-first-publish', async () => {
    await again.goto(`${options.url}?run=demo_nodes/talker`);
    await waitForLog(again, 'talker', /Publishing: 'Hello World: 1'/);
    const firstPublish = await again.evaluate(() => window.__launcherLogs.find((l) => /Publishing:/.test(l.text)).time);
    return { first_publish_ms: Math.round(firstPublish) };
  });
  await context.close();
}

// The same flow on Humble's rclcpp examples (built by the rmw_wasm_cpp issue).
async function humbleFlow() {
  const context = await browser.newContext({ viewport: { width: 1440, height: 900 } });
  const page = await context.newPage();
  page.on('pageerror', (e) => pageErrors.push(e.message));
  await page.addInitScript(RECORD_LOGS);
  const pub = 'examples_rclcpp_minimal_publisher/publisher_member_function';
  const sub = 'examples_rclcpp_minimal_subscriber/subscriber_member_function';

  await step(page, 'humble-open-with-run-publisher-subscriber', async () => {
    await page.goto(`${options.url}?run=${pub}&run=${sub}`);
    await page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: STEP_TIMEOUT });
    await waitForLog(page, 'publisher_member_function', /Publishing: 'Hello, world! \d+'/);
    const firstPublish = await page.evaluate(() => window.__launcherLogs.find((l) => /Publishing:/.test(l.text)).time);
    await waitForLog(page, 'subscriber_member_function', /I heard: 'Hello, world! \d+'/);
    return { first_publish_ms: Math.round(firstPublish) };
  });

  await step(page, 'humble-nodes-topics-echo', async () => {
    await tab(page, 'nodes');
    await page.locator('tr[data-node="/minimal_publisher"]').waitFor({ timeout: STEP_TIMEOUT });
    await page.locator('tr[data-node="/minimal_subscriber"]').waitFor({ timeout: STEP_TIMEOUT });
    await tab(page, 'topics');
    const row = page.locator('tr[data-topic="/topic"]');
    await row.waitFor({ timeout: STEP_TIMEOUT });
    const cells = await row.locator('td').allTextContents();
    if (cells[1] !== 'std_msgs/msg/String') throw new Error(`/topic row is ${JSON.stringify(cells)}`);
    await row.click();
    await page.waitForFunction(() => /data: 'Hello, world! \d+'/.test(
      document.querySelector('[data-echo="/topic"] .echo-msg pre')?.textContent || ''), null, { timeout: STEP_TIMEOUT });
  });

  await step(page, 'humble-publish-reaches-the-subscriber', async () => {
    await page.locator('.topic-inspector button[data-subtab="publish"]').click();
    await page.locator('[data-publish="/topic"] input[data-field="data"]').fill('from the page');
    await page.locator('[data-publish="/topic"] button.primary').click();
    await waitForLog(page, 'subscriber_member_function', /I heard: 'from the page'/);
  });

  await step(page, 'humble-service-call', async () => {
    await startFromSidebar(page, 'examples_rclcpp_minimal_service/service_main');
    await tab(page, 'services');
    const row = page.locator('tr[data-service="/add_two_ints"]');
    await row.waitFor({ timeout: STEP_TIMEOUT });
    await row.click();
    await page.locator('[data-call="/add_two_ints"] input[data-field="a"]').fill('2');
    await page.locator('[data-call="/add_two_ints"] input[data-field="b"]').fill('40');
    await page.locator('[data-call="/add_two_ints"] button.primary').click();
    await page.waitForFunction(() => /sum: 42/.test(document.querySelector('[data-response="/add_two_ints"]')?.textContent || ''),
      null, { timeout: STEP_TIMEOUT });
  });

  await step(page, 'humble-stdin-typed-into-the-async-client', async () => {
    // the service of the previous step answers; the client reads its numbers from stdin
    await startFromSidebar(page, 'examples_rclcpp_async_client/client_main');
    await waitForLog(page, 'client_main', /insert the first one/);
    await page.locator('.logtabs button[data-log^="client_main"]').click();
    const input = page.locator('.logs form.stdin input');
    await input.waitFor({ timeout: STEP_TIMEOUT });
    for (const line of ['2', '3']) {
      await input.fill(line);
      await input.press('Enter');
    }
    await waitForLog(page, 'client_main', /Result of 2 \+ 3 is: 5/);
    await input.fill('q');
    await input.press('Enter');
    await page.locator('.logpane .logline', { hasText: 'finished (exit code 0)' }).waitFor({ timeout: STEP_TIMEOUT });
  });

  await step(page, 'humble-action-goal-with-feedback', async () => {
    await startFromSidebar(page, 'examples_rclcpp_minimal_action_server/action_server_member_functions');
    await tab(page, 'actions');
    const row = page.locator('tr[data-action="/fibonacci"]');
    await row.waitFor({ timeout: STEP_TIMEOUT });
    await row.click();
    await page.locator('[data-goal="/fibonacci"] input[data-field="order"]').fill('5');
    await page.locator('[data-goal="/fibonacci"] button.primary').click();
    await page.waitForFunction(() => /SUCCEEDED/.test(document.querySelector('[data-result="/fibonacci"]')?.textContent || ''),
      null, { timeout: STEP_TIMEOUT });
    const text = await page.locator('[data-goal="/fibonacci"]').textContent();
    if (!/feedback #\d+/.test(text)) throw new Error('no feedback was shown');
    const result = await page.locator('[data-result="/fibonacci"] pre').textContent();
    if (!/sequence:\n- 0\n- 1\n- 1\n- 2\n- 3\n- 5/.test(result)) throw new Error(`unexpected result: ${result}`);
  });

  await step(page, 'humble-parameters-list-get-set', async () => {
    await tab(page, 'parameters');
    await page.locator('[data-view="parameters"] select').selectOption('/minimal_publisher');
    const input = page.locator('[data-params="/minimal_publisher"] input[data-param="use_sim_time"]');
    await input.waitFor({ timeout: STEP_TIMEOUT });
    if ((await input.inputValue()) !== 'false') throw new Error(`use_sim_time is ${await input.inputValue()}`);
    await input.fill('true');
    await input.press('Enter');
    await page.locator('[data-params="/minimal_publisher"] .ok-text', { hasText: 'set' }).waitFor({ timeout: STEP_TIMEOUT });
  });

  await step(page, 'humble-stop-updates-the-graph', async () => {
    await page.locator('.proc[data-proc^="publisher_member_function"] button.stop').click();
    await tab(page, 'nodes');
    await page.locator('tr[data-node="/minimal_publisher"]').waitFor({ state: 'detached', timeout: STEP_TIMEOUT });
  });
  await context.close();
}

async function notIsolatedFlow() {
  // The same server, with the isolation headers taken out of every response.
  const context = await browser.newContext({ viewport: { width: 1280, height: 720 } });
  const page = await context.newPage();
  await context.route('**/*', async (route) => {
    const response = await route.fetch();
    const headers = { ...response.headers() };
    delete headers['cross-origin-opener-policy'];
    delete headers['cross-origin-embedder-policy'];
    await route.fulfill({ response, headers });
  });
  await step(page, 'not-isolated-page-says-so', async () => {
    await page.goto(`${options.url}?run=demo_nodes/talker`);
    const banner = page.locator('#isolation-error');
    await banner.waitFor({ timeout: STEP_TIMEOUT });
    const text = await banner.textContent();
    for (const needle of ['not cross-origin isolated', 'Cross-Origin-Opener-Policy: same-origin',
      'Cross-Origin-Embedder-Policy: require-corp', 'colcon-wasm serve']) {
      if (!text.includes(needle)) throw new Error(`the message lacks '${needle}': ${text}`);
    }
    if (!(await page.locator('.exe button.run').first().isDisabled())) throw new Error('Run buttons stay enabled');
    if ((await page.locator('.proc').count()) !== 0) throw new Error('?run started a process on a non-isolated page');
  });
  await context.close();
}

try {
  if (options.flow === 'demo' || !options.flow) await demoFlow();
  if (options.flow === 'isolation' || !options.flow) await notIsolatedFlow();
  if (options.flow === 'humble') await humbleFlow();
} finally {
  await browser.close();
}
process.exit(failed ? 1 : 0);
