// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// Debian's Chromium, headless, for the page drivers of tests/js and bench/:
// through playwright-core, which downloads no browser. One place for the
// flags: no GPU (WebGL is SwiftShader's), no QUIC, no background traffic.

import { chromium } from 'playwright-core';

/** The flags every driver starts Chromium with. */
export const HEADLESS_ARGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic',
  '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'];

/**
 * Start Chromium with a fresh temporary profile.
 * @param {string} executablePath /usr/bin/chromium (the drivers' `chromium` option)
 * @param {object} [options] more of playwright's launch options
 */
export function launchChromium(executablePath, options = {}) {
  return chromium.launch({ ...options, executablePath, args: [...HEADLESS_ARGS, ...(options.args || [])] });
}

/**
 * Start Chromium with a profile of its own (a folder it keeps between pages: caches,
 * service workers, localStorage); returns playwright's persistent context.
 * @param {string} executablePath
 * @param {string} userDataDir the profile's folder
 * @param {object} [options] more of playwright's context options (viewport, ...)
 */
export function launchChromiumProfile(executablePath, userDataDir, options = {}) {
  return chromium.launchPersistentContext(userDataDir, {
    ...options, executablePath, args: [...HEADLESS_ARGS, ...(options.args || [])],
  });
}
