// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Recording a bag: the Record / Stop button of the playback bar (the bag
// downloads when it stops) and the header's red REC chip, with the elapsed
// time, while it records (bag.mjs does the work with serve, bag_local.mjs
// in a page without serve).

import { h } from '../dom.mjs';
import { PageRecorder } from '../bag.mjs';
import { LocalRecorder } from '../bag_local.mjs';

function download(url, name) {
  const a = h('a', { href: url, download: name, hidden: true });
  document.body.append(a);
  a.click();
  a.remove();
}

/** '0:07', '12:30': minutes and seconds since `startedMs` (performance.now()). */
export function elapsed(startedMs, nowMs = performance.now()) {
  const total = Math.max(0, Math.floor((nowMs - startedMs) / 1000));
  return `${Math.floor(total / 60)}:${String(total % 60).padStart(2, '0')}`;
}

/**
 * The recorder's controls: `button` (for the playback bar) and `chip` (for
 * the header); `say(text, state)` reports in the bar's status. With `local`
 * the page builds the file itself (no serve behind it).
 */
export function recordControl(session, say, { local = false } = {}) {
  const recorder = local ? new LocalRecorder(session) : new PageRecorder(session);
  const title = local
    ? `record every topic into a rosbag2 MCAP file built in this page (uncompressed, up to ${recorder.maxBytes / 2 ** 20} MiB)`
    : 'record every topic into a rosbag2 MCAP file';
  const button = h('button#bag-record', { title }, '● Record');
  const time = h('span.rec-time', {}, '0:00');
  const chip = h('span.chip.rec#rec-chip', { hidden: true, title: 'recording every topic' },
    h('span.dot'), 'REC', time);
  let ticking = null;
  let started = 0;
  const tick = () => {
    time.textContent = elapsed(started);
    chip.title = `recording every topic: ${recorder.messages} messages`;
    say(`recording, ${recorder.messages} messages`, 'ok');
  };
  button.onclick = async () => {
    button.disabled = true;
    try {
      if (!recorder.recording) {
        await recorder.start();
        started = performance.now();
        button.textContent = '■ Stop';
        button.classList.add('recording');
        chip.hidden = false;
        tick();
        ticking = setInterval(tick, 500);
      } else {
        clearInterval(ticking);
        chip.hidden = true;
        button.classList.remove('recording');
        const result = await recorder.stop();
        button.textContent = '● Record';
        const lost = result.dropped ? `, ${result.dropped} dropped (${result.droppedWhy || 'serve did not keep up'})` : '';
        say(result.error || `${result.name}: ${result.messages} messages${lost}`, result.error || result.dropped ? 'bad' : undefined);
        download(result.url, result.name);
      }
    } catch (e) {
      clearInterval(ticking);
      chip.hidden = !recorder.recording;
      say(e.message, 'bad');
    } finally {
      button.disabled = false;
    }
  };
  return { recorder, button, chip };
}
