// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The first script of an exported page (colcon-wasm export inlines it into
// index.html). A static host sends no cross-origin isolation headers: before
// the page loads a single module or program, this registers the site's
// service worker (coi_sw.js), which adds them, and reloads once under it.
// Only then it preloads the page's modules and programs and starts the page
// (app.mjs), so that a first visit fetches each file once, through the
// worker (its .gz, kept under its hash). Why isolation is missing, if it is,
// is left in window.colconWasmIsolation for the page to say.
(async () => {
  const boot = JSON.parse(document.getElementById('boot').textContent);
  const key = 'colcon-wasm:isolating';
  let problem = null;
  if (!window.crossOriginIsolated) {
    if (!('serviceWorker' in navigator) || !window.isSecureContext) {
      problem = 'this browser gives the page no service worker (it needs https:// or '
        + 'http://localhost), and the host sends no isolation headers';
    } else if (sessionStorage.getItem(key) === location.href) {
      problem = 'the page is not isolated although the site\'s service worker (coi_sw.js) '
        + 'runs: the browser may block service workers for this site';
    } else {
      try {
        await navigator.serviceWorker.register(new URL('coi_sw.js', document.baseURI));
        await navigator.serviceWorker.ready;
        sessionStorage.setItem(key, location.href);
        location.reload();
        return;
      } catch (e) {
        problem = `the site's service worker (coi_sw.js) did not start: ${e && e.message ? e.message : e}`;
      }
    }
  }
  sessionStorage.removeItem(key);
  window.colconWasmIsolation = problem;
  const link = (rel, href, fetchLike) => {
    const element = Object.assign(document.createElement('link'), { rel, href });
    if (fetchLike) Object.assign(element, { as: 'fetch', crossOrigin: 'anonymous' });
    document.head.append(element);
  };
  for (const href of boot.modules) link('modulepreload', href, false);
  for (const href of boot.preload) link('preload', href, true);
  document.head.append(Object.assign(document.createElement('script'), { type: 'module', src: boot.app }));
})();
