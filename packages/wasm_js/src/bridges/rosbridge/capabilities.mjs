// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * What a WebSocket client may do (`--rosbridge-capabilities FILE`): lists of
 * name patterns per verb, as rosbridge_server's topics_glob /
 * services_glob / actions_glob but per verb:
 *
 *   {"publish":   ["/cmd_vel"],            # advertise + publish on topics
 *    "subscribe": ["/chatter", "/camera/*"],
 *    "call":      ["/add_two_ints", "/rosapi/*", "/fibonacci"],  # services, action goals
 *    "advertise": ["/my_service", "/my_action"]}                # advertise_service, advertise_action
 *
 * Patterns are fnmatch globs (`*` matches any characters, `/` too; `?` one
 * character; `[abc]`). A verb that the list does not name is refused for
 * every name; without a list everything is allowed.
 *
 * @module bridges/rosbridge/capabilities
 */

export const VERBS = Object.freeze(['publish', 'subscribe', 'call', 'advertise']);

function globToRegExp(glob) {
  let re = '';
  for (let i = 0; i < glob.length; i++) {
    const c = glob[i];
    if (c === '*') re += '.*';
    else if (c === '?') re += '.';
    else if (c === '[') {
      const end = glob.indexOf(']', i + 1);
      if (end < 0) re += '\\[';
      else {
        let body = glob.slice(i + 1, end);
        if (body.startsWith('!')) body = `^${body.slice(1)}`;
        re += `[${body.replace(/\\/g, '\\\\')}]`;
        i = end;
      }
    } else re += c.replace(/[.+^${}()|\\]/g, '\\$&');
  }
  return new RegExp(`^${re}$`);
}

/** A client's permissions. */
export class Capabilities {
  /**
   * @param {object|null} spec {publish, subscribe, call, advertise: string[]} or null (everything)
   * @throws {Error} naming the key or value that is wrong
   */
  constructor(spec) {
    this.spec = spec;
    this._rules = null;
    if (spec === null || spec === undefined) return;
    if (typeof spec !== 'object' || Array.isArray(spec)) throw new Error('a capability list must be a mapping of verbs to name patterns');
    this._rules = {};
    for (const [verb, patterns] of Object.entries(spec)) {
      if (!VERBS.includes(verb)) throw new Error(`unknown capability '${verb}': use ${VERBS.join(', ')}`);
      if (!Array.isArray(patterns) || !patterns.every((p) => typeof p === 'string')) {
        throw new Error(`capability '${verb}' must be a list of name patterns (strings)`);
      }
      this._rules[verb] = patterns.map((p) => ({ pattern: p, re: globToRegExp(p) }));
    }
  }

  /** True when `verb` is allowed on `name` (a topic, service or action name). */
  allows(verb, name) {
    if (!this._rules) return true;
    const rules = this._rules[verb];
    if (!rules) return false;
    const full = name.startsWith('/') ? name : `/${name}`;
    return rules.some((r) => r.re.test(full) || r.re.test(name));
  }

  /** Why `verb` on `name` is refused, for a status error. */
  refusal(verb, name) {
    const rules = this._rules && this._rules[verb];
    return `not allowed to ${verb} '${name}': the capability list of this server ${rules && rules.length
      ? `allows '${verb}' only for ${rules.map((r) => r.pattern).join(', ')}` : `grants no '${verb}'`}`;
  }
}
