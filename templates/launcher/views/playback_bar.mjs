// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The playback bar at the bottom of the main area, as in Foxglove: Record,
// Play bag… (or drop a .mcap anywhere on the page), and once a bag is open
// play/pause (its state shown: playing, paused, ended), step, the position in
// a fixed-width field, a seek bar, the rate and a status line. The REC chip
// and the /clock box go in the header (`headerItems`). bag.mjs does the work
// with serve; in a page without serve (`workspace.bag.local`, an export)
// bag_local.mjs reads, plays and records the bags in the page.

import { h } from '../dom.mjs';
import { PagePlayer } from '../bag.mjs';
import { LocalBagSource } from '../bag_local.mjs';
import { recordControl } from './bag.mjs';

const seconds = (ms) => `${(Math.max(0, ms) / 1000).toFixed(1)} s`;

/** The play button's icons, drawn (a font may lack ⏸): SVG path data in a 16×16 box. */
const ICONS = {
  play: 'M4 2.5v11l9-5.5z',
  pause: 'M3.5 2.5h3v11h-3zM9.5 2.5h3v11h-3z',
  replay: 'M8 3a5 5 0 1 1-4.9 6h1.6A3.5 3.5 0 1 0 8 4.5V7L4.5 3.75 8 .5z',
};

function icon(name) {
  const ns = 'http://www.w3.org/2000/svg';
  const svg = document.createElementNS(ns, 'svg');
  svg.setAttribute('viewBox', '0 0 16 16');
  svg.setAttribute('aria-hidden', 'true');
  const path = document.createElementNS(ns, 'path');
  path.setAttribute('d', ICONS[name]);
  path.setAttribute('fill', 'currentColor');
  svg.append(path);
  return svg;
}

/** What the play button shows and does in each state of the player. */
const PLAY = {
  closed: { icon: 'play', label: '', title: 'open a bag first' },
  paused: { icon: 'play', label: 'paused', title: 'play' },
  playing: { icon: 'pause', label: 'playing', title: 'pause' },
  ended: { icon: 'replay', label: 'ended', title: 'play again from the start' },
};

/** The bar; `window.colconWasm.bag` holds the recorder and the player. */
export class PlaybackBar {
  /**
   * @param {string} [problem] why bags cannot be recorded or played here
   * (`session.workspace.bag.local`: the page does both itself, without serve)
   */
  constructor(session, problem = null) {
    const local = !problem && !!session.workspace?.bag?.local;
    this.local = local;
    this.status = h('span.bag-status#bag-state', {}, 'no bag open');
    const say = (text, state, more = '') => {
      this.status.textContent = text;
      this.status.title = more ? `${text}\n${more}` : text;
      for (const s of ['ok', 'warn', 'bad']) this.status.classList.toggle(s, state === s);
    };
    this.say = say;
    const record = recordControl(session, say, { local });
    const file = h('input#bag-file', { type: 'file', accept: '.mcap', hidden: true });
    const open = h('button#bag-open', { title: 'play a rosbag2 MCAP bag into these nodes (or drop it on the page)' }, 'Play bag…');
    this.play = h('button.play#bag-play', { dataset: { state: 'closed', icon: 'play' } }, icon('play'));
    this.playState = h('span.play-state#bag-play-state', {}, '');
    const step = h('button#bag-step', { title: 'send the next message' }, 'Step');
    this.position = h('span.position#bag-position', { title: 'position / duration' }, '');
    this.seek = h('input#bag-seek', { type: 'range', min: 0, max: 0, step: 1, value: 0, 'aria-label': 'position in the bag' });
    const rate = h('select#bag-rate', { title: 'playback rate' },
      ...['0.25', '0.5', '1', '2', '4', '10'].map((r) => h('option', { value: r, selected: r === '1' }, `${r}×`)));
    this.controls = h('span.bag-player#bag-player', { hidden: true },
      this.play, this.playState, step, this.position, this.seek, rate);
    this.hint = h('span.hint', {}, local
      ? 'drop a .mcap (uncompressed chunks) on the page to replay it into these nodes'
      : 'drop a .mcap on the page to replay it into these nodes');
    const clock = h('input#bag-clock', { type: 'checkbox' });
    this.clock = h('label.chip.clock#bag-clock-label', {
      hidden: true, title: 'publish /clock with the bag time (for use_sim_time nodes)',
    }, clock, '/clock');
    this.element = h('div.playback#playback-bar', { dataset: { state: 'closed' } },
      record.button, open, file, h('span.sep'), this.controls, this.hint, this.status);
    if (problem) {
      record.button.disabled = true;
      open.disabled = true;
      this.hint.textContent = `Off: ${problem}.`;
      this.hint.classList.add('reason');
    }
    /** For the header: the REC chip (while recording) and the /clock box (once a bag is open). */
    this.headerItems = [record.chip, this.clock];

    const player = new PagePlayer(session, (p) => this.render(p),
      local ? { makeSource: (hooks) => new LocalBagSource(session, hooks) } : {});
    this.player = player;
    window.colconWasm = Object.assign(window.colconWasm || {}, { bag: { recorder: record.recorder, player } });
    open.onclick = () => file.click();
    file.onchange = () => { if (file.files[0]) this.open(file.files[0]); };
    this.play.onclick = () => (player.state.state === 'playing' ? player.pause() : player.play());
    step.onclick = () => player.step();
    this.seek.onchange = () => player.seek(Number(this.seek.value));
    rate.onchange = () => player.setRate(Number(rate.value));
    clock.onchange = () => player.setClock(clock.checked ? 40 : 0).catch((e) => say(e.message, 'bad'));
    document.addEventListener('dragover', (e) => { e.preventDefault(); });
    document.addEventListener('drop', (e) => {
      const f = [...(e.dataTransfer?.files || [])].find((x) => x.name.endsWith('.mcap'));
      if (!f || problem) return;
      e.preventDefault();
      this.open(f);
    });
  }

  async open(f) {
    this.say(`${this.local ? 'reading' : 'uploading'} ${f.name}…`);
    try {
      const info = await this.player.open(f);
      const duration = seconds(info.duration_ms);
      this.seek.max = String(Math.ceil(info.duration_ms));
      // as wide as its longest text, so that it does not move while playing
      this.position.style.width = `${`${duration} / ${duration}`.length}ch`;
      this.controls.hidden = false;
      this.clock.hidden = false;
      this.hint.hidden = true;
      this.render(this.player);
      if (info.error) this.say(info.error, 'bad');
      else this.say(this.summary(this.player), info.skipped.length ? 'warn' : undefined, PlaybackBar.skippedText(info));
    } catch (e) {
      // nothing is open: the bar is as before any bag, with why in its status
      this.controls.hidden = true;
      this.clock.hidden = true;
      this.hint.hidden = false;
      this.render(this.player);
      this.say(e.message, 'bad');
    }
  }

  /**
   * `name: 20 messages on 1 topic`, then `name: 5/20 sent`; with `, 1 topic
   * skipped` (a warning) when the page cannot play some: they and why are in
   * the tooltip.
   */
  summary(p) {
    const { info } = p;
    const plural = (n, word) => `${n} ${word}${n === 1 ? '' : 's'}`;
    const sent = p.state.state === 'paused' && p.published === 0
      ? `${plural(info.count, 'message')} on ${plural(info.topics.length, 'topic')}`
      : `${p.published}/${info.count} sent`;
    const skipped = info.skipped.length ? `, ${plural(info.skipped.length, 'topic')} skipped` : '';
    return `${info.name}: ${sent}${skipped}`;
  }

  /** The skipped topics and why, for the status' tooltip. */
  static skippedText(info) {
    return info.skipped.map((s) => `skipped ${s.topic}: ${s.why}`).join('\n');
  }

  render(p) {
    const s = p.state;
    const look = PLAY[s.state] || PLAY.paused;
    this.element.dataset.state = s.state;
    this.play.dataset.state = s.state;
    if (this.play.dataset.icon !== look.icon) {
      this.play.dataset.icon = look.icon;
      this.play.replaceChildren(icon(look.icon));
    }
    this.play.title = look.title;
    this.play.setAttribute('aria-label', `${look.title} (${look.label || 'no bag'})`);
    this.playState.textContent = look.label;
    if (!this.seek.matches(':active')) this.seek.value = String(Math.round(s.position_ms));
    if (!p.info) return;
    const end = p.info.duration_ms;
    this.position.textContent = `${seconds(Math.min(s.position_ms, end))} / ${seconds(end)}`;
    if (p.error) this.say(p.error, 'bad');
    else {
      this.say(this.summary(p), p.info.skipped.length ? 'warn' : (s.state === 'playing' ? 'ok' : undefined),
        PlaybackBar.skippedText(p.info));
    }
  }
}
