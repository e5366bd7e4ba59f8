// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The Node.js side of `colcon-wasm run` and `colcon-wasm launch`.
 *
 *   node run_plan.mjs '<plan JSON>'
 *
 * The plan (colcon_wasm/launch/runner.py) lists processes with absolute .js
 * paths, arguments and environment, an optional duration, topics to echo,
 * the types.json files, the read-only views every process gets of the
 * install bases (`mounts`, see view_fs.mjs) and the URL of the Runtime module to use (the install
 * space's, which matches the executables). All processes share one bus (one Runtime). Output is
 * prefixed `[label]` and process events are reported as `ros2 launch` does.
 * Composable nodes (`plan.loads`) are loaded into their containers once the
 * processes have started (./composable.mjs). `plan.rosbridge` and
 * `plan.rosbridge_connect` start the rosbridge server and client first, `plan.foxglove`
 * the Foxglove server (../bridges/rosbridge/launch.mjs). `plan.record` / `plan.play` record the
 * bus and replay a bag (../bridges/record/launch.mjs): recording starts
 * before the processes and ends after them, playing after they started.
 * With `plan.control` (a Python launch file), Humble's `launch` on the host
 * starts the processes: each asks for its executable on this bus through the
 * socket `plan.control.socket` (./process_server.mjs), and the host ends once
 * the launcher says the launch has ended and its processes are gone.
 * The exit status is 1 when a process crashed or exited with a non-zero
 * code, or a composable node failed to load, 0 otherwise.
 */

import { closeSync, readFileSync, writeSync } from 'node:fs';
import process from 'node:process';
import { pathToFileURL } from 'node:url';

import { TypeRegistry } from '../cdr.mjs';
import { ComposableLoader } from './composable.mjs';
import { graphModel, subscriptionQos } from '../page/graph.mjs';
import { formatYaml } from '../page/yaml.mjs';

const out = (line) => process.stdout.write(`${line}\n`);
const err = (line) => process.stderr.write(`${line}\n`);

function loadRegistry(paths) {
  const registry = new TypeRegistry();
  for (const path of paths) {
    try {
      registry.add(JSON.parse(readFileSync(path, 'utf-8')));
    } catch (e) {
      err(`[WARNING] [launch]: cannot read the type descriptions ${path}: ${e.message}`);
    }
  }
  return registry;
}

/** Print the messages of one topic, decoded, once it is in the graph. */
function echoTopic(runtime, tools, registry, topic, stopping) {
  let subscription = null;
  const tryStart = () => {
    if (subscription || stopping()) return;
    const entry = graphModel(runtime.graph(), { toolsPid: tools.pid }).topics.find((t) => t.name === topic);
    if (!entry || entry.types.length === 0) return;
    const type = entry.types[0];
    if (!registry.has(type)) {
      err(`[ERROR] [echo]: cannot decode ${topic}: no type description of ${type}; build its `
        + 'interface package with colcon build --wasm');
      subscription = { close() {} };
      return;
    }
    subscription = tools.subscribe({ topic, type, qos: subscriptionQos(entry.publisherQos) }, (messages) => {
      for (const m of messages) {
        let text;
        try {
          text = formatYaml(registry.decode(type, m.data));
        } catch (e) {
          text = `# ${e.message}`;
        }
        out(`[echo ${topic}]\n${text}\n---`);
      }
    });
    subscription.catch((e) => err(`[ERROR] [echo]: cannot subscribe to ${topic}: ${e.message}`));
  };
  runtime.onGraphChange(tryStart);
  tryStart();
}

/**
 * spawn() of a Python node (`python`: its script): the runtime's python/spawn.mjs
 * (docs/python.md), with the plan's Pyodide folder and type descriptions.
 */
function spawnPythonNode(runtimeUrl, runtime, proc, plan) {
  return async (spec) => {
    let spawnPython;
    try {
      ({ spawnPython } = await import(new URL('python/spawn.mjs', runtimeUrl).href));
    } catch (e) {
      throw new Error(`the wasm_js runtime ${runtimeUrl} has no Python nodes (python/spawn.mjs): rebuild it `
        + "with 'colcon build --wasm --packages-select wasm_js'");
    }
    return spawnPython(runtime, {
      ...spec, file: proc.python, entry: proc.python_entry, pythonPath: proc.python_path,
      pyodideDir: plan.pyodide, types: plan.types || [],
    });
  };
}

async function main() {
  const plan = JSON.parse(process.argv[2]);
  const runtimeUrl = plan.runtime || new URL('../runtime.mjs', import.meta.url).href;
  const { Runtime } = await import(runtimeUrl);
  if (plan.mounts && plan.mounts.length && !(Runtime.features && Runtime.features.mounts)) {
    err(`[WARNING] [launch]: the wasm_js runtime ${runtimeUrl} predates read-only views: the processes `
      + 'do not see their install space (AMENT_PREFIX_PATH is set all the same); rebuild it with '
      + "'colcon build --wasm --packages-select wasm_js'");
  }
  const runtime = await Runtime.create({});
  const registry = loadRegistry(plan.types || []);
  // the rosbridge server / client (--rosbridge, --rosbridge-connect), before any process
  let bridges = null;
  if (plan.rosbridge || plan.rosbridge_connect || plan.foxglove || plan.zenoh) {
    const { startBridges } = await import('../bridges/rosbridge/launch.mjs');
    try {
      bridges = await startBridges(plan, runtime, registry, { out, err });
    } catch (e) {
      err(`${plan.command || 'colcon-wasm launch'}: ${['RosbridgeError', 'FoxgloveError'].includes(e.name) ? e.message : e.stack}`);
      await runtime.close();
      return 1;
    }
  }
  // --record, --play (bridges/record/): the recorder taps the bus before any process
  let bags = null;
  if (plan.record || plan.play) {
    const { startBags } = await import('../bridges/record/launch.mjs');
    bags = await startBags(plan, runtime, { out, err });
  }
  const handles = new Map();
  const states = new Map();
  let failed = false;
  let stopping = false;
  let pendingLoads = 0;
  let finish;
  const done = new Promise((resolve) => { finish = resolve; });

  let launchOver = !plan.control;
  const checkDone = () => {
    if (launchOver && pendingLoads === 0 && [...states.values()].every((s) => s !== 'running')) finish();
  };
  const loader = new ComposableLoader({
    runtime,
    tools: () => runtime.tools(),
    registry,
    timeoutMs: (plan.load_timeout || 60) * 1000,
    isRunning: (label) => states.get(label) === 'running',
    out,
    err,
  });

  const startProcess = (proc, hooks) => (proc.python ? spawnPythonNode(runtimeUrl, runtime, proc, plan)
    : (spec) => runtime.spawn(spec))({
    url: pathToFileURL(proc.js).href,
    args: proc.args,
    env: proc.env,
    name: proc.label,
    onLog: hooks.onLog,
    onExit: hooks.onExit,
    stdin: plan.stdin ? true : undefined,
    files: proc.files,
    // a launch file's parameters, given to a program that is no ROS node, are not read
    filesOptional: !!plan.control,
    mounts: plan.mounts || [],
  });

  for (const proc of plan.processes) {
    states.set(proc.label, 'running');
    const onExit = ({ code, crashed, reason } = {}) => {
      if (states.get(proc.label) !== 'running') return;
      const stoppedByUs = stopping && !crashed;
      if (crashed || (code !== 0 && code !== undefined && code !== null && !stoppedByUs)) {
        failed = true;
        states.set(proc.label, 'crashed');
        err(`[ERROR] [${proc.label}]: process has died [exit code ${code ?? 'none'}${reason ? `, ${reason}` : ''}, `
          + `cmd '${proc.js} ${proc.args.join(' ')}']`.replace(/ '\]$/, "']"));
      } else if (stopping && reason === 'stopped') {
        states.set(proc.label, 'exited');
        out(`[INFO] [${proc.label}]: process stopped`);
      } else {
        states.set(proc.label, 'exited');
        out(`[INFO] [${proc.label}]: process has finished cleanly`);
      }
      loader.processExited();
      checkDone();
    };
    try {
      const handle = await startProcess(proc, {
        onLog: ({ stream, text }) => {
          const write = stream === 'stderr' ? err : out;
          for (const line of String(text).split('\n')) if (line !== '') write(`[${proc.label}] ${line}`);
        },
        onExit,
      });
      handles.set(proc.label, handle);
      if (plan.stdin) forwardStdin(handle);
      out(`[INFO] [${proc.label}]: process started`);
    } catch (e) {
      onExit({ code: null, crashed: true, reason: e.message });
    }
  }

  // a Python launch file (plan.control): real `launch` on the host starts the processes,
  // each through a shim that asks for it here (./process_server.mjs); launch prints their
  // output and events, this host keeps the bus, the bridges and the recording until it ends
  let controlled = null;
  if (plan.control) {
    const { serveProcesses } = await import('./process_server.mjs');
    let launchEnded;
    controlled = { ended: new Promise((resolve) => { launchEnded = resolve; }), count: 0 };
    controlled.server = await serveProcesses(plan.control.socket, {
      spawn: async (proc, hooks) => {
        const label = `${proc.label}#${++controlled.count}`;
        states.set(label, 'running');
        const onExit = (result) => {
          const { code, crashed } = result;
          if (crashed || (code !== 0 && code !== undefined && code !== null && result.reason !== 'stopped')) {
            failed = true;
          }
          states.set(label, crashed ? 'crashed' : 'exited');
          handles.delete(label);
          hooks.onExit(result);
          checkDone();
        };
        try {
          const handle = await startProcess({ ...proc, label: proc.label }, { onLog: hooks.onLog, onExit });
          handles.set(label, handle);
          return handle;
        } catch (e) {
          states.set(label, 'crashed');
          failed = true;
          throw e;
        }
      },
      end: () => launchEnded(),
      link: async () => {
        const { startHostLink } = await import('./host_link.mjs');
        return startHostLink(runtime, plan.types || []);
      },
      err,
    });
    if (plan.control.ready_fd !== undefined) {
      writeSync(plan.control.ready_fd, 'ready\n');
      closeSync(plan.control.ready_fd);
    }
  }

  for (const group of plan.loads || []) {
    pendingLoads++;
    loader.load(group).then((ok) => {
      if (!ok) failed = true;
    }, (e) => {
      failed = true;
      err(`[ERROR] [launch]: loading into '${group.target}' failed: ${e && e.stack ? e.stack : e}`);
    }).finally(() => {
      pendingLoads--;
      checkDone();
    });
  }

  if (bags && bags.play) {
    pendingLoads++;
    bags.play().catch((e) => {
      failed = true;
      err(`[ERROR] [rosbag2]: playing failed: ${e && e.stack ? e.stack : e}`);
    }).finally(() => {
      pendingLoads--;
      if (plan.play.stop_after) stopAll('the bag has played');
      checkDone();
    });
  }

  const stopAll = async (why) => {
    if (stopping) return;
    stopping = true;
    out(`[INFO] [launch]: ${why}`);
    loader.shutdown();
    // bridged peers see the end first, so they keep what they send (rosbridge client queues),
    // and the nodes get a moment to take what the bridges delivered last
    if (bridges) {
      await bridges.close();
      await new Promise((resolve) => setTimeout(resolve, 250));
    }
    await Promise.all([...handles.entries()].map(async ([label, handle]) => {
      if (states.get(label) !== 'running') return;
      await handle.stop();
      if (states.get(label) === 'running') {
        states.set(label, 'exited');
        out(`[INFO] [${label}]: process stopped`);
      }
    }));
    // what the processes published last is recorded
    if (bags) await bags.close();
    checkDone();
  };

  if (plan.echo && plan.echo.length) {
    const tools = await runtime.tools();
    for (const topic of plan.echo) echoTopic(runtime, tools, registry, topic, () => stopping);
  }
  if (plan.duration) {
    setTimeout(() => stopAll(`stopping every process after ${plan.duration} s (--duration)`), plan.duration * 1000).unref();
  }
  if (controlled) {
    // Ctrl-C is the launch's to handle: it stops its processes, then ends this host
    process.on('SIGINT', () => {});
    controlled.ended.then(() => {
      launchOver = true;
      controlled.server.close();
      if ([...states.values()].some((s) => s === 'running')) stopAll('the launch has ended');
      checkDone();
    });
  } else {
    process.on('SIGINT', () => stopAll('user interrupted with ctrl-c (SIGINT)'));
  }
  process.on('SIGTERM', () => {
    launchOver = true;
    stopAll('terminated (SIGTERM)');
  });
  checkDone();
  await done;
  if (bridges) await bridges.close(); // closing twice is harmless
  if (bags) await bags.close();
  if (runtime.close) await runtime.close();
  return failed ? 1 : 0;
}

/**
 * Give this process' standard input (a terminal, a pipe or a file) to the
 * node, as `ros2 run` does; its end becomes the node's end of file.
 * @param {NodeProcess} handle
 */
function forwardStdin(handle) {
  const ignoreEnded = () => {}; // the node may end first: the rest is not read
  process.stdin.on('data', (chunk) => {
    handle.writeStdin(Uint8Array.from(chunk)).catch(ignoreEnded);
  });
  process.stdin.on('end', () => handle.closeStdin().catch(ignoreEnded));
  process.stdin.on('error', () => handle.closeStdin().catch(ignoreEnded));
  handle.exited.then(() => process.stdin.pause());
}

main().then((code) => process.exit(code), (e) => {
  err(`[ERROR] [launch]: ${e && e.stack ? e.stack : e}`);
  process.exit(1);
});
