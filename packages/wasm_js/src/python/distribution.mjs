// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Packages of Pyodide's distribution that a Python node imports (numpy, PyYAML, ...).
 *
 * Before the script runs, its imports (and those of an entry point's module)
 * are found with Pyodide's own `pyodide.code.find_imports`; each one that is
 * not importable already and that the Pyodide folder's `pyodide-lock.json`
 * names (its `imports`) is a package of the distribution. When its wheel is
 * in that folder (a full Pyodide release, given with `--pyodide DIR`), it is
 * loaded with `pyodide.loadPackage`, with what it depends on, from there:
 * nothing is fetched from elsewhere. When it is not (the npm package carries
 * no wheels), the import fails with a ModuleNotFoundError that names the
 * package, its wheel and the folder (rclpy/_native_only.py).
 *
 * @module python/distribution
 */

/** The Python side: the top-level modules a script and its entry point's module import. */
const IMPORTS = `
def _colcon_wasm_imports(source, module):
    import importlib.util
    from pyodide.code import find_imports
    names = set(find_imports(source))
    if module:
        try:
            spec = importlib.util.find_spec(module)
        except (ImportError, ValueError):
            spec = None
        if spec is not None and spec.origin and spec.origin.endswith('.py'):
            with open(spec.origin, encoding='utf-8') as f:
                names |= set(find_imports(f.read()))
    missing = []
    for name in sorted(n.split('.')[0] for n in names):
        try:
            found = importlib.util.find_spec(name) is not None
        except (ImportError, ValueError):
            found = False
        if not found and name not in missing:
            missing.append(name)
    return missing
`;

/**
 * Read the lock file of a Pyodide folder.
 * @param {string} indexURL the folder (Node.js: a path ending in '/') or its URL
 * @param {boolean} isNode
 * @returns {Promise<object|null>} null when there is none
 */
async function readLock(indexURL, isNode) {
  try {
    if (isNode) {
      const fs = await import('node:fs');
      return JSON.parse(fs.readFileSync(`${indexURL}pyodide-lock.json`, 'utf8'));
    }
    const response = await fetch(new URL('pyodide-lock.json', indexURL));
    return response.ok ? await response.json() : null;
  } catch (e) {
    return null;
  }
}

/** Tell whether the folder has a wheel. */
async function hasFile(indexURL, file, isNode) {
  if (isNode) {
    const fs = await import('node:fs');
    return fs.existsSync(`${indexURL}${file}`);
  }
  try {
    const response = await fetch(new URL(file, indexURL), { method: 'HEAD' });
    return response.ok;
  } catch (e) {
    return false;
  }
}

/**
 * Load what the node imports of Pyodide's distribution, from the Pyodide folder.
 * @param {object} pyodide the node's Pyodide
 * @param {object} options
 * @param {string} options.source the script's text
 * @param {string} [options.module] an entry point's module
 * @param {string} options.indexURL the Pyodide folder (or URL)
 * @param {boolean} options.isNode
 * @param {function(string, string): void} options.log the node's output (stream, text)
 * @returns {Promise<Object<string, string[]>>} the modules of packages whose wheel is not
 *   there: module -> [package, version, wheel file, folder]
 */
export async function loadDistributionPackages(pyodide, { source, module, indexURL, isNode, log }) {
  pyodide.runPython(IMPORTS, { filename: '<colcon-wasm distribution>' });
  const find = pyodide.globals.get('_colcon_wasm_imports');
  const result = find(source, module || null);
  const wanted = result.toJs();
  result.destroy();
  find.destroy();
  if (!wanted.length) return {};
  const lock = await readLock(indexURL, isNode);
  if (!lock || !lock.packages) return {};
  const byImport = new Map();
  for (const [name, info] of Object.entries(lock.packages)) {
    for (const top of info.imports || []) byImport.set(top, { name, info });
  }
  const load = [];
  const absent = {};
  for (const top of wanted) {
    const entry = byImport.get(top);
    if (!entry) continue;
    if (await hasFile(indexURL, entry.info.file_name, isNode)) {
      load.push(entry.name);
    } else {
      absent[top] = [entry.name, String(entry.info.version || ''), entry.info.file_name,
        isNode ? indexURL.replace(/\/$/, '') : indexURL];
    }
  }
  if (load.length) {
    await pyodide.loadPackage(load, {
      messageCallback: () => {},
      errorCallback: (text) => log('stderr', text),
      checkIntegrity: true,
    });
  }
  return absent;
}
