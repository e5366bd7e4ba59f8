// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Run a scenario (see web/scenario.mjs) in Node.js and print its report as JSON.
 *
 *   node run_scenario.mjs <wasm_js runtime.mjs> <scenario.json>
 *
 * Exits 0 when the report was written (whatever the scenario's outcome).
 */

import fs from 'node:fs';
import process from 'node:process';
import { pathToFileURL } from 'node:url';

import { runScenario } from './web/scenario.mjs';

const [runtimePath, scenarioPath] = process.argv.slice(2);
if (!runtimePath || !scenarioPath) {
  process.stderr.write('usage: node run_scenario.mjs <wasm_js runtime.mjs> <scenario.json>\n');
  process.exit(2);
}
const { Runtime } = await import(pathToFileURL(runtimePath).href);
const scenario = JSON.parse(fs.readFileSync(scenarioPath, 'utf8'));
const report = await runScenario(Runtime, scenario);
// Let the (possibly large) report drain to the pipe before Node.js exits.
process.stdout.write(JSON.stringify(report) + '\n', () => process.exit(0));
