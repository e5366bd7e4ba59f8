#!/usr/bin/env node
// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Node.js runner: start one or more executables on one bus, print their
 * logs, exit with the first failure.
 *
 *   node cli.mjs [runner options] [--name N] [--env K=V]... exe.js [args...] [--- ...]
 *
 * Runner options (before the first executable):
 *   --timeout SECONDS      stop everything after this long (exit code 124)
 *   --until NAME           when process NAME ends, stop the others
 *   --max-message-bytes N  bus message limit (default 64 MiB)
 *   --max-bytes N          bus size limit (default 1 GiB)
 *   --quiet-prefix         do not prefix log lines with "[name] "
 *   --mount DIR            every executable sees DIR read-only at its real path (repeatable;
 *                          see view_fs.mjs); set AMENT_PREFIX_PATH with --env yourself
 * Per executable (before its path): --name N, --env K=V (repeatable), --delay MS.
 * Executables are separated by `---`.
 *
 * @module cli
 */

import path from 'node:path';
import process from 'node:process';

import { Runtime } from './runtime.mjs';

const USAGE = 'usage: node cli.mjs [--timeout S] [--until NAME] [--max-message-bytes N] [--max-bytes N] ' +
  '[--quiet-prefix] [--mount DIR]... [--name N] [--env K=V]... [--delay MS] exe.js [args...] [--- [--name N] exe2.js [args...]]...';

class UsageError extends Error {}

/**
 * Parse the command line.
 * @param {string[]} argv arguments after the script
 */
export function parseArgs(argv) {
  const opts = { timeout: 0, until: null, maxMessageBytes: undefined, maxBytes: undefined, prefix: true, mounts: [] };
  const segments = [];
  let i = 0;
  const intArg = (name) => {
    const v = Number(argv[++i]);
    if (!Number.isFinite(v) || v < 0) throw new UsageError(`${name} needs a non-negative number, got ${JSON.stringify(argv[i])}`);
    return v;
  };
  for (; i < argv.length; i++) {
    const a = argv[i];
    if (a === '--timeout') opts.timeout = intArg(a);
    else if (a === '--until') opts.until = argv[++i];
    else if (a === '--max-message-bytes') opts.maxMessageBytes = intArg(a);
    else if (a === '--max-bytes') opts.maxBytes = intArg(a);
    else if (a === '--quiet-prefix') opts.prefix = false;
    else if (a === '--mount') {
      if (!argv[i + 1]) throw new UsageError('--mount needs a directory');
      opts.mounts.push({ path: path.resolve(argv[++i]) });
    }
    else if (a === '-h' || a === '--help') throw new UsageError('');
    else break;
  }
  while (i < argv.length) {
    const seg = { name: undefined, env: {}, delay: 0, path: null, args: [] };
    for (; i < argv.length; i++) {
      const a = argv[i];
      if (a === '--name') seg.name = argv[++i];
      else if (a === '--env') {
        const kv = argv[++i] || '';
        const eq = kv.indexOf('=');
        if (eq <= 0) throw new UsageError(`--env needs KEY=VALUE, got ${JSON.stringify(kv)}`);
        seg.env[kv.slice(0, eq)] = kv.slice(eq + 1);
      } else if (a === '--delay') seg.delay = intArg(a);
      else break;
    }
    seg.path = argv[i++];
    if (!seg.path || seg.path === '---') throw new UsageError('missing executable (.js) path');
    while (i < argv.length && argv[i] !== '---') seg.args.push(argv[i++]);
    if (argv[i] === '---') i++;
    segments.push(seg);
  }
  if (!segments.length) throw new UsageError('no executable given');
  return { opts, segments };
}

/**
 * Run the executables; resolves with the exit code.
 * @param {string[]} argv
 */
export async function main(argv) {
  let parsed;
  try {
    parsed = parseArgs(argv);
  } catch (e) {
    if (e instanceof UsageError) {
      if (e.message) process.stderr.write(`cli.mjs: ${e.message}\n`);
      process.stderr.write(`${USAGE}\n`);
      return 2;
    }
    throw e;
  }
  const { opts, segments } = parsed;
  const rt = await Runtime.create({ maxMessageBytes: opts.maxMessageBytes, maxBytes: opts.maxBytes });
  let exitCode = 0;
  let stopping = false;
  const procs = [];
  const stopAll = () => {
    stopping = true;
    for (const p of procs) p.stop();
  };
  let timer = null;
  if (opts.timeout > 0) {
    timer = setTimeout(() => {
      process.stderr.write(`cli.mjs: timeout after ${opts.timeout} s, stopping all processes\n`);
      if (!exitCode) exitCode = 124;
      stopAll();
    }, opts.timeout * 1000);
  }
  const onSignal = () => {
    if (!exitCode) exitCode = 130;
    stopAll();
  };
  process.on('SIGINT', onSignal);
  process.on('SIGTERM', onSignal);
  for (const seg of segments) {
    if (seg.delay) await new Promise((r) => setTimeout(r, seg.delay));
    if (stopping) break;
    let name;
    const proc = await rt.spawn({
      url: seg.path,
      args: seg.args,
      env: seg.env,
      name: seg.name,
      mounts: opts.mounts,
      onLog: ({ stream, text }) => {
        const line = opts.prefix ? `[${name}] ${text}\n` : `${text}\n`;
        (stream === 'stderr' ? process.stderr : process.stdout).write(line);
      },
      onExit: ({ code, crashed, reason }) => {
        if (crashed && !stopping) {
          process.stderr.write(`[${name}] ${reason || 'crashed'}\n`);
          if (!exitCode) exitCode = code || 1;
        }
        if (opts.until && name === opts.until && !stopping) stopAll();
      },
    });
    name = proc.name;
    procs.push(proc);
  }
  await Promise.all(procs.map((p) => p.exited));
  if (timer) clearTimeout(timer);
  await rt.close();
  process.off('SIGINT', onSignal);
  process.off('SIGTERM', onSignal);
  return exitCode;
}

const isMain = process.argv[1] && import.meta.url === new URL(`file://${process.argv[1]}`).href;
if (isMain) {
  main(process.argv.slice(2)).then((code) => process.exit(code), (err) => {
    process.stderr.write(`cli.mjs: ${err && err.stack ? err.stack : err}\n`);
    process.exit(1);
  });
}
