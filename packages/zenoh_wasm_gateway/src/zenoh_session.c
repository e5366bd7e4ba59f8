// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/*
 * One zenoh-pico session for the Zenoh gateway of colcon-wasm
 * (wasm_js/src/bridges/zenoh/). zenoh-pico runs single-threaded: the
 * gateway's JavaScript calls zg_spin() when the link has a batch to read and
 * on a timer for keep-alives and the lease. Entities are handles (pointers)
 * the JavaScript side keeps; samples, queries and replies go to JavaScript
 * through the imports of zenoh_session_js.js, with the JavaScript id the
 * entity was declared with.
 *
 * The link: zenoh-pico's WebSocket link (datagram flow: one batch per
 * message) with its socket functions defined here over a JavaScript socket
 * (a WebSocket, or in Node.js a TCP socket whose stream JavaScript splits
 * into batches). These definitions take the place of zenoh-pico's
 * src/system/emscripten/network.c, which the linker then leaves out of
 * libzenohpico.a. Reads never wait, except while z_open() runs its
 * handshake: then zg_js_wait_readable() suspends (Asyncify) until the
 * socket has a batch or the timeout passes.
 */

#include <emscripten.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "zenoh-pico.h"
#include "zenoh-pico/system/link/ws.h"

/* the imports (zenoh_session_js.js) */
extern int zg_js_connect(const char *address, uint32_t timeout_ms);
extern int zg_js_read(int socket, uint8_t *ptr, size_t len);
extern int zg_js_wait_readable(int socket, uint32_t timeout_ms);
extern int zg_js_send(int socket, const uint8_t *ptr, size_t len);
extern void zg_js_close(int socket);
extern void zg_js_sample(int id, int kind, const char *key, size_t key_len, const uint8_t *payload, size_t len,
                         const uint8_t *attachment, size_t attachment_len);
extern void zg_js_query(int id, z_owned_query_t *query, const char *key, size_t key_len, const uint8_t *payload,
                        size_t len, const uint8_t *attachment, size_t attachment_len);
extern void zg_js_reply(int id, int ok, const char *key, size_t key_len, const uint8_t *payload, size_t len,
                        const uint8_t *attachment, size_t attachment_len);
extern void zg_js_reply_done(int id);
extern void zg_js_matching(int id, int matching);

static z_owned_session_t g_session;
static bool g_open = false;
static bool g_handshake = false; /* reads may wait: z_open() is running */

/*------------------ the socket functions of zenoh-pico's WebSocket link ------------------*/

z_result_t _z_create_endpoint_ws(_z_sys_net_endpoint_t *ep, const char *s_addr, const char *s_port) {
    size_t n = strlen(s_addr) + strlen(s_port) + 2;
    char *address = (char *)z_malloc(n);
    if (address == NULL) return _Z_ERR_SYSTEM_OUT_OF_MEMORY;
    snprintf(address, n, "%s:%s", s_addr, s_port);
    ep->_iptcp = (struct addrinfo *)address; /* the "host:port" text, for zg_js_connect */
    return _Z_RES_OK;
}

void _z_free_endpoint_ws(_z_sys_net_endpoint_t *ep) {
    z_free(ep->_iptcp);
    ep->_iptcp = NULL;
}

z_result_t _z_open_ws(_z_sys_net_socket_t *sock, const _z_sys_net_endpoint_t rep, uint32_t tout) {
    int fd = zg_js_connect((const char *)rep._iptcp, tout);
    if (fd < 0) return _Z_ERR_TRANSPORT_OPEN_FAILED;
    sock->_ws._fd = fd;
    sock->_ws._tout = tout;
    return _Z_RES_OK;
}

z_result_t _z_listen_ws(_z_sys_net_socket_t *sock, const _z_sys_net_endpoint_t lep) {
    (void)sock;
    (void)lep;
    return _Z_ERR_GENERIC; /* the gateway is a client: it never listens */
}

void _z_close_ws(_z_sys_net_socket_t *sock) { zg_js_close(sock->_ws._fd); }

size_t _z_read_ws(const _z_sys_net_socket_t sock, uint8_t *ptr, size_t len) {
    int n = zg_js_read(sock._ws._fd, ptr, len);
    if (n == -1 && g_handshake && zg_js_wait_readable(sock._ws._fd, sock._ws._tout)) {
        n = zg_js_read(sock._ws._fd, ptr, len);
    }
    if (n == -2) return 0;        /* closed */
    if (n < 0) return SIZE_MAX;   /* nothing to read yet */
    return (size_t)n;
}

size_t _z_read_exact_ws(const _z_sys_net_socket_t sock, uint8_t *ptr, size_t len) {
    size_t got = 0;
    while (got < len) {
        size_t n = _z_read_ws(sock, ptr + got, len - got);
        if (n == 0 || n == SIZE_MAX) return n;
        got += n;
    }
    return got;
}

size_t _z_send_ws(const _z_sys_net_socket_t sock, const uint8_t *ptr, size_t len) {
    int n = zg_js_send(sock._ws._fd, ptr, len);
    return n < 0 ? SIZE_MAX : (size_t)n;
}

z_result_t _z_socket_set_blocking(const _z_sys_net_socket_t *sock, bool blocking) {
    (void)sock;
    (void)blocking;
    return _Z_RES_OK;
}

z_result_t _z_socket_accept(const _z_sys_net_socket_t *sock_in, _z_sys_net_socket_t *sock_out) {
    (void)sock_in;
    (void)sock_out;
    return _Z_ERR_GENERIC;
}

void _z_socket_close(_z_sys_net_socket_t *sock) { zg_js_close(sock->_ws._fd); }

z_result_t _z_socket_wait_event(void *peers, _z_mutex_rec_t *mutex) {
    (void)peers;
    (void)mutex;
    return _Z_RES_OK;
}

/*------------------ helpers ------------------*/

static uint8_t *bytes_copy(const z_loaned_bytes_t *bytes, size_t *len) {
    *len = bytes == NULL ? 0 : z_bytes_len(bytes);
    if (*len == 0) return NULL;
    uint8_t *data = (uint8_t *)malloc(*len);
    if (data == NULL) {
        *len = 0;
        return NULL;
    }
    z_bytes_reader_t reader = z_bytes_get_reader(bytes);
    z_bytes_reader_read(&reader, data, *len);
    return data;
}

static void bytes_from(z_owned_bytes_t *out, const uint8_t *data, size_t len) {
    z_bytes_copy_from_buf(out, data, len);
}

/*------------------ the session ------------------*/

/**
 * Open the session in client mode to `locator` (e.g. "ws/127.0.0.1:7447"), with the Zenoh id `zid` (a UUID text
 * from JavaScript's crypto: zenoh-pico 1.9.0's Emscripten z_random_fill fills only the first byte). Suspends
 * (Asyncify) until the router answers or the connect timeout passes.
 */
EMSCRIPTEN_KEEPALIVE int zg_open(const char *locator, const char *zid) {
    z_owned_config_t config;
    z_config_default(&config);
    zp_config_insert(z_loan_mut(config), Z_CONFIG_MODE_KEY, "client");
    zp_config_insert(z_loan_mut(config), Z_CONFIG_CONNECT_KEY, locator);
    zp_config_insert(z_loan_mut(config), Z_CONFIG_SESSION_ZID_KEY, zid);
    g_handshake = true;
    z_result_t ret = z_open(&g_session, z_move(config), NULL);
    g_handshake = false;
    g_open = ret == _Z_RES_OK;
    return ret;
}

/** Run zenoh-pico's tasks once: read a pending batch, keep-alive, lease. Returns 1 while the session is up. */
EMSCRIPTEN_KEEPALIVE int zg_spin(void) {
    if (!g_open) return 0;
    zp_spin_once(z_loan(g_session));
    return z_session_is_closed(z_loan(g_session)) ? 0 : 1;
}

/** Close the session (sends a Close to the router). */
EMSCRIPTEN_KEEPALIVE void zg_close(void) {
    if (!g_open) return;
    g_open = false;
    z_drop(z_move(g_session));
}

/** The session's Zenoh id as 32 hex digits, last byte first (zenoh prints it so, without leading zeros). */
EMSCRIPTEN_KEEPALIVE void zg_zid(char *out) {
    z_id_t id = z_info_zid(z_loan(g_session));
    static const char *hex = "0123456789abcdef";
    for (int i = 0; i < 16; i++) {
        out[2 * i] = hex[id.id[15 - i] >> 4];
        out[2 * i + 1] = hex[id.id[15 - i] & 15];
    }
    out[32] = 0;
}

/** Gather the messages sent until zg_batch_stop() into as few batches as they fit (one socket write each). */
EMSCRIPTEN_KEEPALIVE int zg_batch_start(void) { return g_open ? zp_batch_start(z_loan(g_session)) : -1; }

/** Send what zg_batch_start() gathered and go back to one batch per message. */
EMSCRIPTEN_KEEPALIVE int zg_batch_stop(void) { return g_open ? zp_batch_stop(z_loan(g_session)) : -1; }

/*------------------ subscribers (data and liveliness) ------------------*/

static void on_sample(z_loaned_sample_t *sample, void *ctx) {
    z_view_string_t key;
    z_keyexpr_as_view_string(z_sample_keyexpr(sample), &key);
    size_t len, attachment_len;
    uint8_t *payload = bytes_copy(z_sample_payload(sample), &len);
    uint8_t *attachment = bytes_copy(z_sample_attachment(sample), &attachment_len);
    zg_js_sample((int)(intptr_t)ctx, z_sample_kind(sample) == Z_SAMPLE_KIND_DELETE ? 1 : 0,
                 z_string_data(z_loan(key)), z_string_len(z_loan(key)), payload, len, attachment, attachment_len);
    free(payload);
    free(attachment);
}

/** Declare a subscriber on `keyexpr`; samples go to zg_js_sample(id, ...). Returns a handle or 0. */
EMSCRIPTEN_KEEPALIVE z_owned_subscriber_t *zg_subscriber(int id, const char *keyexpr) {
    z_view_keyexpr_t ke;
    if (z_view_keyexpr_from_str(&ke, keyexpr) < 0) return NULL;
    z_owned_subscriber_t *sub = (z_owned_subscriber_t *)malloc(sizeof(*sub));
    z_owned_closure_sample_t callback;
    z_closure(&callback, on_sample, NULL, (void *)(intptr_t)id);
    if (z_declare_subscriber(z_loan(g_session), sub, z_loan(ke), z_move(callback), NULL) < 0) {
        free(sub);
        return NULL;
    }
    return sub;
}

/** Declare a liveliness subscriber; with `history` the tokens alive now arrive first. */
EMSCRIPTEN_KEEPALIVE z_owned_subscriber_t *zg_liveliness_subscriber(int id, const char *keyexpr, int history) {
    z_view_keyexpr_t ke;
    if (z_view_keyexpr_from_str(&ke, keyexpr) < 0) return NULL;
    z_owned_subscriber_t *sub = (z_owned_subscriber_t *)malloc(sizeof(*sub));
    z_owned_closure_sample_t callback;
    z_closure(&callback, on_sample, NULL, (void *)(intptr_t)id);
    z_liveliness_subscriber_options_t options;
    z_liveliness_subscriber_options_default(&options);
    options.history = history != 0;
    if (z_liveliness_declare_subscriber(z_loan(g_session), sub, z_loan(ke), z_move(callback), &options) < 0) {
        free(sub);
        return NULL;
    }
    return sub;
}

/** Undeclare a subscriber of either kind. */
EMSCRIPTEN_KEEPALIVE void zg_subscriber_drop(z_owned_subscriber_t *sub) {
    if (sub == NULL) return;
    if (g_open) z_undeclare_subscriber(z_move(*sub));
    free(sub);
}

/*------------------ publishers ------------------*/

/*
 * A new publisher's write filter drops puts until the router has declared
 * the matching subscribers: the matching status (zg_js_matching(id, ...))
 * tells the gateway when to send what waited.
 */
static void on_matching(const z_matching_status_t *status, void *ctx) {
    zg_js_matching((int)(intptr_t)ctx, status->matching ? 1 : 0);
}

/** Declare a publisher; `reliable` picks congestion control BLOCK (else DROP), `express` sends without batching. */
EMSCRIPTEN_KEEPALIVE z_owned_publisher_t *zg_publisher(int id, const char *keyexpr, int reliable, int express) {
    z_view_keyexpr_t ke;
    if (z_view_keyexpr_from_str(&ke, keyexpr) < 0) return NULL;
    z_owned_publisher_t *pub = (z_owned_publisher_t *)malloc(sizeof(*pub));
    z_publisher_options_t options;
    z_publisher_options_default(&options);
    options.congestion_control = reliable ? Z_CONGESTION_CONTROL_BLOCK : Z_CONGESTION_CONTROL_DROP;
    options.is_express = express != 0;
    if (z_declare_publisher(z_loan(g_session), pub, z_loan(ke), &options) < 0) {
        free(pub);
        return NULL;
    }
    z_owned_closure_matching_status_t matching;
    z_closure_matching_status(&matching, on_matching, NULL, (void *)(intptr_t)id);
    z_publisher_declare_background_matching_listener(z_loan(*pub), z_move(matching));
    return pub;
}

/** Publish `payload` with `attachment` (may be empty). Returns zenoh-pico's result. */
EMSCRIPTEN_KEEPALIVE int zg_put(z_owned_publisher_t *pub, const uint8_t *payload, size_t len,
                                const uint8_t *attachment, size_t attachment_len) {
    z_owned_bytes_t bytes, att;
    bytes_from(&bytes, payload, len);
    z_publisher_put_options_t options;
    z_publisher_put_options_default(&options);
    if (attachment_len) {
        bytes_from(&att, attachment, attachment_len);
        options.attachment = z_move(att);
    }
    return z_publisher_put(z_loan(*pub), z_move(bytes), &options);
}

/** Undeclare a publisher. */
EMSCRIPTEN_KEEPALIVE void zg_publisher_drop(z_owned_publisher_t *pub) {
    if (pub == NULL) return;
    if (g_open) z_undeclare_publisher(z_move(*pub));
    free(pub);
}

/*------------------ transient local: zenoh-ext's advanced publisher and subscriber ------------------*/

#if Z_FEATURE_ADVANCED_PUBLICATION != 1 || Z_FEATURE_ADVANCED_SUBSCRIPTION != 1
#error "the Zenoh gateway needs zenoh-pico's advanced publisher and subscriber (recipes/humble.yaml)"
#endif

/*
 * As rmw_zenoh declares them for TRANSIENT_LOCAL (rmw_publisher_data.cpp,
 * rmw_subscription_data.cpp): the publisher keeps its last `depth` samples
 * for late subscribers and can be detected; RELIABLE adds sequence numbers
 * and a sporadic heartbeat (500 ms) for last-sample miss detection.
 */
EMSCRIPTEN_KEEPALIVE ze_owned_advanced_publisher_t *zg_advanced_publisher(int id, const char *keyexpr, int reliable,
                                                                          int depth) {
    z_view_keyexpr_t ke;
    if (z_view_keyexpr_from_str(&ke, keyexpr) < 0) return NULL;
    ze_owned_advanced_publisher_t *pub = (ze_owned_advanced_publisher_t *)malloc(sizeof(*pub));
    ze_advanced_publisher_options_t options;
    ze_advanced_publisher_options_default(&options);
    options.publisher_options.congestion_control = reliable ? Z_CONGESTION_CONTROL_BLOCK : Z_CONGESTION_CONTROL_DROP;
    ze_advanced_publisher_cache_options_default(&options.cache);
    options.cache.is_enabled = true;
    options.cache.max_samples = depth > 0 ? (size_t)depth : 1;
    options.publisher_detection = true;
    if (reliable) {
        ze_advanced_publisher_sample_miss_detection_options_default(&options.sample_miss_detection);
        options.sample_miss_detection.is_enabled = true;
        options.sample_miss_detection.heartbeat_mode = ZE_ADVANCED_PUBLISHER_HEARTBEAT_MODE_SPORADIC;
        options.sample_miss_detection.heartbeat_period_ms = 500;
    }
    if (ze_declare_advanced_publisher(z_loan(g_session), pub, z_loan(ke), &options) < 0) {
        free(pub);
        return NULL;
    }
    z_owned_closure_matching_status_t matching;
    z_closure_matching_status(&matching, on_matching, NULL, (void *)(intptr_t)id);
    ze_advanced_publisher_declare_background_matching_listener(z_loan(*pub), z_move(matching));
    return pub;
}

/** Publish with an advanced publisher (kept in its cache). */
EMSCRIPTEN_KEEPALIVE int zg_advanced_put(ze_owned_advanced_publisher_t *pub, const uint8_t *payload, size_t len,
                                         const uint8_t *attachment, size_t attachment_len) {
    z_owned_bytes_t bytes, att;
    bytes_from(&bytes, payload, len);
    ze_advanced_publisher_put_options_t options;
    ze_advanced_publisher_put_options_default(&options);
    if (attachment_len) {
        bytes_from(&att, attachment, attachment_len);
        options.put_options.attachment = z_move(att);
    }
    return ze_advanced_publisher_put(z_loan(*pub), z_move(bytes), &options);
}

/** Undeclare an advanced publisher. */
EMSCRIPTEN_KEEPALIVE void zg_advanced_publisher_drop(ze_owned_advanced_publisher_t *pub) {
    if (pub == NULL) return;
    if (g_open) ze_undeclare_advanced_publisher(z_move(*pub));
    free(pub);
}

/** An advanced subscriber that asks the publishers' caches for their last `depth` samples, late joiners too. */
EMSCRIPTEN_KEEPALIVE ze_owned_advanced_subscriber_t *zg_advanced_subscriber(int id, const char *keyexpr, int reliable,
                                                                            int depth) {
    z_view_keyexpr_t ke;
    if (z_view_keyexpr_from_str(&ke, keyexpr) < 0) return NULL;
    ze_owned_advanced_subscriber_t *sub = (ze_owned_advanced_subscriber_t *)malloc(sizeof(*sub));
    z_owned_closure_sample_t callback;
    z_closure(&callback, on_sample, NULL, (void *)(intptr_t)id);
    ze_advanced_subscriber_options_t options;
    ze_advanced_subscriber_options_default(&options);
    ze_advanced_subscriber_history_options_default(&options.history);
    options.history.is_enabled = true;
    options.history.detect_late_publishers = true;
    options.history.max_samples = depth > 0 ? (size_t)depth : 1;
    options.subscriber_detection = true;
    options.query_timeout_ms = UINT64_MAX;
    if (reliable) {
        ze_advanced_subscriber_recovery_options_default(&options.recovery);
        options.recovery.is_enabled = true;
        ze_advanced_subscriber_last_sample_miss_detection_options_default(&options.recovery.last_sample_miss_detection);
        options.recovery.last_sample_miss_detection.is_enabled = true;
        options.recovery.last_sample_miss_detection.periodic_queries_period_ms = 0; /* heartbeats */
    }
    if (ze_declare_advanced_subscriber(z_loan(g_session), sub, z_loan(ke), z_move(callback), &options) < 0) {
        free(sub);
        return NULL;
    }
    return sub;
}

/** Undeclare an advanced subscriber. */
EMSCRIPTEN_KEEPALIVE void zg_advanced_subscriber_drop(ze_owned_advanced_subscriber_t *sub) {
    if (sub == NULL) return;
    if (g_open) ze_undeclare_advanced_subscriber(z_move(*sub));
    free(sub);
}

/*------------------ liveliness tokens ------------------*/

/** Declare a liveliness token on `keyexpr`. Returns a handle or 0. */
EMSCRIPTEN_KEEPALIVE z_owned_liveliness_token_t *zg_token(const char *keyexpr) {
    z_view_keyexpr_t ke;
    if (z_view_keyexpr_from_str(&ke, keyexpr) < 0) return NULL;
    z_owned_liveliness_token_t *token = (z_owned_liveliness_token_t *)malloc(sizeof(*token));
    if (z_liveliness_declare_token(z_loan(g_session), token, z_loan(ke), NULL) < 0) {
        free(token);
        return NULL;
    }
    return token;
}

/** Withdraw a liveliness token. */
EMSCRIPTEN_KEEPALIVE void zg_token_drop(z_owned_liveliness_token_t *token) {
    if (token == NULL) return;
    if (g_open) z_liveliness_undeclare_token(z_move(*token));
    free(token);
}

/*------------------ queryables and queries ------------------*/

static void on_query(z_loaned_query_t *query, void *ctx) {
    z_owned_query_t *owned = (z_owned_query_t *)malloc(sizeof(*owned));
    z_query_clone(owned, query);
    z_view_string_t key;
    z_keyexpr_as_view_string(z_query_keyexpr(query), &key);
    size_t len, attachment_len;
    uint8_t *payload = bytes_copy(z_query_payload(query), &len);
    uint8_t *attachment = bytes_copy(z_query_attachment(query), &attachment_len);
    zg_js_query((int)(intptr_t)ctx, owned, z_string_data(z_loan(key)), z_string_len(z_loan(key)), payload, len,
                attachment, attachment_len);
    free(payload);
    free(attachment);
}

/** Declare a queryable (complete) on `keyexpr`; queries go to zg_js_query(id, handle, ...). */
EMSCRIPTEN_KEEPALIVE z_owned_queryable_t *zg_queryable(int id, const char *keyexpr) {
    z_view_keyexpr_t ke;
    if (z_view_keyexpr_from_str(&ke, keyexpr) < 0) return NULL;
    z_owned_queryable_t *q = (z_owned_queryable_t *)malloc(sizeof(*q));
    z_owned_closure_query_t callback;
    z_closure(&callback, on_query, NULL, (void *)(intptr_t)id);
    z_queryable_options_t options;
    z_queryable_options_default(&options);
    options.complete = true;
    if (z_declare_queryable(z_loan(g_session), q, z_loan(ke), z_move(callback), &options) < 0) {
        free(q);
        return NULL;
    }
    return q;
}

/** Undeclare a queryable. */
EMSCRIPTEN_KEEPALIVE void zg_queryable_drop(z_owned_queryable_t *q) {
    if (q == NULL) return;
    if (g_open) z_undeclare_queryable(z_move(*q));
    free(q);
}

/** Reply to a query kept by zg_js_query (len < 0: no reply), then release it (the final response). */
EMSCRIPTEN_KEEPALIVE int zg_query_reply(z_owned_query_t *query, const char *keyexpr, const uint8_t *payload,
                                        int len, const uint8_t *attachment, size_t attachment_len) {
    int ret = 0;
    if (len >= 0 && g_open) {
        z_view_keyexpr_t ke;
        if (z_view_keyexpr_from_str(&ke, keyexpr) < 0) {
            ret = -1;
        } else {
            z_owned_bytes_t bytes, att;
            bytes_from(&bytes, payload, (size_t)len);
            z_query_reply_options_t options;
            z_query_reply_options_default(&options);
            if (attachment_len) {
                bytes_from(&att, attachment, attachment_len);
                options.attachment = z_move(att);
            }
            ret = z_query_reply(z_loan(*query), z_loan(ke), z_move(bytes), &options);
        }
    }
    z_drop(z_move(*query));
    free(query);
    return ret;
}

static void on_reply(z_loaned_reply_t *reply, void *ctx) {
    int id = (int)(intptr_t)ctx;
    if (z_reply_is_ok(reply)) {
        const z_loaned_sample_t *sample = z_reply_ok(reply);
        z_view_string_t key;
        z_keyexpr_as_view_string(z_sample_keyexpr(sample), &key);
        size_t len, attachment_len;
        uint8_t *payload = bytes_copy(z_sample_payload(sample), &len);
        uint8_t *attachment = bytes_copy(z_sample_attachment(sample), &attachment_len);
        zg_js_reply(id, 1, z_string_data(z_loan(key)), z_string_len(z_loan(key)), payload, len, attachment,
                    attachment_len);
        free(payload);
        free(attachment);
    } else {
        size_t len;
        uint8_t *payload = bytes_copy(z_reply_err_payload(z_reply_err(reply)), &len);
        zg_js_reply(id, 0, "", 0, payload, len, NULL, 0);
        free(payload);
    }
}

static void on_reply_done(void *ctx) { zg_js_reply_done((int)(intptr_t)ctx); }

/** Query `keyexpr` with payload and attachment; replies go to zg_js_reply(id, ...), then zg_js_reply_done(id). */
EMSCRIPTEN_KEEPALIVE int zg_get(int id, const char *keyexpr, const uint8_t *payload, int len,
                                const uint8_t *attachment, size_t attachment_len, uint32_t timeout_ms) {
    z_view_keyexpr_t ke;
    if (z_view_keyexpr_from_str(&ke, keyexpr) < 0) return -1;
    z_owned_closure_reply_t callback;
    z_closure(&callback, on_reply, on_reply_done, (void *)(intptr_t)id);
    z_get_options_t options;
    z_get_options_default(&options);
    z_owned_bytes_t bytes, att;
    if (len >= 0) {
        bytes_from(&bytes, payload, (size_t)len);
        options.payload = z_move(bytes);
    }
    if (attachment_len) {
        bytes_from(&att, attachment, attachment_len);
        options.attachment = z_move(att);
    }
    options.target = Z_QUERY_TARGET_ALL_COMPLETE;
    options.consolidation.mode = Z_CONSOLIDATION_MODE_NONE;
    options.timeout_ms = timeout_ms;
    return z_get(z_loan(g_session), z_loan(ke), "", z_move(callback), &options);
}

/** Query the liveliness tokens alive on `keyexpr`; replies as zg_get's. */
EMSCRIPTEN_KEEPALIVE int zg_liveliness_get(int id, const char *keyexpr, uint32_t timeout_ms) {
    z_view_keyexpr_t ke;
    if (z_view_keyexpr_from_str(&ke, keyexpr) < 0) return -1;
    z_owned_closure_reply_t callback;
    z_closure(&callback, on_reply, on_reply_done, (void *)(intptr_t)id);
    z_liveliness_get_options_t options;
    z_liveliness_get_options_default(&options);
    options.timeout_ms = timeout_ms;
    return z_liveliness_get(z_loan(g_session), z_loan(ke), z_move(callback), &options);
}
