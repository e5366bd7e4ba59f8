// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Run core scenarios under Node.js and print one JSON result per line.
 *
 *   node run_scenario.mjs WASM_JS_SRC_DIR CORE_NODE_JS SCENARIO...
 */

import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [srcDir, exe, ...names] = process.argv.slice(2);
if (!srcDir || !exe || !names.length) {
  process.stderr.write('usage: node run_scenario.mjs WASM_JS_SRC_DIR CORE_NODE_JS SCENARIO...\n');
  process.exit(2);
}
const { Runtime } = await import(pathToFileURL(path.join(srcDir, 'index.mjs')).href);
const scenarios = await import('./scenarios.mjs');
for (const name of names) {
  const r = await scenarios.run(name, { Runtime, exe: path.resolve(exe) });
  process.stdout.write(`${JSON.stringify({ scenario: name, ...r })}\n`);
}
process.exit(0);
