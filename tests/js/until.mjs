// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A bounded wait of the Node scripts of the tests and benchmarks.
 * @param {string} what named in the error
 * @param {function(): *} test polled every 20 ms until it returns something truthy
 * @param {number} [ms=20000]
 * @returns {Promise<*>} what `test` returned
 */
export async function until(what, test, ms = 20000) {
  const end = Date.now() + ms;
  while (Date.now() < end) {
    const v = test();
    if (v) return v;
    await new Promise((r) => setTimeout(r, 20));
  }
  throw new Error(`waited ${ms} ms for ${what}`);
}
