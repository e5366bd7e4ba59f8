// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Record and replay in the header: Record / Stop (the bag downloads when it
// stops), Play bag… (or drop a .mcap anywhere on the page), and, once a bag
// is open, play/pause, step, a seek bar, the rate and /clock (bag.mjs does the work).

import { h } from '../dom.mjs';
import { PagePlayer, PageRecorder } from '../bag.mjs';

function download(url, name) {
  const a = h('a', { href: url, download: name, hidden: true });
  document.body.append(a);
  a.click();
  a.remove();
}

const seconds = (ms) => `${(ms / 1000).toFixed(1)} s`;

/** The record and replay controls; `window.colconWasm.bag` holds the recorder and player. */
export function bagControl(session) {
  const recorder = new PageRecorder(session);
  const record = h('button#bag-record', { title: 'record every topic into a rosbag2 MCAP file' }, '● Record');
  const chip = h('span.chip#bag-state', {}, h('span.dot'), 'bag: idle');
  const file = h('input#bag-file', { type: 'file', accept: '.mcap', hidden: true });
  const open = h('button#bag-open', { title: 'play a rosbag2 MCAP bag into these nodes (or drop it on the page)' }, 'Play bag…');
  const play = h('button#bag-play', {}, '▶');
  const step = h('button#bag-step', { title: 'send the next message' }, 'Step');
  const seek = h('input#bag-seek', { type: 'range', min: 0, max: 0, step: 1, value: 0 });
  const rate = h('select#bag-rate', {}, ...['0.25', '0.5', '1', '2', '4', '10'].map((r) => h('option', { value: r, selected: r === '1' }, `${r}×`)));
  const position = h('span#bag-position', {}, '');
  const clockBox = h('input#bag-clock', { type: 'checkbox', title: 'publish /clock with the bag time (for use_sim_time nodes)' });
  const clockLabel = h('label', {}, clockBox, '/clock');
  const bar = h('span.bag-player#bag-player', { hidden: true }, play, step, seek, position, rate, clockLabel);
  const say = (text, state) => {
    chip.lastChild.textContent = `bag: ${text}`;
    chip.classList.toggle('ok', state === 'ok');
    chip.classList.toggle('bad', state === 'bad');
  };
  const player = new PagePlayer(session, (p) => {
    const s = p.state;
    play.textContent = s.state === 'playing' ? '⏸' : '▶';
    if (!seek.matches(':active')) seek.value = String(Math.round(s.position_ms));
    position.textContent = p.info ? `${seconds(s.position_ms)} / ${seconds(p.info.duration_ms)}, ${p.published} sent` : '';
    if (p.error) say(p.error, 'bad');
    else if (p.info) say(`${p.info.name}: ${s.state}`, s.state === 'playing' ? 'ok' : undefined);
  });
  window.colconWasm = Object.assign(window.colconWasm || {}, { bag: { recorder, player } });

  let ticking = null;
  record.onclick = async () => {
    record.disabled = true;
    try {
      if (!recorder.recording) {
        await recorder.start();
        record.textContent = '■ Stop';
        say('recording', 'ok');
        ticking = setInterval(() => say(`recording, ${recorder.messages} messages`, 'ok'), 500);
      } else {
        clearInterval(ticking);
        const result = await recorder.stop();
        record.textContent = '● Record';
        const lost = result.dropped ? `, ${result.dropped} dropped (serve did not keep up)` : '';
        say(result.error || `${result.name}: ${result.messages} messages${lost}`, result.error || result.dropped ? 'bad' : undefined);
        download(result.url, result.name);
      }
    } catch (e) {
      say(e.message, 'bad');
    } finally {
      record.disabled = false;
    }
  };
  const openBag = async (f) => {
    say(`uploading ${f.name}…`);
    try {
      const info = await player.open(f);
      seek.max = String(Math.ceil(info.duration_ms));
      bar.hidden = false;
      const skipped = info.skipped.map((s) => `${s.topic} (${s.why})`).join('; ');
      say(info.error || `${info.name}: ${info.count} messages on ${info.topics.length} topics${skipped ? `; skipped ${skipped}` : ''}`,
        info.error || skipped ? 'bad' : undefined);
    } catch (e) {
      say(e.message, 'bad');
    }
  };
  open.onclick = () => file.click();
  file.onchange = () => { if (file.files[0]) openBag(file.files[0]); };
  play.onclick = () => (player.state.state === 'playing' ? player.pause() : player.play());
  step.onclick = () => player.step();
  seek.onchange = () => player.seek(Number(seek.value));
  rate.onchange = () => player.setRate(Number(rate.value));
  clockBox.onchange = () => player.setClock(clockBox.checked ? 40 : 0).catch((e) => say(e.message, 'bad'));
  document.addEventListener('dragover', (e) => { e.preventDefault(); });
  document.addEventListener('drop', (e) => {
    const f = [...(e.dataTransfer?.files || [])].find((x) => x.name.endsWith('.mcap'));
    if (!f) return;
    e.preventDefault();
    openBag(f);
  });
  return h('span.bag', {}, record, open, file, bar, chip);
}
