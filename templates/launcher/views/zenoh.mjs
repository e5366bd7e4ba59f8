// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The Zenoh connect field of the connections panel (connections.mjs): a
// router endpoint (ws/HOST:PORT), Connect / Disconnect, and the gateway's
// state (what `?zenoh=ws/...` starts too). Without the zenoh_wasm_gateway
// package in the install space the field is off and says why, under it.

import { h } from '../dom.mjs';

const UNAVAILABLE = 'the install space has no zenoh_wasm_gateway: build zenoh-pico in the workspace (docs/zenoh.md)';

export function zenohControl(session, workspace) {
  const available = Boolean(workspace.zenoh);
  const input = h('input#zenoh-endpoint', {
    type: 'text', placeholder: 'ws/robot:7447', disabled: !available, 'aria-label': 'Zenoh router endpoint', spellcheck: false,
    title: available ? 'a Zenoh router (its WebSocket listener) to join the ROS 2 graph of rmw_zenoh nodes' : UNAVAILABLE,
  });
  const button = h('button#zenoh-connect', { disabled: !available, title: available ? null : UNAVAILABLE }, 'Connect');
  const chip = h('span.chip#zenoh-state', { title: 'zenoh' }, h('span.dot'), 'zenoh: off');
  const render = () => {
    const g = session.zenoh;
    const state = g ? g.state : 'off';
    const lost = g && g.counters.lost ? `, ${g.counters.lost} lost` : '';
    chip.lastChild.textContent = g ? `zenoh: ${state}${lost}` : 'zenoh: off';
    chip.title = g ? `${g.endpoint}: ${JSON.stringify(g.status())}` : 'zenoh';
    chip.classList.toggle('ok', state === 'connected');
    chip.classList.toggle('bad', state === 'retrying' || state === 'reconnecting');
    button.textContent = g ? 'Disconnect' : 'Connect';
    if (g && !input.value) input.value = g.endpoint;
  };
  button.onclick = async () => {
    if (session.zenoh) await session.disconnectZenoh();
    else if (input.value.trim()) await session.connectZenoh(input.value.trim()).catch((e) => { chip.title = e.message; chip.lastChild.textContent = 'zenoh: error'; });
    render();
  };
  input.onkeydown = (e) => { if (e.key === 'Enter') button.onclick(); };
  session.on('zenoh', render);
  render();
  return h('div.connection.zenoh', {},
    h('div.connection-head', {}, chip),
    h('div.connection-row', {}, input, button),
    available
      ? h('div.hint', {}, 'joins the ROS 2 graph of rmw_zenoh nodes through a router\'s WebSocket listener (ws/HOST:PORT)')
      : h('div.reason#zenoh-reason', {}, `Off: ${UNAVAILABLE}.`));
}
