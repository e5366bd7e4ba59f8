// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// What a hostile Zenoh peer's liveliness tokens cost the gateway
// (tests/test_security.py, docs/security.md): the gateway's RemoteGraph, as
// the gateway's worker feeds it, with tokens a peer declares.
//
//   node security_zenoh.mjs   -> {ok, malformed, warnings, entities, otherDomain, own}

import { Kind, tokenKey } from '../../packages/wasm_js/src/bridges/zenoh/keys.mjs';
import { RemoteGraph } from '../../packages/wasm_js/src/bridges/zenoh/remote_graph.mjs';

const OWN = 'aa00000000000000000000000000000b';
const PEER = '1f2e3d4c5b6a79880716253443526170';
const warnings = [];
const graph = new RemoteGraph({
  domain: 0, ownZid: () => OWN, log: (level, text) => warnings.push(`${level} ${text}`), onChange: () => {},
});
const node = (zid, domain, i) => tokenKey({
  domain, zid, nodeId: i, id: i, kind: Kind.NODE, enclave: '/', namespace: '/', node: `n${i}`,
});

// 500 different malformed tokens: each counted, at most 32 named in the log
for (let i = 0; i < 500; i++) graph.sample({ kind: 'put', key: `@ros2_lv/0/${PEER}/${i}/${i}/X${i}/%/%/n` });
// tokens of another domain, and tokens that claim the gateway's own session: not taken
for (let i = 0; i < 100; i++) graph.sample({ kind: 'put', key: node(PEER, 7, i) });
for (let i = 0; i < 100; i++) graph.sample({ kind: 'put', key: node(OWN, 0, i) });
const otherDomain = graph.entities.size;
// 2000 valid tokens of one peer: each one is held (the remote graph has no bound)
for (let i = 0; i < 2000; i++) graph.sample({ kind: 'put', key: node(PEER, 0, i) });
const entities = graph.entities.size;
// and each goes with its delete
for (let i = 0; i < 2000; i++) graph.sample({ kind: 'delete', key: node(PEER, 0, i) });

process.stdout.write(`${JSON.stringify({
  ok: true, malformed: graph.malformed, warnings: warnings.length, lastWarning: warnings[warnings.length - 1],
  otherDomain, entities, afterDeletes: graph.entities.size,
})}\n`);
