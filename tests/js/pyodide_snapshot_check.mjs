// Copyright 2026 colcon-wasm contributors. Licensed under the Apache License 2.0.
//
// node pyodide_snapshot_check.mjs SRC PYODIDE_DIR SCRIPT COUNT [snapshot=false]
//
// Runs SCRIPT as COUNT Python nodes, one after the other, on one Runtime of SRC
// (packages/wasm_js/src), each with its own argv and environment; prints one JSON
// line per node: {snapshot (started from the host's snapshot), warm (it took the runtime's
// warm Python worker), code, lines}.
// tests/test_pyodide_snapshot.py.

const [src, pyodideDir, script, count, option] = process.argv.slice(2);
const { Runtime } = await import(`${src}/runtime.mjs`);
const { spawnPython } = await import(`${src}/python/spawn.mjs`);

const runtime = await Runtime.create({});
try {
  for (let i = 0; i < Number(count); i++) {
    const lines = [];
    const proc = await spawnPython(runtime, {
      file: script, pyodideDir, args: [`arg${i}`], env: { NODE_INDEX: String(i) },
      onLog: (l) => lines.push(l.text), ...(option === 'snapshot=false' ? { snapshot: false } : {}),
    });
    const { code } = await proc.exited;
    console.log(JSON.stringify({ snapshot: proc.pyodideSnapshot, warm: proc.warmPythonWorker, code, lines }));
  }
} finally {
  await runtime.close();
}
