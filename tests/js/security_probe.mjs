// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// What a web page can reach of colcon-wasm's listeners from a browser
// (tests/test_security.py, docs/security.md). Headless Chromium, one page.
//
//   node security_probe.mjs '<json>'
//
// mode 'hostile': {chromium, page: URL of a page of another origin, probes: [{name, kind, url,
//   protocols?}]}: from that page, each probe is tried; kind 'fetch' (a CORS fetch: 'read' when
//   the page could read the body, else 'refused'), 'no-cors' ('read', 'opaque' or 'refused'),
//   'ws' (a WebSocket: 'open' when it opened, else 'refused'). Prints {ok, results: {name: ...}}.
//
// mode 'sw': {chromium, site: URL of an exported site, outside: URL of a page of the same
//   origin outside the site's folder, foreign: URL of another origin}: waits until the site's
//   page is isolated under its service worker, then reports its registration (scope, script),
//   the caches and their keys, before and after a fetch of the foreign URL and one of a site
//   file with a query; then opens `outside` and reports whether a service worker controls it.

import { launchChromium } from './chromium.mjs';

const options = JSON.parse(process.argv[2]);
const browser = await launchChromium(options.chromium);
const out = { ok: false };

async function cacheState(page) {
  return page.evaluate(async () => {
    const names = await caches.keys();
    const keys = {};
    for (const name of names) keys[name] = (await (await caches.open(name)).keys()).map((r) => r.url);
    return { names, keys };
  });
}

try {
  const page = await browser.newPage();
  if (options.mode === 'hostile') {
    await page.goto(options.page);
    out.origin = await page.evaluate(() => location.origin);
    out.results = await page.evaluate(async (probes) => {
      const results = {};
      const ws = (url, protocols) => new Promise((resolve) => {
        let socket;
        try {
          socket = protocols ? new WebSocket(url, protocols) : new WebSocket(url);
        } catch (e) {
          resolve(`refused (${e.message})`);
          return;
        }
        const timer = setTimeout(() => { socket.close(); resolve('refused (no answer in 10 s)'); }, 10000);
        socket.onopen = () => { clearTimeout(timer); socket.close(); resolve('open'); };
        socket.onerror = () => { clearTimeout(timer); resolve('refused'); };
      });
      for (const probe of probes) {
        if (probe.kind === 'ws') {
          results[probe.name] = await ws(probe.url, probe.protocols);
          continue;
        }
        try {
          const response = await fetch(probe.url, { mode: probe.kind === 'no-cors' ? 'no-cors' : 'cors' });
          if (response.type === 'opaque') results[probe.name] = 'opaque';
          else results[probe.name] = `read ${(await response.text()).length} bytes`;
        } catch (e) {
          results[probe.name] = `refused (${e.message})`;
        }
      }
      return results;
    }, options.probes);
  } else if (options.mode === 'sw') {
    await page.goto(options.site);
    await page.waitForFunction(() => window.crossOriginIsolated && navigator.serviceWorker.controller
      && window.colconWasm && window.colconWasm.session, null, { timeout: 60000 });
    out.registration = await page.evaluate(async () => {
      const registration = await navigator.serviceWorker.getRegistration();
      return { scope: registration.scope, script: navigator.serviceWorker.controller.scriptURL };
    });
    out.before = await cacheState(page);
    out.fetches = await page.evaluate(async ({ foreign }) => {
      const results = {};
      try {
        results.foreign = (await fetch(foreign, { mode: 'no-cors' })).type;
      } catch (e) {
        results.foreign = `refused (${e.message})`;
      }
      const queried = await fetch('launcher/app.mjs?probe=1');
      results.queried = queried.status;
      return results;
    }, { foreign: options.foreign });
    out.after = await cacheState(page);
    await page.goto(options.outside);
    out.outside = await page.evaluate(() => ({
      controlled: !!navigator.serviceWorker.controller, isolated: window.crossOriginIsolated,
    }));
  } else {
    throw new Error(`unknown mode ${options.mode}`);
  }
  out.ok = true;
} catch (e) {
  out.error = String(e && e.stack ? e.stack : e);
}
await browser.close();
process.stdout.write(`${JSON.stringify(out)}\n`);
