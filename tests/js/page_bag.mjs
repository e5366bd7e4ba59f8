// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The launcher page's record and replay, as a user does them, in Debian's
// Chromium (playwright-core; never a downloaded browser). Prints one JSON line.
//
//   node page_bag.mjs '<json: {url, chromium, mode, ...}>'
//
// mode 'record' {out}: starts the demo talker and camera, clicks Record,
//   waits 4 s, clicks Stop and saves the download to `out`:
//   {ok, error, logs: {talker}, chip, result}
// mode 'play' {bag}: starts the demo listener, drops `bag` on the page, then
//   Step ×3, seek to `seekMs`, Play, Pause, Play to the end:
//   {ok, error, logs: {listener}, marks: {afterSteps, afterPause, afterPauseWait, end}, info}
// mode 'clock' {bag, pkg, exe, args, until}: starts pkg/exe args, drops `bag`, ticks
//   /clock, plays, and waits for a log line matching `until`: {ok, error, logs: {node}}

import fs from 'node:fs';
import path from 'node:path';
import { chromium } from 'playwright-core';

const options = JSON.parse(process.argv[2]);
const browser = await chromium.launch({
  executablePath: options.chromium,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
const out = { ok: false, error: null, logs: {}, marks: {}, pageErrors: [] };
let page = null;

const logsOf = (id) => page.evaluate((i) => window.colconWasm.session.processes.get(i).log.map((e) => e.text), id);
const until = async (what, fn, arg, timeoutMs = 30000) => {
  try {
    await page.waitForFunction(fn, arg, { timeout: timeoutMs, polling: 50 });
  } catch (e) {
    throw new Error(`timed out waiting for ${what}`);
  }
};
/** Drop a bag on the page, as a user drags it from the file manager. */
async function dropBag(file) {
  const bytes = fs.readFileSync(file).toString('base64');
  const transfer = await page.evaluateHandle(([b64, name]) => {
    const raw = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const dt = new DataTransfer();
    dt.items.add(new File([raw], name));
    return dt;
  }, [bytes, path.basename(file)]);
  await page.dispatchEvent('body', 'drop', { dataTransfer: transfer });
  await until('the bag to open', () => !document.querySelector('#bag-player').hidden);
}
const heard = (id) => logsOf(id).then((lines) => lines.filter((l) => l.includes('I heard: [played')).map((l) => Number(/played (\d+)/.exec(l)[1])));

try {
  const context = await browser.newContext({ acceptDownloads: true });
  page = await context.newPage();
  page.on('pageerror', (e) => out.pageErrors.push(String(e)));
  await page.goto(options.url);
  await until('the page to be ready', () => document.body.dataset.state === 'ready', null, 60000);

  if (options.mode === 'record') {
    const talker = await page.evaluate(() => window.colconWasm.session.startProcess('demo_nodes', 'talker', []).id);
    const camera = await page.evaluate(() => window.colconWasm.session.startProcess('demo_nodes', 'camera', []).id);
    await until('the talker and the camera', ([t, c]) => {
      const s = window.colconWasm.session;
      return s.processes.get(t).log.some((e) => e.text.includes('Hello World: 2'))
        && s.graph.topics.some((x) => x.name === '/camera/image' && x.publishers > 0);
    }, [talker, camera]);
    await page.click('#bag-record');
    await until('recording', () => document.querySelector('#bag-state').textContent.includes('recording'));
    await page.waitForTimeout(4000);
    const downloading = page.waitForEvent('download', { timeout: 30000 });
    await page.click('#bag-record');
    const download = await downloading;
    await download.saveAs(options.out);
    out.suggested = download.suggestedFilename();
    out.logs.talker = await logsOf(talker);
    out.chip = await page.textContent('#bag-state');
  } else if (options.mode === 'clock') {
    const node = await page.evaluate(([p, e, a]) => window.colconWasm.session.startProcess(p, e, a).id,
      [options.pkg, options.exe, options.args]);
    await dropBag(options.bag);
    await page.check('#bag-clock');
    await until('the /clock publisher', () => window.colconWasm.bag.player.clock !== null);
    await page.click('#bag-play');
    await until(`a line matching ${options.until}`, ([id, re]) => window.colconWasm.session.processes.get(id).log.some((e) => new RegExp(re).test(e.text)), [node, options.until], 60000);
    out.logs.node = await logsOf(node);
  } else {
    const listener = await page.evaluate(() => window.colconWasm.session.startProcess('demo_nodes', 'listener', []).id);
    await until('the listener', (id) => window.colconWasm.session.graph.topics.some((x) => x.name === '/chatter' && x.subscribers > 0), listener);
    await dropBag(options.bag);
    out.info = await page.evaluate(() => window.colconWasm.bag.player.info);
    out.chip = await page.textContent('#bag-state');
    for (let i = 1; i <= 3; i++) {
      await page.click('#bag-step');
      await until(`step ${i} to be heard`, ([id, n]) => window.colconWasm.session.processes.get(id).log.filter((e) => e.text.includes('I heard: [played')).length >= n, [listener, i]);
    }
    await page.waitForTimeout(500);
    out.marks.afterSteps = await heard(listener);
    // seek with the bar, as a user drags it, then play
    await page.$eval('#bag-seek', (el, ms) => { el.value = String(ms); el.dispatchEvent(new Event('change')); }, options.seekMs);
    await page.waitForTimeout(300);
    await page.click('#bag-play');
    await until('two more messages', ([id, n]) => window.colconWasm.session.processes.get(id).log.filter((e) => e.text.includes('I heard: [played')).length >= n, [listener, 5]);
    await page.click('#bag-play');
    await until('the pause', () => window.colconWasm.bag.player.state.state === 'paused');
    await page.waitForTimeout(400); // what serve sent before it paused
    out.marks.afterPause = await heard(listener);
    await page.waitForTimeout(1500);
    out.marks.afterPauseWait = await heard(listener);
    await page.click('#bag-play');
    await until('the end of the bag', () => window.colconWasm.bag.player.state.state === 'ended', null, 30000);
    await page.waitForTimeout(500);
    out.marks.end = await heard(listener);
    out.logs.listener = await logsOf(listener);
    out.state = await page.evaluate(() => window.colconWasm.bag.player.state);
  }
  out.ok = true;
} catch (e) {
  out.error = String(e && e.stack ? e.stack : e);
  if (page) {
    out.chip = await page.textContent('#bag-state').catch(() => null);
    out.seen = await page.evaluate(() => {
      const s = window.colconWasm.session;
      return {
        processes: [...s.processes.values()].map((p) => ({ name: p.exe, state: p.state, log: p.log.slice(-8).map((x) => x.text) })),
        topics: s.graph.topics.map((t) => `${t.name} ${t.publishers}/${t.subscribers}`),
      };
    }).catch((x) => String(x));
  }
} finally {
  await browser.close();
  console.log(JSON.stringify(out));
}
