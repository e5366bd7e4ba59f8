// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The wire format of the Foxglove WebSocket protocol (foxglove/ws-protocol,
 * `foxglove.websocket.v1`; `foxglove.sdk.v1` frames these messages the same
 * way): the subprotocols, the capabilities, and the binary messages, which
 * start with a one-byte opcode and carry little-endian integers. JSON
 * messages are plain objects with an `op`. No logic here.
 *
 * @module bridges/foxglove/protocol
 */

/** The subprotocols served, preferred first. */
export const SUBPROTOCOLS = Object.freeze(['foxglove.sdk.v1', 'foxglove.websocket.v1']);

/** Opcodes of the server's binary messages. */
export const ServerBinary = Object.freeze({ MESSAGE_DATA: 1, TIME: 2, SERVICE_CALL_RESPONSE: 3, FETCH_ASSET_RESPONSE: 4 });

/** Opcodes of the client's binary messages. */
export const ClientBinary = Object.freeze({ MESSAGE_DATA: 1, SERVICE_CALL_REQUEST: 2 });

/** Levels of a status message. */
export const StatusLevel = Object.freeze({ INFO: 0, WARNING: 1, ERROR: 2 });

/** Capabilities a server may declare in its serverInfo. */
export const Capability = Object.freeze({
  clientPublish: 'clientPublish', parameters: 'parameters', parametersSubscribe: 'parametersSubscribe',
  services: 'services', connectionGraph: 'connectionGraph', time: 'time', assets: 'assets',
});

const enc = new TextEncoder();
const dec = new TextDecoder();

/** The 9-byte header of a MESSAGE_DATA message (opcode, subscription id, timestamp in ns). */
export function messageDataHeader(subscriptionId, timestampNs) {
  const header = new Uint8Array(13);
  const view = new DataView(header.buffer);
  view.setUint8(0, ServerBinary.MESSAGE_DATA);
  view.setUint32(1, subscriptionId, true);
  view.setBigUint64(5, timestampNs, true);
  return header;
}

/** A MESSAGE_DATA message: the header, then the message's bytes as the bus carried them. */
export function messageData(subscriptionId, timestampNs, data) {
  const out = new Uint8Array(13 + data.byteLength);
  out.set(messageDataHeader(subscriptionId, timestampNs));
  out.set(data, 13);
  return out;
}

/** A TIME message. */
export function timeMessage(timestampNs) {
  const out = new Uint8Array(9);
  const view = new DataView(out.buffer);
  view.setUint8(0, ServerBinary.TIME);
  view.setBigUint64(1, timestampNs, true);
  return out;
}

/** A SERVICE_CALL_RESPONSE message. */
export function serviceCallResponse(serviceId, callId, encoding, data) {
  const name = enc.encode(encoding);
  const out = new Uint8Array(13 + name.length + data.byteLength);
  const view = new DataView(out.buffer);
  view.setUint8(0, ServerBinary.SERVICE_CALL_RESPONSE);
  view.setUint32(1, serviceId, true);
  view.setUint32(5, callId, true);
  view.setUint32(9, name.length, true);
  out.set(name, 13);
  out.set(data, 13 + name.length);
  return out;
}

/**
 * A FETCH_ASSET_RESPONSE message: the file's bytes, or (with `error`) status 1 and the error text.
 * @param {number} requestId
 * @param {?string} error
 * @param {Uint8Array} [data]
 */
export function fetchAssetResponse(requestId, error, data = new Uint8Array(0)) {
  const text = enc.encode(error || '');
  const body = error ? new Uint8Array(0) : data;
  const out = new Uint8Array(10 + text.length + body.byteLength);
  const view = new DataView(out.buffer);
  view.setUint8(0, ServerBinary.FETCH_ASSET_RESPONSE);
  view.setUint32(1, requestId, true);
  view.setUint8(5, error ? 1 : 0);
  view.setUint32(6, text.length, true);
  out.set(text, 10);
  out.set(body, 10 + text.length);
  return out;
}

/** A client's binary message that cannot be read: the message says why. */
export class ProtocolError extends Error {
  constructor(message) {
    super(message);
    this.name = 'ProtocolError';
  }
}

/**
 * Read a client's binary message.
 * @param {Uint8Array} bytes
 * @returns {{op: number, channelId?: number, serviceId?: number, callId?: number, encoding?: string, data: Uint8Array}}
 * @throws {ProtocolError} for an unknown opcode or a short message
 */
export function parseClientBinary(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const need = (n, what) => {
    if (bytes.byteLength < n) throw new ProtocolError(`a binary ${what} message of ${bytes.byteLength} bytes is too short (at least ${n})`);
  };
  need(1, 'client');
  const op = view.getUint8(0);
  if (op === ClientBinary.MESSAGE_DATA) {
    need(5, 'message data');
    return { op, channelId: view.getUint32(1, true), data: bytes.subarray(5) };
  }
  if (op === ClientBinary.SERVICE_CALL_REQUEST) {
    need(13, 'service call request');
    const length = view.getUint32(9, true);
    need(13 + length, 'service call request');
    return {
      op, serviceId: view.getUint32(1, true), callId: view.getUint32(5, true),
      encoding: dec.decode(bytes.subarray(13, 13 + length)), data: bytes.subarray(13 + length),
    };
  }
  throw new ProtocolError(`unknown binary opcode 0x${op.toString(16).padStart(2, '0')}: clients send `
    + '0x01 (message data) and 0x02 (service call request)');
}
