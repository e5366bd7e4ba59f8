// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The executables of the install space, grouped by package: run any of them
// with arguments, as often as wanted (each run is a new process).

import { breakable, formatBytes, h, splitArgs } from '../dom.mjs';

/**
 * Why the Python buttons are off, under them: its first clause, and the
 * whole text (with the command that installs Pyodide) one click away.
 */
function pythonReason(problem) {
  const text = problem || 'this serve does not serve Pyodide: start it with --pyodide DIR';
  const short = text.split(/: |, and /)[0];
  return h('div.reason#python-reason', { title: text }, `Off: ${short}.`,
    short === text ? null : h('details', {}, h('summary', {}, 'how to fix'), h('div.mono', {}, text)));
}

export class ExecutablesView {
  constructor(session, workspace) {
    this.session = session;
    this.buttons = [];
    const filter = h('input.filter', {
      type: 'search', placeholder: 'Filter executables…', oninput: () => this.filter(filter.value),
    });
    this.list = h('div.packages');
    let total = 0;
    for (const pkg of workspace.packages) {
      const group = h('details.package', { open: true, dataset: { package: pkg.name } },
        h('summary', {}, pkg.name, pkg.version ? h('span.version', {}, pkg.version) : null));
      for (const exe of pkg.executables) {
        group.append(this.row(pkg, exe));
        total++;
      }
      this.list.append(group);
    }
    if (total === 0) this.list.append(h('div.empty', {}, 'No executables found.'));
    this.element = h('section.executables', {},
      h('h2', {}, 'Executables', h('span.count', {}, String(total))),
      total > 6 ? filter : null, this.list, this.pythonRow(workspace));
  }

  /** Run a Python file (rclpy on Pyodide) picked from disk. */
  pythonRow(workspace) {
    const python = workspace.python || {};
    const file = h('input#python-file', { type: 'file', accept: '.py', hidden: true });
    const args = h('input#python-args', { type: 'text', placeholder: 'arguments', spellcheck: false, 'aria-label': 'arguments of the Python node' });
    const button = h('button#python-run', {
      title: python.pyodide ? 'run a Python node (rclpy) in a worker of this page' : (python.problem || 'Pyodide is not served'),
      disabled: !python.pyodide,
    }, 'Run Python file…');
    button.onclick = () => file.click();
    const consoleButton = h('button#python-console', {
      title: python.pyodide ? 'a Python REPL with rclpy on this page\'s bus: type into the log dock' : (python.problem || 'Pyodide is not served'),
      disabled: !python.pyodide,
      onclick: () => this.session.startPythonConsole().then((proc) => this.onConsole && this.onConsole(proc.id)).catch((e) => { consoleButton.title = e.message; }),
    }, 'Python console');
    const error = h('div.error-text');
    file.onchange = async () => {
      const f = file.files[0];
      if (!f) return;
      file.value = '';
      let argv;
      try {
        argv = splitArgs(args.value);
      } catch (e) {
        error.textContent = `arguments of ${f.name}: ${e.message}; it was not started`;
        return;
      }
      error.textContent = '';
      this.session.startPython(f.name, await f.text(), argv);
    };
    this.pythonButtons = { buttons: [button, consoleButton], available: !!python.pyodide };
    return h('details.package.python', { open: true }, h('summary', {}, 'Python (rclpy)'),
      h('div.row', {}, button, args, file), error, h('div.row', {}, consoleButton),
      python.pyodide ? null : pythonReason(python.problem));
  }

  row(pkg, exe) {
    const args = h('input', {
      type: 'text', placeholder: '--ros-args -r chatter:=news -p rate:=2',
      spellcheck: false, 'aria-label': `arguments of ${pkg.name}/${exe.name}`,
      onkeydown: (e) => { if (e.key === 'Enter') run(); },
    });
    const error = h('div.error-text');
    const item = h('div.exe', { dataset: { exe: `${pkg.name}/${exe.name}` }, title: exe.url });
    const run = () => {
      error.textContent = '';
      let argv;
      try {
        argv = splitArgs(args.value);
      } catch (e) {
        error.textContent = `arguments: ${e.message}`;
        item.classList.add('expanded');
        return;
      }
      this.session.startProcess(pkg.name, exe.name, argv);
    };
    const button = h('button.run', { onclick: run, title: `Start ${pkg.name}/${exe.name}` }, '▶ Run');
    this.buttons.push(button);
    const toggle = h('button.icon', {
      title: 'Arguments', onclick: () => { item.classList.toggle('expanded'); args.focus(); },
    }, '⋯');
    item.append(
      h('div.row', {}, h('span.name', {}, breakable(exe.name)),
        exe.python
          ? h('span.size', { title: `Python entry point ${exe.python.module}:${exe.python.function} (Pyodide)` }, 'Python')
          : h('span.size', { title: 'download size (gzip)' }, formatBytes(exe.gzip_size || exe.size)),
        toggle, button),
      h('div.args', {}, args,
        h('div.hint', {}, 'ROS arguments as on the command line; Enter runs it.'), error));
    return item;
  }

  filter(text) {
    const needle = text.trim().toLowerCase();
    for (const item of this.list.querySelectorAll('.exe')) {
      item.hidden = needle !== '' && !item.dataset.exe.toLowerCase().includes(needle);
    }
  }

  setEnabled(enabled) {
    for (const b of this.buttons) b.disabled = !enabled;
    if (this.pythonButtons) {
      for (const b of this.pythonButtons.buttons) b.disabled = !enabled || !this.pythonButtons.available;
    }
  }
}
