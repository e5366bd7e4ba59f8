// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * bench/transport in Node.js: prints the measurements as one JSON line.
 *
 *   node run_node.mjs WASM_JS_SRC_DIR BENCH_NODE_JS BENCH_NODE_NO_PTHREAD_JS [--quick] [--only=PART,...] [--sab-bus]
 */

import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [srcDir, exe, exeNoPthread, ...flags] = process.argv.slice(2);
const src = pathToFileURL(path.resolve(srcDir)).href + '/';
const { Runtime } = await import(new URL('index.mjs', src).href);
const { ProgramWorker } = await import(new URL('platform.mjs', src).href);
const { runAll } = await import('./bench.mjs');
const only = flags.filter((f) => f.startsWith('--only=')).flatMap((f) => f.slice(7).split(','));
// If a measurement never settles, say so instead of exiting silently (code 13).
const keepAlive = setInterval(() => {}, 1 << 30);
process.on('exit', (code) => {
  if (code === 13) process.stderr.write('run_node.mjs: a measurement never finished\n');
});
const result = await runAll({
  Runtime, ProgramWorker, exe: path.resolve(exe), exeNoPthread: path.resolve(exeNoPthread),
  here: new URL('./', import.meta.url).href,
  log: (m) => process.stderr.write(`[node] ${m}\n`),
  trace: process.env.BENCH_TRACE ? (m) => process.stderr.write(`[trace] ${m}\n`) : undefined,
}, {
  quick: flags.includes('--quick'),
  parts: only.length ? only : undefined,
  wasmMemory: !flags.includes('--sab-bus'),
});
clearInterval(keepAlive);
process.stdout.write(`${JSON.stringify(result)}\n`);
process.exit(0);
