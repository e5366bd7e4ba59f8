// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The launcher page: reads the workspace that `colcon-wasm serve` embedded,
// starts the wasm_js Runtime, and wires the views. `?run=pkg/exe` (repeatable,
// optionally followed by arguments: `?run=pkg/exe --ros-args -p rate:=5`)
// starts executables on load; `?rosbridge=ws://HOST:PORT` bridges them to a
// rosbridge server; `?zenoh=ws/HOST:PORT` joins them to a Zenoh router's graph.

import { h, setChildren, splitArgs } from './dom.mjs';
import { Session } from './session.mjs';
import { ExecutablesView } from './views/executables.mjs';
import { LaunchFilesView } from './views/launch_files.mjs';
import { ProcessesView } from './views/processes.mjs';
import { LogsDock } from './views/logs.mjs';
import { NodesView } from './views/nodes.mjs';
import { GraphView } from './views/graph.mjs';
import { TopicsView } from './views/topics.mjs';
import { ServicesView } from './views/services.mjs';
import { ActionsView } from './views/actions.mjs';
import { ParametersView } from './views/parameters.mjs';
import { SceneView } from './views/scene/scene_view.mjs';
import { dockSplitter } from './views/splitter.mjs';
import { ConnectionsPanel } from './views/connections.mjs';
import { PlaybackBar } from './views/playback_bar.mjs';
import { siteUrl } from './site_url.mjs';
import { LaunchRun } from './launch_run.mjs';

const workspace = JSON.parse(document.getElementById('workspace').textContent);
const app = document.getElementById('app');

/**
 * The header: what runs here, in one line that never overflows (the
 * workspace path is cut with an ellipsis, in full in its tooltip); `items`
 * (the REC chip, the /clock box) come before the status chips.
 */
function header(session, items) {
  const isolation = h('span.chip', {},
    h('span.dot'), window.crossOriginIsolated ? 'cross-origin isolated' : 'not isolated');
  isolation.classList.add(window.crossOriginIsolated ? 'ok' : 'bad');
  const running = h('span.chip', { id: 'running-chip' }, h('span.dot'), '0 running');
  session.on('processes', () => {
    const n = session.runningCount();
    running.lastChild.textContent = `${n} running`;
    running.classList.toggle('ok', n > 0);
  });
  return h('header.top', {},
    h('img.logo', { src: siteUrl('launcher/favicon.svg'), alt: '' }),
    h('h1', {}, 'colcon-wasm launcher'),
    h('span.workspace', { title: workspace.install_base }, workspace.install_base),
    h('span.spacer'),
    ...items,
    running,
    h('span.chip', { title: `wasm_js runtime from ${workspace.runtime_origin}` }, h('span.dot'), 'wasm_js'),
    isolation);
}

/** The clear message of a page that cannot share memory between workers. */
function isolationBanner() {
  return h('div.banner.fatal#isolation-error', {},
    h('h2', {}, 'This page is not cross-origin isolated: nodes cannot run here'),
    h('div', {}, 'The nodes share memory (SharedArrayBuffer), which browsers allow only on pages '
      + 'served with these two HTTP headers:'),
    h('pre', {}, 'Cross-Origin-Opener-Policy: same-origin\nCross-Origin-Embedder-Policy: require-corp'),
    workspace.isolationProblem ? h('div', {}, `This is an exported site: ${workspace.isolationProblem}.`) : null,
    h('div', { style: { marginTop: '8px' } }, 'Open the page through ',
      h('code', {}, 'colcon-wasm serve'), ', which sends them, or add them to your web server.'));
}

function tabs(views) {
  const nav = h('nav.tabs');
  const buttons = new Map();
  const show = (name) => {
    for (const [n, v] of Object.entries(views)) {
      v.element.hidden = n !== name;
      buttons.get(n).classList.toggle('active', n === name);
      if (n === name && v.shown) v.shown();
    }
    history.replaceState(null, '', `${location.search}#${name}`);
  };
  for (const [name, view] of Object.entries(views)) {
    const count = h('span.count', {}, '0');
    const button = h('button', { dataset: { tab: name }, onclick: () => show(name) }, view.title, count);
    view.setCount = (n) => { count.textContent = String(n); };
    buttons.set(name, button);
    nav.append(button);
  }
  return { nav, show };
}

function runRequests() {
  const params = new URLSearchParams(location.search);
  // ?run= wins; an exported site may name its own (export --run)
  const specs = params.getAll('run').length ? params.getAll('run') : (workspace.autorun || []);
  return specs.map((spec) => {
    const words = splitArgs(spec);
    const [pkg, exe] = (words[0] || '').split('/');
    return { spec, pkg, exe, args: words.slice(1) };
  });
}

/**
 * An exported site (colcon-wasm export) isolates itself before this module
 * loads (static_boot.js, inlined into its page); what it found missing is
 * said in the page.
 */
function staticIsolationProblem() {
  if (!workspace.static || window.crossOriginIsolated) return;
  workspace.isolationProblem = window.colconWasmIsolation
    || 'the page is not cross-origin isolated, and the host sends no isolation headers';
}

async function main() {
  staticIsolationProblem();
  const session = new Session(workspace);
  // for the browser console: colconWasm.session.runtime, .graph, .processes
  window.colconWasm = { session };
  // Start the runtime first, and build the views once it exists: its host
  // worker then boots (on another thread) while they build. (A failure is
  // shown below, once the views are there.)
  const starting = window.crossOriginIsolated ? session.start() : null;
  if (starting) await starting.catch(() => {});
  const banners = h('div.banners');
  const side = h('aside.side');
  const main = h('main.main');
  // record and replay: the bar at the bottom of the main area, its REC chip and /clock box in the header
  const playback = new PlaybackBar(session, workspace.bag && workspace.bag.problem);
  setChildren(app, header(session, playback.headerItems), side, main);

  const processes = new ProcessesView(session);
  const executables = new ExecutablesView(session, workspace);
  const launchFiles = new LaunchFilesView(session, workspace);
  launchFiles.setEnabled(false);
  const connections = new ConnectionsPanel(session, workspace);
  // a robot stack starts from its launch files: they come first, when the packages have any
  if ((workspace.launch?.files || []).length) side.append(launchFiles.element);
  side.append(executables.element, processes.element, connections.element);

  const views = {
    nodes: new NodesView(session),
    graph: new GraphView(session),
    topics: new TopicsView(session),
    services: new ServicesView(session),
    actions: new ActionsView(session),
    parameters: new ParametersView(session),
    '3d': new SceneView(session, workspace),
  };
  // for the browser console and the tests: colconWasm.views['3d'].displays
  window.colconWasm.views = views;
  const { nav, show } = tabs(views);
  // a vertex of the graph, double-clicked, opens in its tab
  views.graph.onTopic = (name) => { show('topics'); views.topics.select(name); };
  views.graph.onNode = (fqn) => { show('nodes'); views.nodes.selected = fqn; views.nodes.render(session.graph); };
  const logs = new LogsDock(session);
  processes.onSelect = (id) => logs.select(id);
  // the console's input is the log dock's line: show its tab
  executables.onConsole = (id) => logs.select(id);
  // a launch shows its log; rviz2 -d FILE.rviz of a launch is the 3D view with that file
  launchFiles.onLaunch = (proc) => processes.select(proc.id);
  launchFiles.onRviz = (uri) => {
    show('3d');
    views['3d'].openRvizUrl(uri).catch((e) => banners.append(h('div.banner.warn', {}, `rviz2 -d ${uri}: ${e.message}`)));
  };
  // the main grid: banners and tabs, the visible view, the logs dock, the playback bar
  const viewHost = h('div.viewhost', {}, ...Object.values(views).map((v) => v.element));
  logs.element.prepend(dockSplitter(logs.element, `colcon-wasm:dock:${workspace.install_base}`));
  main.append(h('div', {}, banners, nav), viewHost, logs.element, playback.element);
  session.on('graph', (model) => {
    views.nodes.setCount(model.nodes.length);
    views.graph.setCount(views.graph.links(model));
    views.topics.setCount(model.topics.length);
    views.services.setCount(model.services.length);
    views.actions.setCount(model.actions.length);
    // the nodes that have parameters to show: those with rcl's parameter services
    views.parameters.setCount(model.nodes.filter((n) => n.services.some((e) => e.name === `${n.fqn}/list_parameters`)).length);
  });
  const wanted = location.hash.slice(1);
  show(wanted in views ? wanted : 'topics');

  if (!window.crossOriginIsolated) {
    banners.append(isolationBanner());
    executables.setEnabled(false);
    document.body.dataset.state = 'not-isolated';
    return;
  }
  for (const warning of workspace.warnings || []) {
    banners.append(h('div.banner.warn', {}, warning));
  }
  if (workspace.packages.length === 0) {
    banners.append(h('div.banner.warn', {}, h('h2', {}, 'No executables in this install space'),
      `${workspace.install_base} has no package with a colcon-wasm manifest. Build your workspace `
      + 'with colcon build --wasm, then reload this page.'));
  }
  try {
    await starting;
  } catch (e) {
    showRuntimeError(banners, executables, e);
    return;
  }
  executables.setEnabled(true);
  launchFiles.setEnabled(true);
  const requests = runRequests();
  for (const request of requests) {
    const found = workspace.packages.find((p) => p.name === request.pkg)
      ?.executables.find((e) => e.name === request.exe);
    if (!found) {
      banners.append(h('div.banner.warn', {}, `?run=${request.spec}: there is no executable `
        + `'${request.exe}' in package '${request.pkg}' of this install space.`));
      continue;
    }
    const proc = session.startProcess(request.pkg, request.exe, request.args);
    if (requests.length === 1) logs.select(proc.id);
  }
  // an exported site's launch files (export --launch), planned when it was written
  if (!new URLSearchParams(location.search).getAll('run').length) {
    for (const plan of (workspace.launch && workspace.launch.planned) || []) {
      new LaunchRun(session, plan.package, plan.file, plan.arguments || {}).startPlanned(plan)
        .catch((e) => banners.append(h('div.banner.warn', {}, `launch ${plan.file}: ${e.message}`)));
    }
  }
  try {
    await session.ready;
  } catch (e) {
    showRuntimeError(banners, executables, e);
    return;
  }
  if (session.typeError) {
    banners.append(h('div.banner.warn', {}, `Type descriptions: ${session.typeError}`));
  }
  // ?rosbridge=ws://HOST:PORT bridges the page's nodes to a rosbridge server
  // (serve --rosbridge: the relay of serve itself, so that tabs share one graph)
  const relay = workspace.rosbridge ? `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}${workspace.rosbridge}` : null;
  const rosbridge = new URLSearchParams(location.search).get('rosbridge') || relay;
  if (rosbridge) {
    session.connectBridge(rosbridge).catch((e) => banners.append(h('div.banner.warn', {}, `?rosbridge=${rosbridge}: ${e.message}`)));
  }
  // ?zenoh=ws/HOST:PORT joins them to the ROS 2 graph of a Zenoh router (rmw_zenoh)
  const zenoh = new URLSearchParams(location.search).get('zenoh');
  if (zenoh) {
    session.connectZenoh(zenoh).catch((e) => banners.append(h('div.banner.warn#zenoh-error', {}, `?zenoh=${zenoh}: ${e.message}`)));
  }
  // ?rviz=package://PKG/FILE.rviz opens the 3D view with that configuration
  const rviz = new URLSearchParams(location.search).get('rviz');
  if (rviz) {
    show('3d');
    views['3d'].openRvizUrl(rviz).catch((e) => banners.append(h('div.banner.warn', {}, `?rviz=${rviz}: ${e.message}`)));
  }
  document.body.dataset.state = 'ready';
}

function showRuntimeError(banners, executables, e) {
  banners.append(h('div.banner.fatal#runtime-error', {}, h('h2', {}, 'The runtime did not start'),
    h('pre', {}, String(e && e.stack ? e.stack : e))));
  executables.setEnabled(false);
  document.body.dataset.state = 'runtime-error';
}

main().catch((e) => {
  app.append(h('div.banner.fatal', {}, h('h2', {}, 'The launcher failed'), h('pre', {}, String(e && e.stack ? e.stack : e))));
});
