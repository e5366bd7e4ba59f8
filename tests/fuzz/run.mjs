// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Run one JS fuzz target (tests/fuzz/targets/NAME.mjs) for a seeded count or
 * a time, or replay its regression inputs:
 *
 *   node tests/fuzz/run.mjs --target cdr --seed 1 --count 2000
 *   node tests/fuzz/run.mjs --target rosbridge --seconds 60 --coverage
 *   node tests/fuzz/run.mjs --target rosbridge --replay tests/fuzz_corpus/rosbridge/regressions
 *   node tests/fuzz/run.mjs --target rosbridge --capture    # (re)write the seed corpus
 *
 * Options: --corpus DIR (default tests/fuzz_corpus/NAME), --findings DIR
 * (where failing inputs are written), --timeout-ms MS (per input, 2000),
 * --check-every N (inputs between two checks that a valid input still
 * works, 50), --types FILE (a types.json for the registry), --schemas FILE
 * (the servers' complete definitions; tests/fuzz/fuzz_types.py writes both).
 *
 * A target's `setup()` returns a harness: `one(bytes)` feeds one input
 * through the entry point the server uses per message and returns the
 * class of what came back (status error, drop, answer); `check()` sends a
 * well-formed request to the same instance and throws unless it gets the
 * right answer. Findings: an exception out of the handler (or uncaught
 * later, or an unhandled rejection), an input that takes longer than the
 * timeout (a watchdog thread kills a stuck event loop and names the
 * input), a failed check (corrupted state). Inputs whose outcome class is
 * new join the corpus (outcome-guided; the count of classes is the
 * "coverage" printed for JS). With --coverage, V8's precise block
 * coverage of the target's source files is printed too.
 *
 * Prints one JSON line at the end: {target, seed, inputs, seconds,
 * classes, checks, findings: [{kind, message, file}], coverage}. Exit
 * status 0 without findings, 1 with.
 */

import { createHash } from 'node:crypto';
import { mkdirSync, mkdtempSync, readdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { Worker } from 'node:worker_threads';

import { nextInput, Random } from './mutate.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const repo = resolve(here, '..', '..');
const MAX_INPUT = 1 << 16;

function parseArgs(argv) {
  const args = { seed: 1, count: null, seconds: null, timeoutMs: 2000, checkEvery: 50, coverage: false };
  for (let i = 0; i < argv.length; i++) {
    const key = argv[i].replace(/^--/, '').replace(/-([a-z])/g, (_, c) => c.toUpperCase());
    if (key === 'coverage' || key === 'capture') args[key] = true;
    else args[key] = argv[++i];
  }
  for (const k of ['seed', 'count', 'seconds', 'timeoutMs', 'checkEvery']) if (args[k] !== null && args[k] !== undefined) args[k] = Number(args[k]);
  if (!args.target) throw new Error('--target NAME is needed');
  return args;
}

/** The files of a corpus folder (not its regressions/), sorted by name. */
export function readCorpus(dir) {
  let names;
  try {
    names = readdirSync(dir).sort();
  } catch {
    return [];
  }
  return names.map((n) => join(dir, n)).filter((p) => statSync(p).isFile()).map((p) => new Uint8Array(readFileSync(p)));
}

/** An outcome as a class: numbers and quoted text folded, so that classes count kinds of answers. */
export function classify(text) {
  return String(text).replace(/"(?:[^"\\]|\\.)*"|'[^']*'/g, 'Q').replace(/\d+/g, 'N').slice(0, 160);
}

/**
 * A watchdog thread: kills the process when the event loop is stuck past the
 * timeout while an input runs (a synchronous loop that never ends); an
 * input whose promises take too long is caught by withTimeout instead.
 */
function startWatchdog(timeoutMs, findingsDir, target) {
  const shared = new SharedArrayBuffer(12 + MAX_INPUT);
  const words = new Int32Array(shared, 0, 3);
  const code = `
    const { workerData } = require('node:worker_threads');
    const fs = require('node:fs');
    const path = require('node:path');
    const crypto = require('node:crypto');
    const words = new Int32Array(workerData.shared, 0, 3);
    const bytes = new Uint8Array(workerData.shared, 12);
    let seen = -1, since = Date.now();
    setInterval(() => {
      // words[0] is the main thread's heartbeat: it stops only when its event loop is stuck
      const n = Atomics.load(words, 0);
      const busy = Atomics.load(words, 1);
      if (n !== seen || !busy) { seen = n; since = Date.now(); return; }
      if (Date.now() - since < workerData.timeoutMs) return;
      const input = Buffer.from(bytes.subarray(0, Atomics.load(words, 2)));
      const file = path.join(workerData.findingsDir, 'hang-' + crypto.createHash('sha1').update(input).digest('hex').slice(0, 12));
      fs.writeFileSync(file, input);
      fs.writeSync(1, JSON.stringify({ target: workerData.target, killed: true, findings: [{ kind: 'hang',
        message: 'one input ran for more than ' + workerData.timeoutMs + ' ms: the event loop was stuck', file }] }) + '\\n');
      process.kill(process.pid, 'SIGKILL');
    }, 50);`;
  const worker = new Worker(code, { eval: true, workerData: { shared, timeoutMs, findingsDir, target } });
  worker.unref();
  setInterval(() => Atomics.add(words, 0, 1), 20).unref();
  return {
    begin(input) {
      const n = Math.min(input.length, MAX_INPUT);
      new Uint8Array(shared, 12, n).set(input.subarray(0, n));
      Atomics.store(words, 2, n);
      Atomics.add(words, 0, 1);
      Atomics.store(words, 1, 1);
    },
    end() {
      Atomics.store(words, 1, 0);
    },
  };
}

function withTimeout(promise, ms, what) {
  let timer;
  const timeout = new Promise((_, reject) => {
    timer = setTimeout(() => reject(Object.assign(new Error(`${what} did not settle within ${ms} ms`), { hang: true })), ms);
  });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

async function startCoverage() {
  const { Session } = await import('node:inspector');
  const session = new Session();
  session.connect();
  const post = (method, params = {}) => new Promise((res, rej) => session.post(method, params, (e, r) => (e ? rej(e) : res(r))));
  await post('Profiler.enable');
  await post('Profiler.startPreciseCoverage', { callCount: true, detailed: true });
  return {
    async take(patterns) {
      const { result } = await post('Profiler.takePreciseCoverage');
      let blocks = 0;
      let covered = 0;
      const files = new Set();
      for (const script of result) {
        if (!patterns.some((p) => script.url.includes(p))) continue;
        files.add(script.url);
        for (const fn of script.functions) {
          for (const range of fn.ranges) {
            blocks++;
            if (range.count > 0) covered++;
          }
        }
      }
      return { unit: 'V8 blocks', blocks, covered, files: files.size };
    },
  };
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  const corpusDir = resolve(args.corpus || join(repo, 'tests', 'fuzz_corpus', args.target));
  const findingsDir = resolve(args.findings || mkdtempSync(join(tmpdir(), `fuzz-${args.target}-`)));
  mkdirSync(findingsDir, { recursive: true });
  const coverage = args.coverage ? await startCoverage() : null;
  const target = await import(pathToFileURL(join(here, 'targets', `${args.target}.mjs`)).href);
  if (args.capture) {
    // write the seed corpus: what the target records of real traffic
    const seeds = await target.capture({ types: args.types, schemas: args.schemas, repo });
    mkdirSync(corpusDir, { recursive: true });
    for (const { name, bytes } of seeds) writeFileSync(join(corpusDir, name), bytes);
    process.stdout.write(`${JSON.stringify({ target: args.target, captured: seeds.length, bytes: seeds.reduce((s, x) => s + x.bytes.length, 0) })}\n`);
    process.exit(0);
  }
  const findings = [];
  let current = new Uint8Array(0);
  const record = (kind, message, input = current) => {
    // one finding per kind of failure (its first line, numbers folded), with a count
    const signature = `${kind} ${classify(String(message).split('\n').slice(0, 2).join(' '))}`;
    const same = findings.find((f) => f.signature === signature);
    if (same) {
      same.count++;
      return;
    }
    const hash = createHash('sha1').update(input).digest('hex').slice(0, 12);
    const file = join(findingsDir, `${kind}-${hash}`);
    writeFileSync(file, input);
    findings.push({ kind, signature, count: 1, message: String(message).slice(0, 1500), file });
  };
  process.on('uncaughtException', (e) => record('exception', `uncaught: ${e && e.stack ? e.stack : e}`));
  process.on('unhandledRejection', (e) => record('exception', `unhandled rejection: ${e && e.stack ? e.stack : e}`));
  const harness = await target.setup({ types: args.types, schemas: args.schemas, repo, finding: (kind, message) => record(kind, message) });
  const watchdog = startWatchdog(args.timeoutMs, findingsDir, args.target);
  const classes = new Map();
  let inputs = 0;
  let checks = 0;
  const started = Date.now();

  const feed = async (input) => {
    current = input;
    watchdog.begin(input);
    let outcome;
    try {
      outcome = await withTimeout(Promise.resolve().then(() => harness.one(input)), args.timeoutMs, 'the input');
    } catch (e) {
      if (e.hang) record('hang', e.message);
      else record('exception', `from the handler: ${e && e.stack ? e.stack : e}`);
      outcome = 'FINDING';
    } finally {
      watchdog.end();
    }
    inputs++;
    const cls = classify(outcome);
    const isNew = !classes.has(cls);
    classes.set(cls, (classes.get(cls) || 0) + 1);
    return isNew;
  };
  const check = async () => {
    checks++;
    watchdog.begin(current);
    try {
      await withTimeout(Promise.resolve().then(() => harness.check()), Math.max(args.timeoutMs, 5000), 'the check after it');
    } catch (e) {
      record('state', `a well-formed input failed after this one: ${e && e.stack ? e.stack : e}`);
    } finally {
      watchdog.end();
    }
  };

  await check(); // the harness works before any malformed input
  if (findings.length) findings[0].message = `the harness failed before fuzzing: ${findings[0].message}`;
  if (args.replay) {
    for (const input of readCorpus(resolve(args.replay))) {
      await feed(input);
      await check();
    }
  } else if (!findings.length) {
    const corpus = readCorpus(corpusDir);
    if (!corpus.length) throw new Error(`no seed corpus in ${corpusDir}`);
    const dec = new TextDecoder();
    const jsonValues = target.options && target.options.json ? corpus.map((c) => { try { return JSON.parse(dec.decode(c)); } catch { return null; } }).filter((v) => v !== null) : [];
    for (const seed of corpus) await feed(seed);
    const seeded = corpus.length;
    const rng = new Random(args.seed);
    const deadline = args.seconds ? started + args.seconds * 1000 : Infinity;
    const count = args.count ?? (args.seconds ? Infinity : 1000);
    while (inputs < count + seeded && Date.now() < deadline && findings.length < 10) {
      const input = nextInput(rng, corpus, { json: target.options && target.options.json, jsonValues });
      if (await feed(input)) corpus.push(input);
      if (inputs % args.checkEvery === 0) await check();
      // let timers and I/O run (fragment timers, bus wake-ups)
      if (inputs % 10 === 0) await new Promise((r) => setImmediate(r));
    }
    await check();
  }
  const seconds = (Date.now() - started) / 1000;
  const cov = coverage ? await coverage.take(harness.coverageFiles || []) : null;
  try {
    await withTimeout(Promise.resolve().then(() => harness.close && harness.close()), 10000, 'close');
  } catch (e) {
    record('hang', `closing the harness: ${e.message}`);
  }
  process.stdout.write(`${JSON.stringify({
    target: args.target, seed: args.seed, inputs, seconds, classes: classes.size, checks, findings, coverage: cov,
    top: [...classes].sort((a, b) => b[1] - a[1]).slice(0, 8),
  })}\n`);
  process.exit(findings.length ? 1 : 0);
}

main().catch((e) => {
  process.stdout.write(`${JSON.stringify({ error: String(e && e.stack ? e.stack : e) })}\n`);
  process.exit(2);
});
