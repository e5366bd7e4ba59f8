// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The page's URLs of the site's files. Under `colcon-wasm serve` the
// workspace names them from the server's root (`/ws/…`); an exported site
// names them relative to its page (`ws/…`), so that it works under any
// sub-path (`--base-url`, a `<base href>` in the page). Both resolve against
// the page's base URL here, to the absolute URL a worker needs (a worker
// resolves a relative URL against its own script).

/**
 * The absolute URL of a file of the site.
 * @param {string} path a path from the workspace (`/ws/…` or `ws/…`), or a page-relative one
 * @returns {string}
 */
export function siteUrl(path) {
  return new URL(path, document.baseURI).href;
}
