// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The connections panel of the sidebar: a collapsible section with the
// rosbridge and Zenoh fields (bridge.mjs, zenoh.mjs). Closed, its title line
// still shows each connection's state; it opens by itself when a connection
// starts (`?rosbridge=`, `?zenoh=`, serve --rosbridge).

import { h } from '../dom.mjs';
import { bridgeControl } from './bridge.mjs';
import { zenohControl } from './zenoh.mjs';

export class ConnectionsPanel {
  constructor(session, workspace) {
    const rosbridge = h('span.conn-dot#rosbridge-dot', { title: 'rosbridge: off' });
    const zenoh = h('span.conn-dot#zenoh-dot', { title: 'zenoh: off' });
    this.element = h('details.side-section.connections#connections', {},
      h('summary', {}, h('h2', {}, 'Connections'), h('span.conn-summary', {}, rosbridge, 'rosbridge', zenoh, 'Zenoh')),
      bridgeControl(session), zenohControl(session, workspace));
    const show = (dot, name, link, connected) => {
      dot.dataset.state = link ? (connected ? 'on' : 'trying') : 'off';
      dot.title = `${name}: ${link ? link.state : 'off'}`;
      // open once when a connection starts; the user may close it again
      if (link && !dot.linked) this.element.open = true;
      dot.linked = Boolean(link);
    };
    // opened at the foot of a long sidebar: scroll it into view
    this.element.addEventListener('toggle', () => {
      if (this.element.open) this.element.scrollIntoView({ block: 'nearest' });
    });
    session.on('bridge', (b) => show(rosbridge, 'rosbridge', b, b && b.state === 'connected'));
    session.on('zenoh', (g) => show(zenoh, 'zenoh', g, g && g.state === 'connected'));
  }
}
