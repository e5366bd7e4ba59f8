// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * bench/python: node start, spawn → first message, on the runtime's API.
 *
 *   node start.mjs RUNTIME_URL PYODIDE_DIR TYPES_JSON TALKER_PY TALKER_JS ROUNDS
 *
 * Each round, interleaved: a Python talker (TALKER_PY) on a new runtime with
 * Pyodide cold (no snapshot); the first Python node of a new runtime (Pyodide
 * from the host's snapshot, on disk in COLCON_WASM_CACHE); the next Python
 * node of that runtime (its warm Python worker, python/python_spares.mjs);
 * and on the same runtime the C++ demo talker (TALKER_JS, its warm program
 * worker), the baseline. Both talkers publish every 20 ms. Prints one JSON
 * line: {cold: [ms], snapshot: [ms], warm: [ms], cpp: [ms]}.
 */

const [runtimeUrl, pyodideDir, typesFile, talkerPy, talkerJs, roundsText] = process.argv.slice(2);
const { Runtime } = await import(runtimeUrl);
const { spawnPython } = await import(new URL('python/spawn.mjs', runtimeUrl).href);

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

/** Start a process with `spawn(onLog)`; resolve with ms to its first `Publishing` line. */
async function timeToFirstMessage(spawn) {
  let heard;
  const first = new Promise((resolve) => { heard = resolve; });
  const t0 = performance.now();
  const proc = await spawn((line) => {
    if (/Publishing/.test(line.text)) heard(performance.now() - t0);
  });
  let timer;
  const late = new Promise((resolve, reject) => {
    timer = setTimeout(() => reject(new Error(`${proc.name}: no first message in 60 s`)), 60000);
  });
  const ms = await Promise.race([first, late]).finally(() => clearTimeout(timer));
  await proc.stop();
  return ms;
}

const python = (runtime, snapshot) => (onLog) => spawnPython(runtime, {
  file: talkerPy, pyodideDir, types: [typesFile], snapshot, onLog,
});

const result = { cold: [], snapshot: [], warm: [], cpp: [] };
for (let round = 0; round < Number(roundsText); round++) {
  let runtime = await Runtime.create();
  result.cold.push(await timeToFirstMessage(python(runtime, false)));
  await runtime.close();
  runtime = await Runtime.create();
  result.snapshot.push(await timeToFirstMessage(python(runtime, true)));
  await sleep(3000); // the warm Python worker is made and loaded
  result.warm.push(await timeToFirstMessage(python(runtime, true)));
  await runtime.warm();
  result.cpp.push(await timeToFirstMessage((onLog) => runtime.spawn({
    url: talkerJs, args: ['--ros-args', '-p', 'rate:=50.0'], onLog,
  })));
  await runtime.close();
}
console.log(JSON.stringify(result));
