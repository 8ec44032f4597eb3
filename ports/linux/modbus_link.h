/*
 * ports/linux/modbus_link.h - the link under the Modbus sink and the simulator: connection
 * specs, libmodbus contexts, and Modbus TCP requests matched to their replies by
 * transaction id.
 *
 * Index:
 *   qo_modbus_link_spec, qo_modbus_link_parse_spec()  "tcp://HOST:PORT" / "rtu:DEVICE,BAUD,8N1"
 *   qo_modbus_link_new_ctx()       a libmodbus context for a parsed spec
 *   qo_modbus_link_connect()       (re)connect a context; TCP: hand the socket over
 *   qo_modbus_link_backoff         exponential reconnection backoff
 *   qo_modbus_link_tcp             one TCP connection's outstanding requests
 *   qo_modbus_link_tcp_reset()     a new socket: forget every request and partial frame
 *   qo_modbus_link_tcp_send()      send one request PDU to a unit (at most one outstanding each)
 *   qo_modbus_link_tcp_pump()      read replies until one unit's arrives or a deadline passes
 *   qo_modbus_link_tcp_busy(), qo_modbus_link_tcp_done(), qo_modbus_link_tcp_take(),
 *   qo_modbus_link_tcp_abandon()
 *
 * Why TCP requests do not go through libmodbus's request functions: a reply later than the
 * response timeout must be accepted (the drive applied the write; its state is known), not
 * be a protocol error. libmodbus 3.1.6 and 3.1.11 both read a reply only inside the call
 * that sent the request: after a timeout, the late reply is read by the NEXT call, whose
 * transaction-id check rejects it (EMBBADDATA), and a frame cut by the timeout is lost. So
 * on TCP the sink takes the socket libmodbus connected (modbus_get_socket), frames the MBAP
 * header itself and keeps partial frames across calls; libmodbus still connects and closes.
 * modbus_send_raw_request + modbus_receive_confirmation would not do: the latter drops a
 * partial frame at its timeout and cannot wait for one of several outstanding requests.
 * RTU stays on libmodbus (no transaction id: see modbus_sink.h for its drain rules).
 */
#ifndef QORIENT_MODBUS_LINK_H
#define QORIENT_MODBUS_LINK_H

#include <stddef.h>
#include <stdint.h>
#include <time.h>

#include <modbus.h>

#include "qorient/status.h"

typedef enum qo_modbus_link_transport {
    QO_MODBUS_LINK_TCP = 0,
    QO_MODBUS_LINK_RTU
} qo_modbus_link_transport;

#define QO_MODBUS_LINK_SPEC_MAX 128

typedef struct qo_modbus_link_spec {
    qo_modbus_link_transport transport;
    char host[QO_MODBUS_LINK_SPEC_MAX];   /* TCP: address or name, IPv6 without its brackets */
    int port;                             /* TCP: 0..65535 (0 = ephemeral, listen side only) */
    char device[QO_MODBUS_LINK_SPEC_MAX]; /* RTU: serial device path */
    int baud;                             /* RTU: > 0 */
    char parity;                          /* RTU: 'N', 'E' or 'O' */
    int data_bits;                        /* RTU: 5..8 */
    int stop_bits;                        /* RTU: 1 or 2 */
} qo_modbus_link_spec;

/* Parses "tcp://HOST:PORT" (PORT optional, default 502; HOST may be empty: 127.0.0.1; an
 * IPv6 address in brackets, "tcp://[::1]:1502") or "rtu:DEVICE[,BAUD[,FRAME]]" with FRAME =
 * data bits, parity N/E/O, stop bits, e.g. "8N1" (defaults 19200 and 8E1, the Modbus serial
 * line default). Returns QO_OK, QO_E_NULL or QO_E_CONFIG (*out zeroed on error). */
qo_status qo_modbus_link_parse_spec(const char *text, qo_modbus_link_spec *out);

/* A libmodbus context for the spec, or NULL (bad spec or libmodbus failure): modbus_new_tcp
 * for an IPv4 literal, modbus_new_tcp_pi for a host name or IPv6 address, modbus_new_rtu
 * for a serial device. */
modbus_t *qo_modbus_link_new_ctx(const qo_modbus_link_spec *spec);

/* ---- reconnection backoff ------------------------------------------------------------- */

typedef struct qo_modbus_link_backoff {
    uint32_t min_us, max_us;  /* first wait after a failure, ceiling */
    uint32_t cur_us;          /* current wait, 0 after a success */
    struct timespec next;     /* CLOCK_MONOTONIC: no attempt before this */
} qo_modbus_link_backoff;

/* min_us >= 1, max_us >= min_us (not checked: the caller validated its settings). An
 * attempt is due at once. */
void qo_modbus_link_backoff_init(qo_modbus_link_backoff *b, uint32_t min_us, uint32_t max_us);

/* An attempt is due at once (the link just went down); the current wait stays. */
void qo_modbus_link_backoff_now(qo_modbus_link_backoff *b);

/* 1 when an attempt may be made now. */
int qo_modbus_link_backoff_due(const qo_modbus_link_backoff *b);

/* After a failed attempt: the wait doubles (min_us first, at most max_us) and the next
 * attempt is due after it. Returns the new wait, us. */
uint32_t qo_modbus_link_backoff_failed(qo_modbus_link_backoff *b);

/* After a success: the next failure waits min_us again. */
void qo_modbus_link_backoff_reset(qo_modbus_link_backoff *b);

/* ---- connection ------------------------------------------------------------------------ */

typedef struct qo_modbus_link_tcp qo_modbus_link_tcp;

/* Closes ctx (if open) and connects it. RTU with rs485: tries MODBUS_RTU_RS485 (failure
 * ignored: ptys and many USB adapters refuse it) and flushes. TCP with tcp != NULL: the
 * socket is handed to it (qo_modbus_link_tcp_reset), so requests bypass libmodbus's reader.
 * Returns QO_OK; QO_E_NULL; QO_E_TIMEOUT (connect timed out); QO_E_DISCONNECTED (refused,
 * unreachable, no device). */
qo_status qo_modbus_link_connect(modbus_t *ctx, const qo_modbus_link_spec *spec, int rs485,
                                 qo_modbus_link_tcp *tcp);

/* ---- Modbus TCP requests matched by transaction id ------------------------------------ */

#define QO_MODBUS_LINK_PDU_MAX 253 /* function code + data */

typedef struct qo_modbus_link_tcp_slot {
    int busy;                     /* a request is outstanding (or answered, not yet taken) */
    int done;                     /* its reply arrived */
    uint16_t tid;                 /* transaction id sent */
    uint8_t fc;                   /* function code sent */
    int tag;                      /* the caller's note (e.g. which request group it was) */
    struct timespec sent;         /* CLOCK_MONOTONIC */
    size_t len;                   /* reply PDU length */
    uint8_t pdu[QO_MODBUS_LINK_PDU_MAX];
} qo_modbus_link_tcp_slot;

struct qo_modbus_link_tcp {
    int fd;                       /* the connected socket, -1 when none */
    uint16_t next_tid;
    size_t rx_len;
    uint8_t rx[2 * 260];          /* a partial frame survives between calls */
    struct timespec last_rx;      /* when bytes last arrived */
    uint64_t late;                /* replies taken after the call that sent them returned */
    uint64_t stale;               /* replies matching no outstanding request (dropped) */
    qo_modbus_link_tcp_slot slot[256]; /* one per unit id */
};

/* Forgets every outstanding request and partial frame; fd is the new socket (-1: none).
 * The transaction id keeps counting, so a reply to the old socket can never match. */
void qo_modbus_link_tcp_reset(qo_modbus_link_tcp *t, int fd);

/* Sends `pdu` (function code + data, 1..QO_MODBUS_LINK_PDU_MAX bytes) to `unit` (0..255) with a
 * new transaction id and notes it outstanding with `tag`. Returns QO_OK; QO_E_NULL;
 * QO_E_RANGE (length); QO_E_STATE (that unit has a request outstanding, or no socket);
 * QO_E_DISCONNECTED (the socket failed; the connection must be dropped). */
qo_status qo_modbus_link_tcp_send(qo_modbus_link_tcp *t, unsigned unit, const uint8_t *pdu,
                                  size_t len, int tag);

/* Reads whatever replies arrive, matching each to its unit's outstanding request by
 * transaction id (a reply matching none is dropped and counted in `stale`), until `unit`'s
 * reply is in (unit < 0: until nothing more is waiting, without blocking) or `deadline`
 * (CLOCK_MONOTONIC; NULL = do not block) passes. Returns QO_OK (the reply is in, or
 * unit < 0); QO_E_TIMEOUT; QO_E_DISCONNECTED (closed by the peer, socket error);
 * QO_E_PROTOCOL (a header that is not Modbus TCP: the stream cannot be re-framed, drop the
 * connection). */
qo_status qo_modbus_link_tcp_pump(qo_modbus_link_tcp *t, int unit, const struct timespec *deadline);

/* 1 when unit has a request outstanding (answered or not) and not yet taken. */
int qo_modbus_link_tcp_busy(const qo_modbus_link_tcp *t, unsigned unit);

/* 1 when unit's outstanding request has its reply. */
int qo_modbus_link_tcp_done(const qo_modbus_link_tcp *t, unsigned unit);

/* Takes unit's answered request: copies the slot (reply PDU, tag, function code) to *out
 * and frees the unit for the next request. 1 when taken, 0 when nothing was answered. */
int qo_modbus_link_tcp_take(qo_modbus_link_tcp *t, unsigned unit, qo_modbus_link_tcp_slot *out);

/* Gives up on unit's outstanding request: its reply, should it come, is dropped as stale. */
void qo_modbus_link_tcp_abandon(qo_modbus_link_tcp *t, unsigned unit);

#endif /* QORIENT_MODBUS_LINK_H */
