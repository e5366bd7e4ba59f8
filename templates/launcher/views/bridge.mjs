// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The rosbridge connect field of the connections panel (connections.mjs): a
// ws:// URL, Connect / Disconnect, and the bridge's state (what
// `?rosbridge=ws://...` starts too).

import { h } from '../dom.mjs';

export function bridgeControl(session) {
  const input = h('input#rosbridge-url', {
    type: 'text', placeholder: 'ws://robot:9090', title: 'a rosbridge v2 server to bridge these nodes to',
    'aria-label': 'rosbridge server URL', spellcheck: false,
  });
  const button = h('button#rosbridge-connect', {}, 'Connect');
  const chip = h('span.chip#rosbridge-state', { title: 'rosbridge' }, h('span.dot'), 'rosbridge: off');
  const render = () => {
    const b = session.bridge;
    const state = b ? b.state : 'off';
    chip.lastChild.textContent = b ? `rosbridge: ${state}${b.counters.lost ? `, ${b.counters.lost} lost` : ''}` : 'rosbridge: off';
    chip.title = b ? `${b.displayUrl}: ${JSON.stringify(b.stats())}` : 'rosbridge';
    chip.classList.toggle('ok', state === 'connected');
    chip.classList.toggle('bad', state === 'disconnected' || state === 'reconnecting');
    button.textContent = b ? 'Disconnect' : 'Connect';
    if (b && !input.value) input.value = b.displayUrl;
  };
  button.onclick = async () => {
    if (session.bridge) await session.disconnectBridge();
    else if (input.value.trim()) await session.connectBridge(input.value.trim()).catch((e) => { chip.title = e.message; });
    render();
  };
  input.onkeydown = (e) => { if (e.key === 'Enter') button.onclick(); };
  session.on('bridge', render);
  render();
  return h('div.connection.rosbridge', {},
    h('div.connection-head', {}, chip),
    h('div.connection-row', {}, input, button),
    h('div.hint', {}, 'bridges these nodes to a rosbridge v2 server (ws://HOST:PORT)'));
}
