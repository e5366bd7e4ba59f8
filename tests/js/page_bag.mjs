// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The launcher page's record and replay, as a user does them, in Debian's
// Chromium (playwright-core; never a downloaded browser). Prints one JSON line.
//
//   node page_bag.mjs '<json: {url, chromium, mode, ...}>'
//
// mode 'record' {out, recordMs?, blobOut?}: starts the demo talker and camera, clicks
//   Record, waits `recordMs` (4000), clicks Stop and saves the download to `out`
//   (with `blobOut`, also the bytes the page's recorder URL gives, fetched in the page):
//   {ok, error, logs: {talker}, chip, result, rec: {first, last, after}} (rec: the
//   header's REC chip as it records and after the stop)
// mode 'play' {bag, listener?}: starts the demo listener (or, with listener 'autorun',
//   takes the one the page started), drops `bag` on the page, then
//   Step ×3, seek to `seekMs`, Play, Pause, Play to the end:
//   {ok, error, logs: {listener}, marks: {afterSteps, afterPause, afterPauseWait, end}, info,
//    bar: {opened, stepped, playing, paused, ended}} (bar: the playback bar at each of those)
// With `screenshots` (a folder), a screenshot of the page while it records or plays.
// mode 'clock' {bag, pkg, exe, args, until}: starts pkg/exe args, drops `bag`, ticks
//   /clock, plays, and waits for a log line matching `until`: {ok, error, logs: {node}}
// mode 'refuse' {bags: [path]}: drops each bag, waits for the bar to say it is bad:
//   {ok, error, refused: [{status, playerHidden, state}]}

import fs from 'node:fs';
import path from 'node:path';
import { launchChromium } from './chromium.mjs';

const options = JSON.parse(process.argv[2]);
const browser = await launchChromium(options.chromium);
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
/** Drop a bag on the page, as a user drags it from the file manager (`opens`: wait until it is open). */
async function dropBag(file, opens = true) {
  const bytes = fs.readFileSync(file).toString('base64');
  const transfer = await page.evaluateHandle(([b64, name]) => {
    const raw = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const dt = new DataTransfer();
    dt.items.add(new File([raw], name));
    return dt;
  }, [bytes, path.basename(file)]);
  await page.dispatchEvent('body', 'drop', { dataTransfer: transfer });
  if (opens) await until('the bag to open', () => !document.querySelector('#bag-player').hidden);
}
/** The playback bar as the user sees it: the play button's state and the position field. */
const barLooks = () => page.evaluate(() => {
  const position = document.querySelector('#bag-position');
  const range = document.createRange();
  range.selectNodeContents(position);
  const tops = new Set([...range.getClientRects()].map((r) => Math.round(r.top)));
  const button = document.querySelector('#bag-play');
  return {
    state: button.dataset.state, icon: button.dataset.icon, iconDrawn: !!button.querySelector('svg path'), label: document.querySelector('#bag-play-state').textContent,
    position: position.textContent, positionLines: tops.size, positionWidth: position.getBoundingClientRect().width,
    positionClipped: position.scrollWidth > position.clientWidth,
    barHeight: document.querySelector('#playback-bar').getBoundingClientRect().height,
    barOverflow: document.querySelector('#playback-bar').scrollWidth - document.querySelector('#playback-bar').clientWidth,
    pageOverflow: document.documentElement.scrollWidth - window.innerWidth,
    inHeader: !!document.querySelector('header.top #bag-play, header.top #bag-seek'),
  };
});
/** The header's REC chip: shown, its text, inside the window. */
const recChip = () => page.evaluate(() => {
  const chip = document.querySelector('header.top #rec-chip');
  if (!chip) return null;
  const r = chip.getBoundingClientRect();
  return { shown: !chip.hidden && r.width > 0, text: chip.textContent, inWindow: r.right <= window.innerWidth,
    background: getComputedStyle(chip).backgroundColor };
});
const shoot = async (name) => {
  if (!options.screenshots) return;
  fs.mkdirSync(options.screenshots, { recursive: true });
  await page.screenshot({ path: path.join(options.screenshots, `${name}.png`) });
};
const heard = (id) => logsOf(id).then((lines) => lines.filter((l) => l.includes('I heard: [played')).map((l) => Number(/played (\d+)/.exec(l)[1])));

try {
  const context = await browser.newContext({ acceptDownloads: true, viewport: { width: 1024, height: 800 } });
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
    out.rec = { first: await recChip() };
    await page.waitForTimeout(options.recordMs || 4000);
    out.rec.last = await recChip();
    await shoot('recording');
    const downloading = page.waitForEvent('download', { timeout: 30000 });
    await page.click('#bag-record');
    const download = await downloading;
    await download.saveAs(options.out);
    out.suggested = download.suggestedFilename();
    out.logs.talker = await logsOf(talker);
    out.chip = await page.textContent('#bag-state');
    out.rec.after = await recChip();
    if (options.blobOut) {
      out.blobUrl = await page.evaluate(() => window.colconWasm.bag.recorder.url);
      const b64 = await page.evaluate(async (url) => {
        const bytes = new Uint8Array(await (await fetch(url)).arrayBuffer());
        let text = '';
        for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
        return btoa(text);
      }, out.blobUrl);
      fs.writeFileSync(options.blobOut, Buffer.from(b64, 'base64'));
    }
  } else if (options.mode === 'refuse') {
    out.refused = [];
    for (const bag of options.bags) {
      await page.evaluate(() => { document.querySelector('#bag-state').textContent = ''; });
      await dropBag(bag, false);
      await until(`the refusal of ${bag}`, () => document.querySelector('#bag-state').classList.contains('bad'));
      out.refused.push(await page.evaluate(() => ({
        status: document.querySelector('#bag-state').textContent,
        playerHidden: document.querySelector('#bag-player').hidden,
        state: window.colconWasm.bag.player.state.state,
      })));
      await page.evaluate(() => document.querySelector('#bag-state').classList.remove('bad'));
    }
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
    const listener = options.listener === 'autorun'
      ? await (async () => {
        await until('the page to start its listener', () => [...window.colconWasm.session.processes.values()].some((p) => p.exe === 'listener'));
        return page.evaluate(() => [...window.colconWasm.session.processes.values()].find((p) => p.exe === 'listener').id);
      })()
      : await page.evaluate(() => window.colconWasm.session.startProcess('demo_nodes', 'listener', []).id);
    await until('the listener', (id) => window.colconWasm.session.graph.topics.some((x) => x.name === '/chatter' && x.subscribers > 0), listener);
    await dropBag(options.bag);
    out.info = await page.evaluate(() => window.colconWasm.bag.player.info);
    out.chip = await page.textContent('#bag-state');
    out.bar = { opened: await barLooks() };
    for (let i = 1; i <= 3; i++) {
      await page.click('#bag-step');
      await until(`step ${i} to be heard`, ([id, n]) => window.colconWasm.session.processes.get(id).log.filter((e) => e.text.includes('I heard: [played')).length >= n, [listener, i]);
    }
    await page.waitForTimeout(500);
    out.marks.afterSteps = await heard(listener);
    out.bar.stepped = await barLooks();
    // seek with the bar, as a user drags it, then play
    await page.$eval('#bag-seek', (el, ms) => { el.value = String(ms); el.dispatchEvent(new Event('change')); }, options.seekMs);
    await page.waitForTimeout(300);
    await page.click('#bag-play');
    await until('two more messages', ([id, n]) => window.colconWasm.session.processes.get(id).log.filter((e) => e.text.includes('I heard: [played')).length >= n, [listener, 5]);
    out.bar.playing = await barLooks();
    await shoot('playing');
    await page.click('#bag-play');
    await until('the pause', () => window.colconWasm.bag.player.state.state === 'paused');
    await page.waitForTimeout(400); // what serve sent before it paused
    out.marks.afterPause = await heard(listener);
    out.bar.paused = await barLooks();
    await page.waitForTimeout(1500);
    out.marks.afterPauseWait = await heard(listener);
    await page.click('#bag-play');
    await until('the end of the bag', () => window.colconWasm.bag.player.state.state === 'ended', null, 30000);
    await page.waitForTimeout(500);
    out.marks.end = await heard(listener);
    out.bar.ended = await barLooks();
    await shoot('ended');
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
