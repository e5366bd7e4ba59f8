// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Fuzz target: the page's YAML reader (packages/wasm_js/src/page/yaml.mjs,
 * what a user types as a message, a service request or a parameter value)
 * and the `.rviz` reader of the 3D view
 * (templates/launcher/views/scene/rviz_file.mjs, its pure part: text in,
 * display settings out; it needs no DOM). An input is a text: parseYaml
 * gives a value or a YamlError; what it gives must format (formatYaml)
 * and read back to the same value; readRviz gives settings, a YamlError or
 * its "not an rviz configuration" Error. Any other exception is a finding,
 * and so is a decoded mapping whose prototype a key changed.
 *
 * rviz_file.mjs imports yaml.mjs as the page's files are laid out when
 * served (wasm_js/ beside launcher/): both are copied into that layout in
 * a temporary folder and imported from there, unchanged.
 *
 * Seeds (`--capture`): the project's own .rviz files (the demo robot's, the
 * 3D view test's), and YAML documents as the page's forms write them
 * (formatYaml of decoded messages).
 */

import assert from 'node:assert/strict';
import { cpSync, mkdirSync, mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

export const options = { json: false };

const enc = new TextEncoder();
const dec = new TextDecoder();

async function load(repo) {
  const site = mkdtempSync(join(tmpdir(), 'fuzz-page-'));
  mkdirSync(join(site, 'launcher', 'views', 'scene'), { recursive: true });
  mkdirSync(join(site, 'wasm_js', 'page'), { recursive: true });
  cpSync(join(repo, 'templates', 'launcher', 'views', 'scene', 'rviz_file.mjs'), join(site, 'launcher', 'views', 'scene', 'rviz_file.mjs'));
  cpSync(join(repo, 'packages', 'wasm_js', 'src', 'page', 'yaml.mjs'), join(site, 'wasm_js', 'page', 'yaml.mjs'));
  const yaml = await import(pathToFileURL(join(site, 'wasm_js', 'page', 'yaml.mjs')).href);
  const rviz = await import(pathToFileURL(join(site, 'launcher', 'views', 'scene', 'rviz_file.mjs')).href);
  return { ...yaml, ...rviz };
}

/** The seed corpus: the project's .rviz files and YAML as formatYaml writes it. */
export async function capture({ repo }) {
  const { formatYaml } = await load(repo);
  const seeds = [];
  for (const [name, path] of [['demo-robot.rviz', 'demo/robot/demo_robot/rviz/demo.rviz'], ['demo-arm.rviz', 'tests/data/scene/demo_arm.rviz']]) {
    // the first 3 KB: the displays, the global options and the view come first
    const text = readFileSync(join(repo, path), 'utf-8');
    seeds.push({ name, bytes: enc.encode(text.length > 3000 ? text.slice(0, text.lastIndexOf('\n', 3000)) : text) });
  }
  const values = {
    'message.yaml': { header: { stamp: { sec: 12, nanosec: 5 }, frame_id: 'base_link' }, data: [1, 2, 3], label: 'a: b # c', big: 18446744073709551615n },
    'parameters.yaml': { rate: 5.5, name: 'talker', enabled: true, names: ['a', 'b'], nested: { empty: [], none: null, quote: "it's" } },
    'list.yaml': [{ x: 1.5, y: -2 }, { x: 0, y: 1e-9 }],
    'scalar.yaml': 'just text',
  };
  for (const [name, value] of Object.entries(values)) seeds.push({ name, bytes: enc.encode(formatYaml(value)) });
  seeds.push({ name: 'flow.yaml', bytes: enc.encode('{data: [1, 2, {a: "x, y"}], s: \'q\'\'s\', n: ~}') });
  return seeds;
}

export async function setup({ repo, finding }) {
  const { parseYaml, formatYaml, YamlError, readRviz } = await load(repo);
  const rvizSeed = readFileSync(join(repo, 'tests', 'data', 'scene', 'demo_arm.rviz'), 'utf-8');
  const expected = readRviz(rvizSeed);
  const protoChanged = (v, depth = 0) => {
    if (depth > 64 || v === null || typeof v !== 'object') return false;
    if (!Array.isArray(v) && !ArrayBuffer.isView(v) && Object.getPrototypeOf(v) !== Object.prototype) return true;
    return Object.values(v).some((x) => protoChanged(x, depth + 1));
  };
  const messageLike = (v, depth = 0) => {
    if (depth > 32) return false;
    if (typeof v === 'string') return !/[\u0000-\u001f\u007f\ufffd]/.test(v);
    if (v === null || typeof v !== 'object') return true;
    if (Array.isArray(v)) return v.every((x) => messageLike(x, depth + 1));
    return Object.keys(v).length > 0 && Object.entries(v).every(([k, x]) => /^[A-Za-z_][A-Za-z0-9_]*$/.test(k) && messageLike(x, depth + 1));
  };
  return {
    coverageFiles: ['/wasm_js/page/yaml.mjs', '/views/scene/rviz_file.mjs'],
    one(input) {
      const text = dec.decode(input);
      let outcome;
      let value;
      try {
        value = parseYaml(text);
        outcome = `yaml ${value === null ? 'null' : Array.isArray(value) ? 'list' : typeof value}`;
      } catch (e) {
        if (!(e instanceof YamlError)) throw e;
        outcome = `YamlError ${e.message.replace(/'[^']*'/g, 'Q')}`;
      }
      if (value !== undefined) {
        if (protoChanged(value)) finding('prototype', 'a key of the YAML text set the prototype of a decoded mapping');
        // what the page formats is a message: field names as keys, printable strings
        if (messageLike(value)) {
          const again = parseYaml(formatYaml(value, { maxArray: Infinity }));
          assert.deepEqual(again, value, 'formatYaml then parseYaml gives another value');
        }
      }
      try {
        const settings = readRviz(text);
        outcome += ` | rviz ${settings.displays.length ? 'displays' : 'none'}`;
      } catch (e) {
        if (!(e instanceof YamlError) && !/^not an rviz configuration/.test(e.message)) throw e;
        outcome += ' | rviz refused';
      }
      return outcome;
    },
    check() {
      assert.deepEqual(readRviz(rvizSeed), expected);
      assert.deepEqual(parseYaml('a: 1\nb: [x, 2]'), { a: 1, b: ['x', 2] });
    },
  };
}
