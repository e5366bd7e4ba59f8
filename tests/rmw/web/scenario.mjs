// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Run a scenario of ROS executables on one wasm_js Runtime, the same way in
 * Node.js and in a browser page, and report what happened.
 *
 * A scenario is JSON:
 *
 *   {
 *     "runtime": {"maxMessageBytes": 1048576},   // Runtime.create() options
 *     "steps": [
 *       {"spawn": "talker", "exe": "<url or path of the .js>", "args": [], "env": {},
 *        "stdin": "text the executable reads as its standard input (then end of file)",
 *        "files": {"/params.yaml": "file content"}},
 *       {"spawn": "client", "exe": "...", "stdin": true},  // an open pipe, fed by stdin steps
 *       {"stdin": "client", "text": "2\n3\n"},          // type into it
 *       {"stdin": "client", "close": true},             // end of file
 *       {"wait": "listener", "text": "I heard", "count": 3, "timeout": 20},
 *       {"wait": "listener", "regex": "^\\[WARN\\]", "timeout": 5},
 *       {"stop": "talker"},
 *       {"exit": "caller", "timeout": 10},             // wait for a process to end
 *       {"quiet": "listener", "text": "I heard", "seconds": 2}, // no such line for 2 s
 *       {"cpu": "idle", "seconds": 2},   // CPU time of the whole Node.js process once the
 *                                        // runtime's warm workers are ready (null in a page)
 *       {"graph": "after"},                            // record a graph snapshot
 *       {"graphWait": {"node": "/talker", "present": false}, "timeout": 5}
 *     ]
 *   }
 *
 * Waits are driven by events (log lines, exits, graph changes); each has a
 * deadline. The report lists every log line with its severity, every exit,
 * the recorded graphs and CPU loads (cores busy, Node.js only), and the first
 * failed step with the reason.
 *
 * @module scenario
 */

/**
 * Run a scenario.
 * @param {typeof import('../../../packages/wasm_js/src/runtime.mjs').Runtime} Runtime
 * @param {object} scenario see the module comment
 * @returns {Promise<object>} the report: {ok, error, logs, exits, graphs, seconds}
 */
export async function runScenario(Runtime, scenario) {
  const started = performance.now();
  const report = { ok: true, error: null, logs: [], exits: {}, graphs: {}, cpu: {}, seconds: 0 };
  const processes = new Map();
  const waiters = new Set();

  const notify = () => {
    for (const waiter of [...waiters]) waiter();
  };
  // Resolve when check() is true, re-checked on every log, exit and graph change.
  const until = (check, timeoutSeconds, what) => new Promise((resolve, reject) => {
    if (check()) {
      resolve();
      return;
    }
    const timer = setTimeout(() => {
      waiters.delete(waiter);
      reject(new Error(`timed out after ${timeoutSeconds} s waiting for ${what}`));
    }, timeoutSeconds * 1000);
    const waiter = () => {
      if (check()) {
        clearTimeout(timer);
        waiters.delete(waiter);
        resolve();
      }
    };
    waiters.add(waiter);
  });

  const runtime = await Runtime.create(scenario.runtime || {});
  const stopGraph = runtime.onGraphChange(notify);
  try {
    for (const [index, step] of (scenario.steps || []).entries()) {
      const timeout = step.timeout ?? 30;
      try {
        if (step.spawn) {
          if (processes.has(step.spawn)) throw new Error(`a process named '${step.spawn}' already runs`);
          report.exits[step.spawn] = null;
          const process = await runtime.spawn({
            url: step.exe,
            args: step.args || [],
            env: step.env || {},
            stdin: step.stdin,
            files: step.files,
            mounts: step.mounts,
            name: step.spawn,
            onLog: ({ stream, severity, text }) => {
              report.logs.push({
                name: step.spawn, stream, severity, text,
                t: Math.round(performance.now() - started),
              });
              notify();
            },
            onExit: (result) => {
              report.exits[step.spawn] = result;
              notify();
            },
          });
          processes.set(step.spawn, process);
        } else if (step.wait) {
          const count = step.count || 1;
          const regex = step.regex ? new RegExp(step.regex) : null;
          const matches = () => report.logs.filter((l) => l.name === step.wait &&
            (regex ? regex.test(l.text) : l.text.includes(step.text))).length;
          await until(() => matches() >= count, timeout,
            `${count} line(s) of '${step.wait}' matching ${JSON.stringify(step.regex || step.text)}`);
        } else if (step.quiet) {
          const regex = step.regex ? new RegExp(step.regex) : null;
          const matching = () => report.logs.some((l) => l.name === step.quiet &&
            (regex ? regex.test(l.text) : l.text.includes(step.text)));
          const appeared = await until(matching, step.seconds, 'silence')
            .then(() => true, () => false);
          if (appeared) {
            throw new Error(`'${step.quiet}' printed ${JSON.stringify(step.regex || step.text)} ` +
              `within ${step.seconds} s`);
          }
        } else if (step.cpu) {
          const usage = globalThis.process && typeof globalThis.process.cpuUsage === 'function'
            ? globalThis.process.cpuUsage.bind(globalThis.process) : null;
          // Measure the nodes, not the runtime booting its next warm worker
          // (it does once a spawned program has settled, see Runtime.warm).
          await runtime.warm();
          const before = usage ? usage() : null;
          await new Promise((resolve) => setTimeout(resolve, step.seconds * 1000));
          if (usage) {
            const delta = usage(before);
            report.cpu[step.cpu] = (delta.user + delta.system) / 1e6 / step.seconds;
          } else {
            report.cpu[step.cpu] = null;
          }
        } else if (step.exit) {
          await until(() => report.exits[step.exit], timeout, `'${step.exit}' to exit`);
        } else if (step.stop) {
          const process = processes.get(step.stop);
          if (!process) throw new Error(`no process named '${step.stop}'`);
          await process.stop();
        } else if (step.stdin) {
          const process = processes.get(step.stdin);
          if (!process) throw new Error(`no process named '${step.stdin}'`);
          if (step.text !== undefined) await process.writeStdin(step.text);
          if (step.close) await process.closeStdin();
        } else if (step.graph) {
          report.graphs[step.graph] = runtime.graph();
        } else if (step.graphWait) {
          const { node, present } = step.graphWait;
          const has = () => runtime.graph().nodes.some(
            (n) => (n.namespace === '/' ? '' : n.namespace) + '/' + n.name === node);
          await until(() => has() === present, timeout,
            `node '${node}' to ${present ? 'appear in' : 'leave'} the graph`);
        } else {
          throw new Error(`unknown step ${JSON.stringify(step)}`);
        }
      } catch (error) {
        report.ok = false;
        report.error = `step ${index} ${JSON.stringify(step)}: ${error.message}`;
        break;
      }
    }
  } finally {
    stopGraph();
    await runtime.close();
    report.seconds = (performance.now() - started) / 1000;
  }
  return report;
}
