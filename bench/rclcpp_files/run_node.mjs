// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * bench/rclcpp in Node.js: prints the results as one JSON line.
 *
 *   node run_node.mjs <wasm_js runtime.mjs> <probe.js> <bench_node.js> [--quick]
 */

import process from 'node:process';
import { pathToFileURL } from 'node:url';

import { runAll } from './bench.mjs';

const [runtime, probe, core, ...rest] = process.argv.slice(2);
const { Runtime } = await import(pathToFileURL(runtime).href);
const result = await runAll({ Runtime, probe, core }, { quick: rest.includes('--quick') });
process.stdout.write(JSON.stringify(result) + '\n', () => process.exit(0));
