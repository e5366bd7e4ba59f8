// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Messages as YAML text, the way ROS users read and type them
 * (`ros2 topic echo` prints it, `ros2 topic pub` takes it).
 *
 * `formatYaml(value)` prints a decoded message in block style.
 * `parseYaml(text)` reads the YAML a user types into a publish or call form:
 * block and flow mappings and sequences, quoted and plain scalars, comments.
 * JSON is accepted too (it is YAML flow syntax). Not supported: anchors,
 * tags, multi-documents, block scalars (| and >).
 */

/** Text that is not YAML this parser reads; says where. */
export class YamlError extends Error {
  constructor(message, line) {
    super(line ? `line ${line}: ${message}` : message);
    this.name = 'YamlError';
    this.line = line;
  }
}

// ------------------------------------------------------------------ format

const PLAIN_SAFE = /^[A-Za-z_/][A-Za-z0-9_ ./:-]*$/;
const RESERVED = /^(true|false|yes|no|on|off|null|~|y|n)$/i;

function formatScalar(v) {
  if (typeof v === 'string') {
    if (v === '' || !PLAIN_SAFE.test(v) || RESERVED.test(v) || v.endsWith(' ') || /: /.test(v)) {
      return `'${v.replace(/'/g, "''")}'`;
    }
    return v;
  }
  if (typeof v === 'number') {
    if (Number.isNaN(v)) return '.nan';
    if (v === Infinity) return '.inf';
    if (v === -Infinity) return '-.inf';
    if (Number.isInteger(v) && !Object.is(v, -0)) return String(v);
    if (Object.is(v, -0)) return '-0.0'; // String(-0) is '0': the sign would be lost
    const s = String(v);
    return /[.e]/.test(s) ? s : `${s}.0`;
  }
  if (typeof v === 'bigint') return v.toString();
  if (typeof v === 'boolean') return v ? 'true' : 'false';
  if (v === null || v === undefined) return 'null';
  return String(v);
}

function isCollection(v) {
  return Array.isArray(v) || (ArrayBuffer.isView(v) && !(v instanceof DataView));
}

function isMapping(v) {
  return v !== null && typeof v === 'object' && !isCollection(v);
}

function isEmpty(v) {
  return isCollection(v) ? v.length === 0 : Object.keys(v).length === 0;
}

function blockLines(v, indent, maxArray) {
  const pad = ' '.repeat(indent);
  const lines = [];
  if (isMapping(v)) {
    for (const key of Object.keys(v)) {
      const child = v[key];
      if ((isMapping(child) || isCollection(child)) && !isEmpty(child)) {
        lines.push(`${pad}${key}:`);
        lines.push(...blockLines(child, isMapping(child) ? indent + 2 : indent, maxArray));
      } else if (isCollection(child)) {
        lines.push(`${pad}${key}: []`);
      } else if (isMapping(child)) {
        lines.push(`${pad}${key}: {}`);
      } else {
        lines.push(`${pad}${key}: ${formatScalar(child)}`);
      }
    }
    return lines;
  }
  const shown = Math.min(v.length, maxArray);
  for (let i = 0; i < shown; i++) {
    const item = v[i];
    if ((isMapping(item) || isCollection(item)) && !isEmpty(item)) {
      const inner = blockLines(item, indent + 2, maxArray);
      if (isMapping(item)) {
        inner[0] = `${pad}- ${inner[0].trimStart()}`;
        lines.push(...inner);
      } else {
        lines.push(`${pad}-`, ...inner);
      }
    } else if (isCollection(item)) {
      lines.push(`${pad}- []`);
    } else if (isMapping(item)) {
      lines.push(`${pad}- {}`);
    } else {
      lines.push(`${pad}- ${formatScalar(item)}`);
    }
  }
  if (shown < v.length) lines.push(`${pad}- '...' # ${v.length - shown} more, ${v.length} in all`);
  return lines;
}

/**
 * Format a decoded message (objects, arrays, typed arrays, BigInt) as YAML,
 * as `ros2 topic echo` prints it. Arrays longer than `maxArray` are cut with
 * a line saying how many elements were left out.
 */
export function formatYaml(value, { maxArray = 64 } = {}) {
  if (isMapping(value) || isCollection(value)) {
    if (isEmpty(value)) return isMapping(value) ? '{}' : '[]';
    return blockLines(value, 0, maxArray).join('\n');
  }
  return formatScalar(value);
}

// ------------------------------------------------------------------- parse

/** How deep [...] and {...} may nest. */
const MAX_DEPTH = 256;

/** Set a key of a mapping as its own property: a '__proto__' key must not set the prototype. */
function setKey(out, key, value) {
  if (key === '__proto__') Object.defineProperty(out, key, { value, enumerable: true, writable: true, configurable: true });
  else out[key] = value;
}

function stripComment(line) {
  let quote = null;
  for (let i = 0; i < line.length; i++) {
    const c = line[i];
    if (quote) {
      if (c === quote) {
        if (quote === "'" && line[i + 1] === "'") { i++; continue; }
        quote = null;
      } else if (c === '\\' && quote === '"') i++;
    } else if (c === '"' || c === "'") {
      quote = c;
    } else if (c === '#' && (i === 0 || /\s/.test(line[i - 1]))) {
      return line.slice(0, i);
    }
  }
  return line;
}

function parsePlain(text) {
  const t = text.trim();
  if (t === '' || t === '~' || t === 'null' || t === 'Null' || t === 'NULL') return null;
  if (/^(true|True|TRUE)$/.test(t)) return true;
  if (/^(false|False|FALSE)$/.test(t)) return false;
  if (/^[-+]?(0|[1-9][0-9_]*)$/.test(t)) {
    const digits = t.replace(/_/g, '');
    const n = Number(digits);
    return Number.isSafeInteger(n) ? n : BigInt(digits);
  }
  if (/^0x[0-9a-fA-F]+$/.test(t)) return Number.parseInt(t, 16);
  if (/^0o[0-7]+$/.test(t)) return Number.parseInt(t.slice(2), 8);
  if (/^[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?$/.test(t)) return Number(t);
  if (/^[-+]?\.(inf|Inf|INF)$/.test(t)) return t.startsWith('-') ? -Infinity : Infinity;
  if (/^\.(nan|NaN|NAN)$/.test(t)) return NaN;
  return t;
}

function unescapeDouble(body, line) {
  return body.replace(/\\(u[0-9a-fA-F]{4}|x[0-9a-fA-F]{2}|.)/g, (m, e) => {
    switch (e[0]) {
      case 'n': return '\n';
      case 't': return '\t';
      case 'r': return '\r';
      case '0': return '\0';
      case '"': return '"';
      case '\\': return '\\';
      case '/': return '/';
      case 'u': case 'x': return String.fromCharCode(parseInt(e.slice(1), 16));
      default: throw new YamlError(`unknown escape \\${e} in a double-quoted string`, line);
    }
  });
}

// Flow syntax ([a, b], {k: v}, quoted strings) on one logical text.
class Flow {
  constructor(text, line) {
    this.s = text;
    this.i = 0;
    this.line = line;
  }

  ws() { while (this.i < this.s.length && /\s/.test(this.s[this.i])) this.i++; }

  fail(message) { return new YamlError(`${message} at column ${this.i + 1}`, this.line); }

  value(stops) {
    this.ws();
    const c = this.s[this.i];
    if (c === '[') return this.seq();
    if (c === '{') return this.map();
    if (c === '"' || c === "'") return this.quoted();
    const start = this.i;
    while (this.i < this.s.length && !stops.includes(this.s[this.i])) {
      if (this.s[this.i] === ':' && stops.includes(':') && /\s|$/.test(this.s[this.i + 1] || '')) break;
      this.i++;
    }
    return parsePlain(this.s.slice(start, this.i));
  }

  quoted() {
    const q = this.s[this.i++];
    let out = '';
    while (this.i < this.s.length) {
      const c = this.s[this.i];
      if (q === "'" && c === "'" && this.s[this.i + 1] === "'") { out += "'"; this.i += 2; continue; }
      if (q === '"' && c === '\\') { out += this.s.slice(this.i, this.i + 2); this.i += 2; continue; }
      if (c === q) { this.i++; return q === '"' ? unescapeDouble(out, this.line) : out; }
      out += c;
      this.i++;
    }
    throw this.fail(`a ${q === '"' ? 'double' : 'single'}-quoted string is not closed`);
  }

  /** Count one more level of [...] or {...}: deeper than MAX_DEPTH is an error, not a stack overflow. */
  nest() {
    this.depth = (this.depth || 0) + 1;
    if (this.depth > MAX_DEPTH) throw this.fail(`flow collections nested deeper than ${MAX_DEPTH} levels`);
  }

  seq() {
    this.nest();
    try {
      return this.seqItems();
    } finally {
      this.depth--;
    }
  }

  seqItems() {
    this.i++;
    const out = [];
    this.ws();
    if (this.s[this.i] === ']') { this.i++; return out; }
    for (;;) {
      out.push(this.value([',', ']']));
      this.ws();
      const c = this.s[this.i++];
      if (c === ']') return out;
      if (c !== ',') throw this.fail("expected ',' or ']' in a [...] sequence");
      this.ws();
      if (this.s[this.i] === ']') { this.i++; return out; }
    }
  }

  map() {
    this.nest();
    try {
      return this.mapItems();
    } finally {
      this.depth--;
    }
  }

  mapItems() {
    this.i++;
    const out = {};
    this.ws();
    if (this.s[this.i] === '}') { this.i++; return out; }
    for (;;) {
      this.ws();
      const key = this.s[this.i] === '"' || this.s[this.i] === "'" ? this.quoted() : this.value([':', ',', '}']);
      this.ws();
      if (this.s[this.i] !== ':') throw this.fail(`expected ':' after the key '${key}' in a {...} mapping`);
      this.i++;
      setKey(out, String(key), this.value([',', '}']));
      this.ws();
      const c = this.s[this.i++];
      if (c === '}') return out;
      if (c !== ',') throw this.fail("expected ',' or '}' in a {...} mapping");
      this.ws();
      if (this.s[this.i] === '}') { this.i++; return out; }
    }
  }

  all() {
    const v = this.value([]);
    this.ws();
    if (this.i < this.s.length) throw this.fail(`unexpected '${this.s.slice(this.i, this.i + 10)}'`);
    return v;
  }
}

function scalarOrFlow(text, line) {
  const t = text.trim();
  if (t.startsWith('[') || t.startsWith('{') || t.startsWith('"') || t.startsWith("'")) {
    return new Flow(t, line).all();
  }
  return parsePlain(t);
}

function splitKey(content, line) {
  // key: value, with quoted keys allowed; ':' must be followed by space or end
  let i = 0;
  if (content[0] === '"' || content[0] === "'") {
    const f = new Flow(content, line);
    const key = f.quoted();
    const rest = content.slice(f.i).trimStart();
    if (!rest.startsWith(':')) return null;
    return [key, rest.slice(1)];
  }
  for (; i < content.length; i++) {
    if (content[i] === ':' && (i + 1 === content.length || content[i + 1] === ' ')) {
      return [content.slice(0, i).trim(), content.slice(i + 1)];
    }
    if (content[i] === '[' || content[i] === '{' || content[i] === '"' || content[i] === "'") return null;
  }
  return null;
}

/**
 * Parse YAML (or JSON) text as typed by a user.
 * Integers beyond 2^53 become BigInt.
 */
export function parseYaml(text) {
  const trimmed = text.trim();
  if (trimmed === '') return {};
  const raw = text.replace(/\t/g, '  ').split(/\r?\n/);
  const lines = [];
  for (let n = 0; n < raw.length; n++) {
    const content = stripComment(raw[n]).replace(/\s+$/, '');
    if (content.trim() === '' || content.trim() === '---') continue;
    lines.push({ indent: content.length - content.trimStart().length, text: content.trim(), line: n + 1 });
  }
  if (lines.length === 0) return {};
  // A flow value may span lines: join everything when the document is flow.
  if (/^[[{]/.test(lines[0].text)) {
    return new Flow(lines.map((l) => l.text).join(' '), lines[0].line).all();
  }
  let pos = 0;
  const block = (indent) => {
    const first = lines[pos];
    if (first.text.startsWith('- ') || first.text === '-') {
      const out = [];
      while (pos < lines.length && lines[pos].indent === indent &&
             (lines[pos].text.startsWith('- ') || lines[pos].text === '-')) {
        const item = lines[pos];
        const rest = item.text === '-' ? '' : item.text.slice(2).trimStart();
        if (rest === '') {
          pos++;
          if (pos < lines.length && lines[pos].indent > indent) out.push(block(lines[pos].indent));
          else out.push(null);
        } else if (splitKey(rest, item.line)) {
          // "- key: value" starts a mapping whose keys sit at indent + 2
          const inner = indent + (item.text.length - rest.length);
          lines[pos] = { indent: inner, text: rest, line: item.line };
          out.push(block(inner));
        } else {
          out.push(scalarOrFlow(rest, item.line));
          pos++;
        }
      }
      return out;
    }
    const out = {};
    while (pos < lines.length && lines[pos].indent === indent) {
      const { text: content, line } = lines[pos];
      const kv = splitKey(content, line);
      if (!kv) {
        if (indent === 0 && lines.length === 1) {
          pos++;
          return scalarOrFlow(content, line);
        }
        throw new YamlError(`expected 'key: value', found '${content}'`, line);
      }
      const [key, rest] = kv;
      if (Object.prototype.hasOwnProperty.call(out, key)) {
        throw new YamlError(`the key '${key}' appears twice`, line);
      }
      pos++;
      if (rest.trim() === '') {
        if (pos < lines.length && (lines[pos].indent > indent ||
            (lines[pos].indent === indent && lines[pos].text.startsWith('-')))) {
          setKey(out, key, block(lines[pos].indent));
        } else {
          setKey(out, key, null);
        }
      } else {
        setKey(out, key, scalarOrFlow(rest, line));
      }
    }
    if (pos < lines.length && lines[pos].indent > indent) {
      throw new YamlError(`unexpected indentation of '${lines[pos].text}'`, lines[pos].line);
    }
    return out;
  };
  const result = block(lines[0].indent);
  if (pos < lines.length) {
    throw new YamlError(`unexpected '${lines[pos].text}' (check the indentation)`, lines[pos].line);
  }
  return result;
}
