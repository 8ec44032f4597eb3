/* The link: connection specs, contexts, Modbus TCP matched by transaction id.
 * Contract: modbus_link.h. */
#include "linux/modbus_link.h"

#include <arpa/inet.h>
#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ---- spec ------------------------------------------------------------------------------ */

static int parse_int(const char *s, size_t len, long lo, long hi, long *out)
{
    char buf[24];
    char *end;
    long v;
    if (len == 0 || len >= sizeof buf) return -1;
    memcpy(buf, s, len);
    buf[len] = '\0';
    if (buf[0] < '0' || buf[0] > '9') return -1;
    errno = 0;
    v = strtol(buf, &end, 10);
    if (errno != 0 || *end != '\0' || v < lo || v > hi) return -1;
    *out = v;
    return 0;
}

qo_status qo_modbus_link_parse_spec(const char *text, qo_modbus_link_spec *out)
{
    if (out == NULL) return QO_E_NULL;
    memset(out, 0, sizeof *out);
    if (text == NULL) return QO_E_NULL;
    if (strncmp(text, "tcp://", 6) == 0) {
        const char *h = text + 6, *colon = strrchr(h, ':');
        size_t hl = colon != NULL ? (size_t)(colon - h) : strlen(h);
        long port = 502;
        if (h[0] == '[') {
            /* an IPv6 literal: its colons are not the port's */
            const char *e = strchr(h, ']');
            if (e == NULL || (e[1] != '\0' && e[1] != ':')) goto bad;
            colon = e[1] == ':' ? e + 1 : NULL;
            h++;
            hl = (size_t)(e - h);
            if (hl == 0) goto bad;
        }
        if (hl >= sizeof out->host) goto bad;
        if (colon != NULL && parse_int(colon + 1, strlen(colon + 1), 0, 65535, &port) != 0) goto bad;
        out->transport = QO_MODBUS_LINK_TCP;
        if (hl == 0) strcpy(out->host, "127.0.0.1");
        else {
            memcpy(out->host, h, hl);
            out->host[hl] = '\0';
        }
        out->port = (int)port;
        return QO_OK;
    }
    if (strncmp(text, "rtu:", 4) == 0) {
        const char *d = text + 4, *c1 = strchr(d, ',');
        size_t dl = c1 != NULL ? (size_t)(c1 - d) : strlen(d);
        long baud = 19200;
        out->transport = QO_MODBUS_LINK_RTU;
        out->parity = 'E';
        out->data_bits = 8;
        out->stop_bits = 1;
        if (dl == 0 || dl >= sizeof out->device) goto bad;
        memcpy(out->device, d, dl);
        out->device[dl] = '\0';
        if (c1 != NULL) {
            const char *b = c1 + 1, *c2 = strchr(b, ',');
            size_t bl = c2 != NULL ? (size_t)(c2 - b) : strlen(b);
            if (parse_int(b, bl, 1, 10000000, &baud) != 0) goto bad;
            if (c2 != NULL) {
                const char *f = c2 + 1;
                char p;
                if (strlen(f) != 3 || f[0] < '5' || f[0] > '8' || (f[2] != '1' && f[2] != '2'))
                    goto bad;
                p = f[1];
                if (p == 'n') p = 'N';
                if (p == 'e') p = 'E';
                if (p == 'o') p = 'O';
                if (p != 'N' && p != 'E' && p != 'O') goto bad;
                out->data_bits = f[0] - '0';
                out->parity = p;
                out->stop_bits = f[2] - '0';
            }
        }
        out->baud = (int)baud;
        return QO_OK;
    }
bad:
    memset(out, 0, sizeof *out);
    return QO_E_CONFIG;
}

modbus_t *qo_modbus_link_new_ctx(const qo_modbus_link_spec *spec)
{
    if (spec == NULL) return NULL;
    if (spec->transport == QO_MODBUS_LINK_TCP) {
        struct in_addr a;
        char port[16];
        /* modbus_new_tcp takes IPv4 literals only; names and IPv6 go through the _pi API. */
        if (inet_pton(AF_INET, spec->host, &a) == 1) return modbus_new_tcp(spec->host, spec->port);
        snprintf(port, sizeof port, "%d", spec->port);
        return modbus_new_tcp_pi(spec->host, port);
    }
    if (spec->transport == QO_MODBUS_LINK_RTU)
        return modbus_new_rtu(spec->device, spec->baud, spec->parity, spec->data_bits,
                              spec->stop_bits);
    return NULL;
}

/* ---- backoff and connection ------------------------------------------------------------ */

void qo_modbus_link_backoff_init(qo_modbus_link_backoff *b, uint32_t min_us, uint32_t max_us)
{
    b->min_us = min_us;
    b->max_us = max_us;
    b->cur_us = 0;
    clock_gettime(CLOCK_MONOTONIC, &b->next);
}

void qo_modbus_link_backoff_now(qo_modbus_link_backoff *b)
{
    clock_gettime(CLOCK_MONOTONIC, &b->next);
}

int qo_modbus_link_backoff_due(const qo_modbus_link_backoff *b)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return now.tv_sec > b->next.tv_sec ||
           (now.tv_sec == b->next.tv_sec && now.tv_nsec >= b->next.tv_nsec);
}

uint32_t qo_modbus_link_backoff_failed(qo_modbus_link_backoff *b)
{
    uint64_t w = b->cur_us == 0 ? b->min_us : (uint64_t)b->cur_us * 2u;
    if (w > b->max_us) w = b->max_us;
    b->cur_us = (uint32_t)w;
    clock_gettime(CLOCK_MONOTONIC, &b->next);
    b->next.tv_sec += (time_t)(w / 1000000u);
    b->next.tv_nsec += (long)(w % 1000000u) * 1000L;
    if (b->next.tv_nsec >= 1000000000L) {
        b->next.tv_sec++;
        b->next.tv_nsec -= 1000000000L;
    }
    return b->cur_us;
}

void qo_modbus_link_backoff_reset(qo_modbus_link_backoff *b)
{
    b->cur_us = 0;
}

qo_status qo_modbus_link_connect(modbus_t *ctx, const qo_modbus_link_spec *spec, int rs485,
                                 qo_modbus_link_tcp *tcp)
{
    if (ctx == NULL || spec == NULL) return QO_E_NULL;
    modbus_close(ctx);
    if (modbus_connect(ctx) != 0) return errno == ETIMEDOUT ? QO_E_TIMEOUT : QO_E_DISCONNECTED;
    if (spec->transport == QO_MODBUS_LINK_RTU && rs485)
        (void)modbus_rtu_set_serial_mode(ctx, MODBUS_RTU_RS485);
    if (tcp != NULL) qo_modbus_link_tcp_reset(tcp, modbus_get_socket(ctx));
    else modbus_flush(ctx);
    return QO_OK;
}

/* ---- TCP ------------------------------------------------------------------------------- */

void qo_modbus_link_tcp_reset(qo_modbus_link_tcp *t, int fd)
{
    uint16_t tid;
    if (t == NULL) return;
    tid = t->next_tid;
    memset(t->slot, 0, sizeof t->slot);
    t->rx_len = 0;
    t->fd = fd;
    t->next_tid = tid;
    clock_gettime(CLOCK_MONOTONIC, &t->last_rx);
}

qo_status qo_modbus_link_tcp_send(qo_modbus_link_tcp *t, unsigned unit, const uint8_t *pdu,
                                  size_t len, int tag)
{
    uint8_t adu[7 + QO_MODBUS_LINK_PDU_MAX];
    qo_modbus_link_tcp_slot *sl;
    size_t off = 0;
    if (t == NULL || pdu == NULL) return QO_E_NULL;
    if (len < 1 || len > QO_MODBUS_LINK_PDU_MAX || unit > 255) return QO_E_RANGE;
    sl = &t->slot[unit];
    if (t->fd < 0 || sl->busy) return QO_E_STATE;
    t->next_tid++;
    adu[0] = (uint8_t)(t->next_tid >> 8);
    adu[1] = (uint8_t)(t->next_tid & 0xFF);
    adu[2] = 0; /* protocol id: Modbus */
    adu[3] = 0;
    adu[4] = (uint8_t)((len + 1) >> 8);
    adu[5] = (uint8_t)((len + 1) & 0xFF);
    adu[6] = (uint8_t)unit;
    memcpy(adu + 7, pdu, len);
    while (off < len + 7) {
        ssize_t n = send(t->fd, adu + off, len + 7 - off, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return QO_E_DISCONNECTED;
        off += (size_t)n;
    }
    memset(sl, 0, sizeof *sl);
    sl->busy = 1;
    sl->tid = t->next_tid;
    sl->fc = pdu[0];
    sl->tag = tag;
    clock_gettime(CLOCK_MONOTONIC, &sl->sent);
    return QO_OK;
}

/* Takes every complete frame out of the receive buffer. QO_E_PROTOCOL when a header is not
 * Modbus TCP (protocol id, length): after that the byte stream cannot be re-framed. */
static qo_status parse_frames(qo_modbus_link_tcp *t)
{
    while (t->rx_len >= 7) {
        const uint8_t *f = t->rx;
        unsigned tid = ((unsigned)f[0] << 8) | f[1];
        unsigned proto = ((unsigned)f[2] << 8) | f[3];
        unsigned len = ((unsigned)f[4] << 8) | f[5];
        qo_modbus_link_tcp_slot *sl = &t->slot[f[6]];
        if (proto != 0 || len < 2 || len > QO_MODBUS_LINK_PDU_MAX + 1) return QO_E_PROTOCOL;
        if (t->rx_len < 6 + (size_t)len) break;
        if (sl->busy && !sl->done && sl->tid == tid) {
            sl->done = 1;
            sl->len = len - 1;
            memcpy(sl->pdu, f + 7, sl->len);
        } else {
            t->stale++;
        }
        memmove(t->rx, t->rx + 6 + len, t->rx_len - 6 - len);
        t->rx_len -= 6 + (size_t)len;
    }
    return QO_OK;
}

static int ms_until(const struct timespec *deadline)
{
    struct timespec now;
    int64_t ns;
    if (deadline == NULL) return 0;
    clock_gettime(CLOCK_MONOTONIC, &now);
    ns = (int64_t)(deadline->tv_sec - now.tv_sec) * 1000000000 + (deadline->tv_nsec - now.tv_nsec);
    if (ns <= 0) return 0;
    return (int)((ns + 999999) / 1000000);
}

qo_status qo_modbus_link_tcp_pump(qo_modbus_link_tcp *t, int unit, const struct timespec *deadline)
{
    if (t == NULL) return QO_E_NULL;
    if (t->fd < 0) return QO_E_DISCONNECTED;
    for (;;) {
        struct pollfd pf;
        ssize_t n;
        int rc;
        if (unit >= 0 && unit <= 255 && t->slot[unit].done) return QO_OK;
        pf.fd = t->fd;
        pf.events = POLLIN;
        pf.revents = 0;
        /* unit < 0 never blocks: it only collects what has arrived */
        rc = poll(&pf, 1, unit < 0 ? 0 : ms_until(deadline));
        if (rc < 0 && errno == EINTR) continue;
        if (rc < 0) return QO_E_DISCONNECTED;
        if (rc == 0) return unit < 0 ? QO_OK : QO_E_TIMEOUT;
        n = recv(t->fd, t->rx + t->rx_len, sizeof t->rx - t->rx_len, 0);
        if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
        if (n <= 0) return QO_E_DISCONNECTED; /* 0: the peer closed */
        t->rx_len += (size_t)n;
        clock_gettime(CLOCK_MONOTONIC, &t->last_rx);
        if (parse_frames(t) != QO_OK) return QO_E_PROTOCOL;
    }
}

int qo_modbus_link_tcp_busy(const qo_modbus_link_tcp *t, unsigned unit)
{
    return t != NULL && unit <= 255 && t->slot[unit].busy;
}

int qo_modbus_link_tcp_done(const qo_modbus_link_tcp *t, unsigned unit)
{
    return t != NULL && unit <= 255 && t->slot[unit].busy && t->slot[unit].done;
}

int qo_modbus_link_tcp_take(qo_modbus_link_tcp *t, unsigned unit, qo_modbus_link_tcp_slot *out)
{
    if (!qo_modbus_link_tcp_done(t, unit) || out == NULL) return 0;
    *out = t->slot[unit];
    memset(&t->slot[unit], 0, sizeof t->slot[unit]);
    return 1;
}

void qo_modbus_link_tcp_abandon(qo_modbus_link_tcp *t, unsigned unit)
{
    if (t != NULL && unit <= 255) memset(&t->slot[unit], 0, sizeof t->slot[unit]);
}
