// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * What the bridges' WebSocket servers (rosbridge, Foxglove) share around
 * their `http.Server`: listening, with an error that says what to do when
 * the port cannot be had, and closing the sessions with a closing
 * handshake first.
 *
 * @module bridges/common/listen
 */

/**
 * Listen on host:port; resolves to the port (the one picked for port 0).
 * @param {import('node:http').Server} server
 * @param {object} options
 * @param {string} options.host
 * @param {number} options.port
 * @param {string} options.option the command-line option, e.g. --rosbridge
 * @param {string} options.other what else may hold the port, e.g. 'another rosbridge server'
 * @param {function(new: Error, string)} options.ErrorClass the error to reject with
 * @returns {Promise<number>}
 */
export function listen(server, { host, port, option, other, ErrorClass }) {
  return new Promise((resolve, reject) => {
    const onError = (e) => {
      const where = `${host}:${port}`;
      if (e.code === 'EADDRINUSE') {
        reject(new ErrorClass(`port ${port} on ${host} is already in use (${other}, `
          + `or another server?): stop it, or pass ${option} HOST:PORT (port 0 picks a free port)`));
      } else if (e.code === 'EACCES') {
        reject(new ErrorClass(`no permission to listen on port ${port} of ${host}: use a port above 1023`));
      } else if (e.code === 'EADDRNOTAVAIL' || e.code === 'ENOTFOUND') {
        reject(new ErrorClass(`cannot listen on ${where}: ${host} is not an address of this machine`));
      } else {
        reject(new ErrorClass(`cannot listen on ${where}: ${e.message}`));
      }
    };
    server.once('error', onError);
    server.listen(port, host, () => {
      server.off('error', onError);
      resolve(server.address().port);
    });
  });
}

/**
 * Stop listening and close every session: the closing handshake first, at
 * most `graceMs`, then the sockets.
 * @param {import('node:http').Server} server
 * @param {Iterable<{conn: object, end: function(): void}>} sessions
 * @param {number} graceMs
 */
export async function closeAll(server, sessions, graceMs) {
  const closing = new Promise((resolve) => server.close(() => resolve()));
  await Promise.all([...sessions].map(async (s) => {
    const ended = new Promise((resolve) => {
      const previous = s.conn.onclose;
      s.conn.onclose = (e) => { if (previous) previous(e); resolve(); };
    });
    s.conn.close(1001, 'the server is stopping');
    await Promise.race([ended, new Promise((r) => setTimeout(r, graceMs))]);
    s.end();
    s.conn.terminate();
  }));
  await closing;
}
