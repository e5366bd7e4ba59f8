// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The packages' launch files (Python, XML, YAML), grouped by package: start
// one with its arguments, read into a form from the file itself
// (../launch_run.mjs; serve evaluates the file, the page runs its nodes).

import { breakable, h, setChildren } from '../dom.mjs';
import { launchArguments, LaunchRun } from '../launch_run.mjs';

const KIND = { py: 'Python', xml: 'XML', yaml: 'YAML', yml: 'YAML' };

export class LaunchFilesView {
  constructor(session, workspace) {
    this.session = session;
    this.workspace = workspace;
    this.buttons = [];
    this.onLaunch = null;
    this.onRviz = null;
    const files = (workspace.launch && workspace.launch.files) || [];
    this.list = h('div.packages');
    const byPackage = new Map();
    for (const file of files) {
      if (!byPackage.has(file.package)) byPackage.set(file.package, []);
      byPackage.get(file.package).push(file);
    }
    for (const [name, entries] of byPackage) {
      const group = h('details.package', { open: true, dataset: { package: name } }, h('summary', {}, name));
      for (const entry of entries) group.append(this.row(entry));
      this.list.append(group);
    }
    if (files.length === 0) this.list.append(h('div.empty', {}, 'No launch files in the packages\' share folders.'));
    this.element = h('section.launch-files', {},
      h('h2', {}, 'Launch files', h('span.count', {}, String(files.length))), this.list);
  }

  row(entry) {
    const kind = KIND[entry.file.split('.').pop().toLowerCase()] || '';
    const error = h('div.error-text');
    const form = h('div.launch-args', {}, h('div.hint', {}, 'Reading the file\'s arguments…'));
    const item = h('div.exe.launch-file', { dataset: { launch: `${entry.package}/${entry.path}` }, title: entry.path });
    let fields = null; // name -> input, once read
    const readArguments = async () => {
      if (fields) return;
      fields = new Map();
      try {
        const declared = await launchArguments(this.workspace, entry.package, entry.path);
        setChildren(form, declared.length ? declared.map((a) => this.field(a, fields)) : h('div.hint', {}, 'No arguments.'));
      } catch (e) {
        fields = null;
        setChildren(form, h('div.error-text', {}, e.message));
      }
    };
    const launch = async () => {
      error.textContent = '';
      const args = {};
      for (const [name, input] of fields || []) if (input.value !== '') args[name] = input.value;
      const run = new LaunchRun(this.session, entry.package, entry.path, args);
      run.onRviz = (uri) => this.onRviz && this.onRviz(uri);
      try {
        const proc = await run.start();
        if (this.onLaunch) this.onLaunch(proc);
      } catch (e) {
        error.textContent = e.message;
        item.classList.add('expanded');
      }
    };
    const button = h('button.run', { onclick: launch, title: `Launch ${entry.package} ${entry.file}`, disabled: !!entry.problem }, '▶ Launch');
    this.buttons.push({ button, problem: entry.problem });
    const toggle = h('button.icon', {
      title: 'Arguments',
      onclick: () => {
        item.classList.toggle('expanded');
        if (item.classList.contains('expanded')) readArguments();
      },
    }, '⋯');
    const runner = entry.runner === 'launch' ? 'run by Humble\'s launch on the build host' : 'read by colcon-wasm\'s launch reader';
    item.append(
      h('div.row', {}, h('span.name', {}, breakable(entry.file)), h('span.size', { title: runner }, kind), toggle, button),
      h('div.args', {}, form, error));
    if (entry.problem) item.append(h('div.reason', { title: entry.problem }, `Off: ${entry.problem.split(': ')[0]}.`));
    return item;
  }

  /** One argument's input: a select for choices; the default as placeholder; required marked. */
  field(argument, fields) {
    const label = `${argument.name}${argument.default === null ? ' (required)' : ''}`;
    let input;
    if (argument.choices && argument.choices.length) {
      input = h('select', { 'aria-label': argument.name },
        h('option', { value: '' }, argument.default === null ? '—' : `default: ${argument.default}`),
        ...argument.choices.map((c) => h('option', { value: c }, c)));
    } else {
      input = h('input', {
        type: 'text', spellcheck: false, 'aria-label': argument.name,
        placeholder: argument.default === null ? 'required' : argument.default,
      });
    }
    input.dataset.argument = argument.name;
    fields.set(argument.name, input);
    return h('label.launch-arg', { title: argument.description || argument.name },
      h('span.arg-name', {}, breakable(label)), input,
      argument.description ? h('span.hint', {}, argument.description) : null);
  }

  setEnabled(enabled) {
    for (const { button, problem } of this.buttons) button.disabled = !enabled || !!problem;
  }
}
