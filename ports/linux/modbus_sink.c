#include "linux/modbus_sink.h"
#include "linux/joint_guard.h"
#include "linux/modbus_layout.h"
#include "sink_view.h"

#include <arpa/inet.h>
#include <errno.h>
#include <stdio.h>
#include <math.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

const qo_modbus_sink_settings qo_modbus_sink_settings_default = {
    20000u,                 /* response_timeout_us */
    5000u,                  /* byte_timeout_us */
    5u,                     /* fail_threshold */
    QO_MODBUS_SINK_ON_FAIL_HOLD, /* on_fail */
    50000u,                 /* reconnect_min_us */
    2000000u,               /* reconnect_max_us */
    0,                      /* rs485 */
    1,                      /* seed_from_feedback */
    0u,                     /* open_timeout_us: the response timeout */
    0u                      /* silence_us: automatic */
};

/* ---- sink ------------------------------------------------------------------------------ */

struct qo_modbus_sink {
    const qo_regmap *map;
    qo_modbus_sink_settings set;
    qo_modbus_link_spec spec;
    modbus_t *ctx;
    int connected, closed, disabled;
    qo_modbus_layout *lay;  /* the requests of one tick */
    qo_joint_guard *js;
    qo_modbus_link_backoff backoff;
    unsigned bus_failures; /* consecutive ticks failed on the bus (argument errors excluded) */
    unsigned cur_slave;    /* slave of the request in progress (modbus_set_slave) */
    int drained;           /* RTU: the line was drained this tick */
    int last_errno;        /* errno of the last failed request */
    struct timespec tick_deadline; /* TCP: the tick waits for outstanding replies until this */
    uint32_t silence_us;   /* the effective silence before a TCP link counts as broken */
    qo_modbus_link_tcp *tcp; /* TCP: requests matched by transaction id; NULL on RTU */
    int connect_ok;        /* the last do_connect got the link up (its requests failed) */
    int in_tick;           /* inside write() or settle: tick_deadline bounds the waits */
    qo_modbus_sink_stats st;
};

static void now_ts(struct timespec *t)
{
    clock_gettime(CLOCK_MONOTONIC, t);
}

static void sleep_us(unsigned us)
{
    struct timespec d;
    if (us == 0) return;
    d.tv_sec = (time_t)(us / 1000000u);
    d.tv_nsec = (long)(us % 1000000u) * 1000L;
    while (nanosleep(&d, &d) != 0 && errno == EINTR) {
    }
}

static void use_slave(qo_modbus_sink *s, unsigned slave)
{
    s->cur_slave = slave;
    modbus_set_slave(s->ctx, (int)slave);
}

/* Every joint of `slave` must be read back before its next write: a request to it had an
 * unknown outcome, so its reply may still come (and, on RTU, be taken for a later one). */
static void mark_slave_uncertain(qo_modbus_sink *s, unsigned slave)
{
    size_t i;
    for (i = 0; i < s->map->n_joints; i++)
        if (s->map->joints[i].slave == slave) s->js[i].uncertain = 1;
}

/* Maps a failed libmodbus call (errno) to a status; *uncertain says whether the request may
 * have been applied (anything but an exception reply). */
static qo_status classify(int err, int *uncertain, qo_modbus_sink *s)
{
    *uncertain = 1;
    if (err > MODBUS_ENOBASE && err <= MODBUS_ENOBASE + MODBUS_EXCEPTION_GATEWAY_TARGET) {
        *uncertain = 0;
        s->st.exceptions++;
        return QO_E_PROTOCOL;
    }
    switch (err) {
    case ETIMEDOUT:
        s->st.timeouts++;
        return QO_E_TIMEOUT;
    case EMBBADCRC: case EMBBADDATA: case EMBBADEXC: case EMBUNKEXC: case EMBMDATA:
    case EMBBADSLAVE:
        s->st.protocol_errors++;
        return QO_E_PROTOCOL;
    case ECONNRESET: case EPIPE: case EBADF: case ENOTCONN: case ECONNREFUSED: case ENOTSOCK:
    case ECONNABORTED: case ENETDOWN: case ENETUNREACH: case EHOSTUNREACH: case ENXIO:
        return QO_E_DISCONNECTED;
    default:
        return QO_E_IO;
    }
}

static void link_down(qo_modbus_sink *s)
{
    if (s->connected) {
        s->st.disconnects++;
        modbus_close(s->ctx);
    }
    if (s->tcp != NULL) {
        size_t i;
        s->st.stale_replies += s->tcp->stale;
        s->tcp->stale = 0;
        qo_modbus_link_tcp_reset(s->tcp, -1);
        /* an outstanding write's reply will never be read: old or new, read back */
        for (i = 0; i < s->map->n_joints; i++) s->js[i].pend = 0;
    }
    s->connected = 0;
    s->st.common.connected = 0;
    qo_modbus_link_backoff_now(&s->backoff); /* first reconnection may be tried at once */
}

/* One request's bookkeeping after a libmodbus call that returned rc. */
static qo_status after_request(qo_modbus_sink *s, int rc, int *uncertain)
{
    int err = errno;
    qo_status st;
    s->st.requests++;
    *uncertain = 0;
    if (rc >= 0) return QO_OK;
    s->st.requests_failed++;
    s->last_errno = err;
    st = classify(err, uncertain, s);
    if (*uncertain) mark_slave_uncertain(s, s->cur_slave);
    /* RTU: a late or partial reply must not be read as the answer to the next request. */
    modbus_flush(s->ctx);
    s->st.last_error = st;
    return st;
}

/* ---- one request ----------------------------------------------------------------------- */

static void add_us(struct timespec *t, uint64_t us)
{
    t->tv_sec += (time_t)(us / 1000000u);
    t->tv_nsec += (long)(us % 1000000u) * 1000L;
    if (t->tv_nsec >= 1000000000L) {
        t->tv_sec++;
        t->tv_nsec -= 1000000000L;
    }
}

static int64_t us_between(const struct timespec *a, const struct timespec *b)
{
    return (int64_t)(b->tv_sec - a->tv_sec) * 1000000 + (int64_t)(b->tv_nsec - a->tv_nsec) / 1000;
}

/* An FC16 of joint targets whose reply arrived (in its own call or later): the drive holds
 * what it carried, or, after an exception, what it held before. */
static void group_answered(qo_modbus_sink *s, size_t g, int applied)
{
    const qo_modbus_layout_request *gr = &s->lay->req[g];
    size_t i;
    for (i = 0; i < gr->n_items; i++)
        qo_joint_guard_answered(&s->js[s->lay->item[gr->first_item + i].joint], applied);
}

/* The meaning of a reply PDU to a request with function code fc: QO_OK (rregs filled for
 * FC03, when rregs is not NULL); QO_E_PROTOCOL for an exception (*applied 0) or a malformed
 * reply (*applied 1: the drive took the request, what it did is unknown). */
static qo_status judge_reply(qo_modbus_sink *s, const qo_modbus_link_tcp_slot *r, unsigned count,
                             uint16_t *rregs, int *applied)
{
    unsigned k;
    *applied = 0;
    if (r->len >= 2 && r->pdu[0] == (uint8_t)(r->fc | 0x80)) {
        s->st.exceptions++;
        s->last_errno = MODBUS_ENOBASE + r->pdu[1];
        return QO_E_PROTOCOL;
    }
    *applied = 1;
    if (r->len < 1 || r->pdu[0] != r->fc) goto bad;
    if (r->fc == MODBUS_FC_READ_HOLDING_REGISTERS) {
        if (rregs == NULL) return QO_OK;
        if (r->len != 2 + 2 * (size_t)count || r->pdu[1] != 2 * count) goto bad;
        for (k = 0; k < count; k++)
            rregs[k] = (uint16_t)(((unsigned)r->pdu[2 + 2 * k] << 8) | r->pdu[3 + 2 * k]);
    } else if (r->len != 5) {
        goto bad;
    }
    return QO_OK;
bad:
    s->st.protocol_errors++;
    s->last_errno = EMBBADDATA;
    return QO_E_PROTOCOL;
}

/* A reply that came after the call that sent its request returned: taken and applied. */
static void take_late(qo_modbus_sink *s, unsigned slave)
{
    qo_modbus_link_tcp_slot r;
    int applied;
    if (!qo_modbus_link_tcp_take(s->tcp, slave, &r)) return;
    s->st.late_replies++;
    (void)judge_reply(s, &r, 0, NULL, &applied);
    /* a late read-back or init write changes nothing: its joints are read back again */
    if (r.tag >= 0) group_answered(s, (size_t)r.tag, applied);
}

/* TCP: collects the replies that arrived since the last call (without blocking) and applies
 * them. QO_OK, or QO_E_DISCONNECTED when the link broke (the caller drops it). */
static qo_status tcp_collect(qo_modbus_sink *s)
{
    size_t i;
    qo_status st = qo_modbus_link_tcp_pump(s->tcp, -1, NULL);
    if (st != QO_OK) {
        if (st == QO_E_PROTOCOL) s->st.protocol_errors++;
        return QO_E_DISCONNECTED;
    }
    for (i = 0; i < s->map->n_slaves; i++) take_late(s, s->map->slaves[i].id);
    return QO_OK;
}

/* TCP: `slave` may get a request only when its previous one is answered. Waits for it until
 * the tick's deadline. QO_OK (free); QO_E_TIMEOUT (still outstanding: skip this slave);
 * QO_E_DISCONNECTED (broken, or nothing received for silence_us: the caller drops it).
 * A request outstanding for silence_us while other replies do arrive is abandoned (its
 * joints are read back) rather than the link dropped. */
static qo_status tcp_wait_free(qo_modbus_sink *s, unsigned slave)
{
    struct timespec now;
    qo_status st;
    if (!qo_modbus_link_tcp_busy(s->tcp, slave)) return QO_OK;
    if (!s->in_tick) {
        /* outside a tick (open, reconnection, feedback reads): one response timeout */
        now_ts(&s->tick_deadline);
        add_us(&s->tick_deadline, s->set.response_timeout_us);
    }
    st = qo_modbus_link_tcp_pump(s->tcp, (int)slave, &s->tick_deadline);
    if (st == QO_OK) {
        take_late(s, slave);
        return QO_OK;
    }
    if (st != QO_E_TIMEOUT) {
        if (st == QO_E_PROTOCOL) s->st.protocol_errors++;
        return QO_E_DISCONNECTED;
    }
    now_ts(&now);
    if (us_between(&s->tcp->slot[slave].sent, &now) < (int64_t)s->silence_us) return QO_E_TIMEOUT;
    if (us_between(&s->tcp->slot[slave].sent, &s->tcp->last_rx) <= 0) {
        s->st.silences++;
        return QO_E_DISCONNECTED;
    }
    s->st.abandoned++;
    qo_modbus_link_tcp_abandon(s->tcp, slave);
    mark_slave_uncertain(s, slave);
    return QO_OK;
}

/* One request to `slave`: FC16 (count registers from wregs), FC06 (wregs[0]) or FC03 (into
 * rregs). *uncertain: the outcome is unknown (it may have been applied). On TCP a request
 * without a reply within the response timeout stays outstanding (QO_E_TIMEOUT, *pending 1):
 * its reply is taken later (tag >= 0: the group whose joints it carries). A slave whose
 * previous request is still outstanding gets nothing: QO_E_TIMEOUT, *pending 1, *sent 0. */
static qo_status xfer(qo_modbus_sink *s, unsigned slave, int fc, uint16_t addr, unsigned count,
                      const uint16_t *wregs, uint16_t *rregs, int tag, int *uncertain,
                      int *pending, int *sent)
{
    uint8_t pdu[QO_MODBUS_LINK_PDU_MAX];
    size_t len = 0, k;
    struct timespec dl;
    qo_modbus_link_tcp_slot r;
    qo_status st;
    int rc, applied;
    *uncertain = 0;
    *pending = 0;
    *sent = 1;
    use_slave(s, slave);
    if (s->tcp == NULL) {
        if (fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS) rc = modbus_write_registers(s->ctx, addr, (int)count, wregs);
        else if (fc == MODBUS_FC_WRITE_SINGLE_REGISTER) rc = modbus_write_register(s->ctx, addr, wregs[0]);
        else rc = modbus_read_registers(s->ctx, addr, (int)count, rregs);
        return after_request(s, rc, uncertain);
    }
    st = tcp_wait_free(s, slave);
    if (st != QO_OK) {
        *sent = 0;
        *pending = st == QO_E_TIMEOUT;
        if (st == QO_E_TIMEOUT) s->st.skipped++;
        s->st.last_error = st;
        return st;
    }
    pdu[len++] = (uint8_t)fc;
    pdu[len++] = (uint8_t)(addr >> 8);
    pdu[len++] = (uint8_t)(addr & 0xFF);
    if (fc == MODBUS_FC_WRITE_SINGLE_REGISTER) {
        pdu[len++] = (uint8_t)(wregs[0] >> 8);
        pdu[len++] = (uint8_t)(wregs[0] & 0xFF);
    } else {
        pdu[len++] = (uint8_t)(count >> 8);
        pdu[len++] = (uint8_t)(count & 0xFF);
        if (fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS) {
            pdu[len++] = (uint8_t)(2 * count);
            for (k = 0; k < count; k++) {
                pdu[len++] = (uint8_t)(wregs[k] >> 8);
                pdu[len++] = (uint8_t)(wregs[k] & 0xFF);
            }
        }
    }
    s->st.requests++;
    st = qo_modbus_link_tcp_send(s->tcp, slave, pdu, len, tag);
    if (st == QO_OK) {
        now_ts(&dl);
        add_us(&dl, s->set.response_timeout_us);
        st = qo_modbus_link_tcp_pump(s->tcp, (int)slave, &dl);
    }
    if (st == QO_E_TIMEOUT) {
        s->st.timeouts++;
        s->st.requests_failed++;
        s->st.last_error = st;
        *uncertain = 1;
        *pending = 1;
        return QO_E_TIMEOUT;
    }
    if (st != QO_OK) {
        if (st == QO_E_PROTOCOL) s->st.protocol_errors++;
        s->st.requests_failed++;
        *uncertain = 1;
        s->st.last_error = QO_E_DISCONNECTED;
        return QO_E_DISCONNECTED;
    }
    (void)qo_modbus_link_tcp_take(s->tcp, slave, &r);
    st = judge_reply(s, &r, count, rregs, &applied);
    if (st != QO_OK) {
        s->st.requests_failed++;
        s->st.last_error = st;
        *uncertain = applied; /* malformed: taken, but what it did is unknown */
        if (applied) mark_slave_uncertain(s, slave);
    }
    return st;
}

static qo_status send_writes(qo_modbus_sink *s, int disable)
{
    size_t i, k;
    int unc;
    for (i = 0; i < s->map->n_slaves; i++) {
        const qo_regmap_slave *sl = &s->map->slaves[i];
        const qo_regmap_write *w = disable ? sl->disable : sl->init;
        size_t n = disable ? sl->n_disable : sl->n_init;
        for (k = 0; k < n; k++) {
            qo_status st;
            int pend, sent;
            st = xfer(s, sl->id, MODBUS_FC_WRITE_SINGLE_REGISTER, w[k].address, 1, &w[k].value,
                      NULL, -1, &unc, &pend, &sent);
            sleep_us(sl->gap_us);
            if (st != QO_OK) return st;
        }
    }
    return QO_OK;
}

static qo_status read_joint_feedback(qo_modbus_sink *s, size_t i, double *raw)
{
    const qo_regmap_joint *j = &s->map->joints[i];
    uint16_t regs[2] = { 0, 0 };
    int unc, pend, sent;
    qo_status st;
    const qo_regmap_slave *sl = qo_regmap_find_slave(s->map, j->slave);
    *raw = 0.0;
    st = xfer(s, j->slave, MODBUS_FC_READ_HOLDING_REGISTERS, j->feedback,
              (unsigned)qo_modbus_reg_type_width(j->fmt.type), NULL, regs, -1, &unc, &pend, &sent);
    if (sl != NULL) sleep_us(sl->gap_us);
    if (st != QO_OK) return st;
    return qo_modbus_reg_unpack_raw(j->fmt.type, j->fmt.order, regs, raw);
}

static qo_status seed_from_feedback(qo_modbus_sink *s)
{
    size_t i;
    for (i = 0; i < s->map->n_joints; i++) {
        double raw;
        qo_status st;
        if (s->js[i].have || !s->map->joints[i].has_feedback) continue;
        st = read_joint_feedback(s, i, &raw);
        if (st != QO_OK) return st;
        qo_joint_guard_known(&s->js[i], raw);
    }
    return QO_OK;
}

/* Connects and brings the drives to the sink's state. Leaves the link closed on failure. */
static qo_status do_connect(qo_modbus_sink *s)
{
    qo_status st;
    s->connect_ok = 0;
    st = qo_modbus_link_connect(s->ctx, &s->spec, s->set.rs485, s->tcp);
    if (st != QO_OK) {
        s->st.last_error = st;
        return st;
    }
    s->connected = 1;
    /* What the sink remembers may be stale now (the drive may have restarted and lost its
     * target, or, on RTU, a late reply may still come): read every known joint back first. */
    {
        size_t i;
        for (i = 0; i < s->map->n_joints; i++)
            if (s->js[i].have) s->js[i].uncertain = 1;
    }
    st = send_writes(s, s->disabled);
    if (st == QO_OK && s->set.seed_from_feedback) st = seed_from_feedback(s);
    if (st != QO_OK) {
        modbus_close(s->ctx);
        s->connected = 0;
        if (s->tcp != NULL) qo_modbus_link_tcp_reset(s->tcp, -1);
        s->connect_ok = 1; /* the link came up; the drives' answers did not */
        return st;
    }
    s->st.common.connected = 1;
    s->st.common.consecutive_failures = 0;
    s->bus_failures = 0;
    qo_modbus_link_backoff_reset(&s->backoff);
    s->st.backoff_us = 0;
    return QO_OK;
}

qo_status qo_modbus_sink_open(const char *spec, const qo_regmap *map,
                              const qo_modbus_sink_settings *settings, qo_modbus_sink **out)
{
    qo_modbus_sink *s;
    qo_status st;
    size_t i;
    if (out == NULL) return QO_E_NULL;
    *out = NULL;
    if (spec == NULL || map == NULL) return QO_E_NULL;
    if (settings == NULL) settings = &qo_modbus_sink_settings_default;
    if (map->n_joints == 0 || map->n_joints > QO_REGMAP_MAX_JOINTS) return QO_E_CONFIG;
    if (settings->response_timeout_us == 0 || settings->reconnect_min_us == 0 ||
        settings->fail_threshold == 0)
        return QO_E_LIMIT;
    if (settings->response_timeout_us > 10000000u || settings->byte_timeout_us > 10000000u ||
        settings->open_timeout_us > 10000000u || settings->silence_us > 60000000u ||
        settings->reconnect_max_us < settings->reconnect_min_us ||
        (settings->on_fail != QO_MODBUS_SINK_ON_FAIL_HOLD && settings->on_fail != QO_MODBUS_SINK_ON_FAIL_DISABLE))
        return QO_E_CONFIG;
    /* A map may be built by hand rather than by qo_regmap_load: check what the sink relies on. */
    for (i = 0; i < map->n_slaves; i++)
        if (map->slaves[i].max_registers < 1 || map->slaves[i].max_registers > QO_REGMAP_MAX_REGISTERS)
            return QO_E_CONFIG;
    for (i = 0; i < map->n_joints; i++) {
        const qo_regmap_joint *j = &map->joints[i];
        const qo_regmap_slave *sl = qo_regmap_find_slave(map, j->slave);
        size_t w = qo_modbus_reg_type_width(j->fmt.type);
        double raw;
        if (w == 0 || qo_modbus_reg_raw_from_value(&j->fmt, 0.0, &raw) != QO_OK ||
            (size_t)j->address + w > 65536u || j->slave < 1 || j->slave > 255 ||
            !(j->max_step >= 0.0) || !isfinite(j->max_step) || j->min > j->max ||
            (sl != NULL && w > sl->max_registers))
            return QO_E_CONFIG;
    }
    s = calloc(1, sizeof *s);
    if (s == NULL) return QO_E_CAPACITY;
    s->map = map;
    s->set = *settings;
    s->st.last_error = QO_OK;
    qo_modbus_link_backoff_init(&s->backoff, settings->reconnect_min_us,
                                settings->reconnect_max_us);
    st = qo_modbus_link_parse_spec(spec, &s->spec);
    if (st == QO_OK && (s->spec.transport == QO_MODBUS_LINK_TCP && s->spec.port == 0))
        st = QO_E_CONFIG;
    if (st == QO_OK) {
        s->js = calloc(map->n_joints, sizeof *s->js);
        if (s->js == NULL) st = QO_E_CAPACITY;
    }
    if (st == QO_OK) {
        s->lay = malloc(sizeof *s->lay);
        st = s->lay == NULL ? QO_E_CAPACITY : qo_modbus_layout_build(map, s->lay);
        if (st == QO_OK) s->st.groups = (unsigned)s->lay->n_requests;
    }
    if (st == QO_OK && s->spec.transport == QO_MODBUS_LINK_TCP) {
        s->tcp = calloc(1, sizeof *s->tcp);
        if (s->tcp == NULL) st = QO_E_CAPACITY;
        else qo_modbus_link_tcp_reset(s->tcp, -1);
    }
    s->silence_us = settings->silence_us;
    if (s->silence_us == 0) {
        /* long enough for a loaded machine's scheduling stalls (tens of ms seen on the
         * 2-core CI box), short enough that the drives do not hold for long */
        uint64_t a = 20u * (uint64_t)settings->response_timeout_us;
        s->silence_us = a < 1000000u ? 1000000u : a > 60000000u ? 60000000u : (uint32_t)a;
    }
    if (st == QO_OK) {
        for (i = 0; i < map->n_joints; i++) qo_joint_guard_init(&s->js[i], &map->joints[i]);
        s->ctx = qo_modbus_link_new_ctx(&s->spec);
        if (s->ctx == NULL) st = QO_E_CONFIG;
    }
    if (st == QO_OK) {
        uint32_t r = settings->response_timeout_us, b = settings->byte_timeout_us;
        modbus_set_error_recovery(s->ctx, MODBUS_ERROR_RECOVERY_NONE);
        uint32_t o = settings->open_timeout_us ? settings->open_timeout_us : r;
        modbus_set_byte_timeout(s->ctx, b / 1000000u, b % 1000000u);
        /* The first connection may take its time (it is outside the control loop); every
         * later request, reconnections included, gets the response timeout. */
        modbus_set_response_timeout(s->ctx, o / 1000000u, o % 1000000u);
        s->set.response_timeout_us = o;
        st = do_connect(s);
        {
            /* The link came up but a request failed (an exception, a lost reply): retried
             * as during streaming, with the reconnection backoff, a few times. A link that
             * does not come up at all fails at once. */
            uint32_t back = settings->reconnect_min_us;
            int tries;
            for (tries = 0; st != QO_OK && s->connect_ok && tries < QO_MODBUS_SINK_OPEN_RETRIES; tries++) {
                s->st.reconnect_attempts++;
                sleep_us(back);
                back = back > settings->reconnect_max_us / 2 ? settings->reconnect_max_us : 2 * back;
                st = do_connect(s);
            }
        }
        s->set.response_timeout_us = r;
        modbus_set_response_timeout(s->ctx, r / 1000000u, r % 1000000u);
    }
    if (st != QO_OK) {
        qo_modbus_sink_free(s);
        return st;
    }
    *out = s;
    return QO_OK;
}

/* Raw value for joint i this tick, within max_step of every value the drive may hold.
 * QO_E_INFEASIBLE when no such value exists (the range [lo, hi] is wider than 2 x max_step,
 * or rounding cannot land inside the window): the joint's slave must not be written. */
static qo_status limit_joint(qo_modbus_sink *s, size_t i, double target, uint16_t *regs)
{
    unsigned changed;
    qo_status st = qo_joint_guard_limit(&s->js[i], &s->map->joints[i], target, regs, &changed);
    if (changed & QO_JOINT_GUARD_CLAMPED) s->st.clamped++;
    if (changed & QO_JOINT_GUARD_SATURATED) s->st.saturated++;
    if (changed & QO_JOINT_GUARD_RATE_LIMITED) s->st.rate_limited++;
    if (st != QO_OK) s->st.blocked++;
    else if (changed) s->st.common.limited++;
    return st;
}

/* RTU: reads and drops whatever arrives during one response timeout, then flushes, so a late
 * reply to an earlier request is gone before the read-back (once per tick: the line is
 * shared by every slave). */
static void drain_line(qo_modbus_sink *s)
{
    struct timespec t0, now;
    int fd = modbus_get_socket(s->ctx);
    int64_t total = (int64_t)s->set.response_timeout_us, el;
    if (s->drained) return;
    s->drained = 1;
    s->st.drains++;
    now_ts(&t0);
    for (;;) {
        struct pollfd pf;
        uint8_t junk[64];
        ssize_t n;
        int rc;
        now_ts(&now);
        el = (int64_t)(now.tv_sec - t0.tv_sec) * 1000000 + (int64_t)(now.tv_nsec - t0.tv_nsec) / 1000;
        if (fd < 0 || el >= total) break;
        pf.fd = fd;
        pf.events = POLLIN;
        pf.revents = 0;
        rc = poll(&pf, 1, (int)((total - el + 999) / 1000));
        if (rc < 0 && errno == EINTR) continue;
        if (rc <= 0) break;
        n = read(fd, junk, sizeof junk);
        if (n <= 0) break;
        s->st.drained_bytes += (uint64_t)n;
    }
    modbus_flush(s->ctx);
}

/* Before the first write of a tick to the slave of groups[g0...]: every uncertain joint of
 * that slave is read back (FC03 on its group's target registers) and its range collapsed to
 * the value read. An exception reply (targets not readable) falls back to the feedback
 * registers, or keeps the old range. Any other failure: nothing may be written to that
 * slave this tick; the error is returned and the joints stay uncertain. */
static qo_status settle_slave(qo_modbus_sink *s, size_t g0)
{
    unsigned slave = s->lay->req[g0].slave;
    size_t g, i;
    int any = 0;
    for (g = g0; g < s->lay->n_requests && s->lay->req[g].slave == slave; g++)
        for (i = 0; i < s->lay->req[g].n_items; i++)
            if (s->js[s->lay->item[s->lay->req[g].first_item + i].joint].uncertain) any = 1;
    if (!any) return QO_OK;
    if (s->spec.transport == QO_MODBUS_LINK_RTU) drain_line(s);
    for (g = g0; g < s->lay->n_requests && s->lay->req[g].slave == slave; g++) {
        const qo_modbus_layout_request *gr = &s->lay->req[g];
        uint16_t regs[QO_REGMAP_MAX_REGISTERS];
        qo_status st;
        int unc, pend, sent, need = 0;
        for (i = 0; i < gr->n_items; i++)
            if (s->js[s->lay->item[gr->first_item + i].joint].uncertain) need = 1;
        if (!need) continue;
        memset(regs, 0, sizeof regs);
        st = xfer(s, slave, MODBUS_FC_READ_HOLDING_REGISTERS, gr->start, gr->count, NULL, regs,
                  -1, &unc, &pend, &sent);
        if (sent) s->st.readbacks++;
        sleep_us(gr->gap_us);
        /* Only "illegal function / address" says the targets cannot be read; any other
         * exception (busy, device failure) is transient: hold the slave, retry next tick. */
        if (st != QO_OK &&
            (unc || (s->last_errno != MODBUS_ENOBASE + MODBUS_EXCEPTION_ILLEGAL_FUNCTION &&
                     s->last_errno != MODBUS_ENOBASE + MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS)))
            return st;
        if (st != QO_OK) s->st.readback_fallbacks++;
        for (i = 0; i < gr->n_items; i++) {
            const qo_modbus_layout_item *it = &s->lay->item[gr->first_item + i];
            const qo_regmap_joint *j = &s->map->joints[it->joint];
            qo_joint_guard *q = &s->js[it->joint];
            double raw;
            if (!q->uncertain) continue;
            if (st == QO_OK) {
                if (qo_modbus_reg_unpack_raw(j->fmt.type, j->fmt.order, regs + it->offset,
                                             &raw) != QO_OK)
                    return QO_E_PROTOCOL;
            } else if (j->has_feedback) {
                /* Weaker: feedback lags the target (see modbus_sink.h). */
                qo_status fs = read_joint_feedback(s, it->joint, &raw);
                if (fs != QO_OK) return fs;
            } else {
                q->uncertain = 0; /* the link is in step; the old range stays */
                continue;
            }
            qo_joint_guard_known(q, raw);
        }
    }
    return QO_OK;
}

static void fail_action(qo_modbus_sink *s)
{
    s->st.actions++;
    if (s->set.on_fail == QO_MODBUS_SINK_ON_FAIL_DISABLE) {
        s->disabled = 1;
        s->st.disabled = 1;
        if (s->connected) (void)send_writes(s, 1); /* best effort: the link is failing */
        link_down(s);
    }
    /* HOLD: the drives keep their last target and the link stays: closing and reopening a
     * link that is not broken only adds a slow first reply (the reconnect spiral). */
}

/* A rejected call (bad arguments, wrong state): counted, but it says nothing about the bus. */
static qo_status rejected(qo_modbus_sink *s, qo_status st)
{
    s->st.common.writes_failed++;
    s->st.common.consecutive_failures++;
    s->st.last_error = st;
    return st;
}

static qo_status tick_result(qo_modbus_sink *s, qo_status st)
{
    if (st == QO_OK) {
        s->st.common.writes_ok++;
        s->st.common.consecutive_failures = 0;
        s->bus_failures = 0;
        return QO_OK;
    }
    s->st.common.writes_failed++;
    s->st.common.consecutive_failures++;
    s->bus_failures++;
    s->st.last_error = st;
    if (st == QO_E_DISCONNECTED && s->connected) {
        link_down(s);
        if (s->set.on_fail == QO_MODBUS_SINK_ON_FAIL_DISABLE) {
            s->disabled = 1;
            s->st.disabled = 1;
            s->st.actions++;
        }
    } else if (s->connected && s->bus_failures >= s->set.fail_threshold) {
        fail_action(s);
    }
    return st;
}

qo_status qo_modbus_sink_write(qo_modbus_sink *s, const float *targets, size_t n,
                               uint64_t tick)
{
    size_t g, i;
    qo_status st = QO_OK, held = QO_OK;
    int soft = 0; /* TCP: a slave skipped or left waiting for its reply this tick */
    (void)tick;
    if (s == NULL) return QO_E_NULL;
    s->st.common.writes++;
    if (targets == NULL) return rejected(s, QO_E_NULL);
    if (s->closed || s->disabled) return rejected(s, QO_E_STATE);
    if (n != s->map->n_joints) return rejected(s, QO_E_RANGE);
    for (i = 0; i < n; i++)
        if (!isfinite(targets[i])) return rejected(s, QO_E_NONFINITE);
    if (!s->connected) return tick_result(s, QO_E_DISCONNECTED);
    s->drained = 0;
    if (s->tcp != NULL) {
        /* Replies that came after their tick are taken first: the drive's state is known. */
        now_ts(&s->tick_deadline);
        add_us(&s->tick_deadline, s->set.response_timeout_us);
        if (tcp_collect(s) != QO_OK) return tick_result(s, QO_E_DISCONNECTED);
    }
    s->in_tick = 1;
    for (g = 0; g < s->lay->n_requests && st == QO_OK; g++) {
        qo_modbus_layout_request *gr = &s->lay->req[g];
        int unc, pend, sent;
        if (g == 0 || gr->slave != s->lay->req[g - 1].slave) {
            /* First group of a slave: read back what is uncertain, then limit and pack every
             * group of the slave before sending any, so a blocked joint holds the whole
             * slave this tick. */
            size_t h;
            int blocked = 0;
            st = settle_slave(s, g);
            if (st == QO_E_TIMEOUT && s->tcp != NULL) {
                /* TCP: the read-back is outstanding (or still waits for an earlier reply):
                 * this slave holds until it is answered, the others go on */
                soft = 1;
                st = QO_OK;
                while (g + 1 < s->lay->n_requests && s->lay->req[g + 1].slave == gr->slave) g++;
                continue;
            }
            if (st != QO_OK) break;
            for (h = g; h < s->lay->n_requests && s->lay->req[h].slave == gr->slave; h++)
                for (i = 0; i < s->lay->req[h].n_items; i++) {
                    const qo_modbus_layout_item *it = &s->lay->item[s->lay->req[h].first_item + i];
                    if (limit_joint(s, it->joint, (double)targets[it->joint],
                                    s->lay->req[h].regs + it->offset) != QO_OK)
                        blocked = 1;
                }
            if (blocked) {
                held = QO_E_INFEASIBLE;
                g = h - 1; /* skip the slave; the other slaves are still written */
                continue;
            }
        }
        if (s->tcp != NULL) {
            /* TCP: noted before sending, so a reply taken in a later call finds them */
            for (i = 0; i < gr->n_items; i++)
                qo_joint_guard_sent(&s->js[s->lay->item[gr->first_item + i].joint]);
        }
        st = xfer(s, gr->slave, MODBUS_FC_WRITE_MULTIPLE_REGISTERS, gr->start, gr->count,
                  gr->regs, NULL, (int)g, &unc, &pend, &sent);
        if (s->tcp != NULL) {
            if (!sent) {
                for (i = 0; i < gr->n_items; i++) s->js[s->lay->item[gr->first_item + i].joint].pend = 0;
            } else if (st == QO_OK || (st == QO_E_PROTOCOL && !unc)) {
                group_answered(s, g, st == QO_OK);
            }
        }
        if (pend) {
            /* TCP, no reply yet: the request stays outstanding; this slave's later groups
             * wait for the next tick, the other slaves are still written. The drive may hold
             * the old or the new value until the reply comes. */
            for (i = 0; sent && i < gr->n_items; i++)
                qo_joint_guard_unknown(&s->js[s->lay->item[gr->first_item + i].joint]);
            soft = 1;
            while (g + 1 < s->lay->n_requests && s->lay->req[g + 1].slave == gr->slave) g++;
            st = QO_OK;
            continue;
        }
        for (i = 0; i < gr->n_items; i++) {
            qo_joint_guard *q = &s->js[s->lay->item[gr->first_item + i].joint];
            if (s->tcp != NULL) break; /* done by group_answered */
            /* unknown: the drive may hold the old or the new value, both stay reachable
             * (used only when the read-back falls back, see settle_slave) */
            if (st == QO_OK) qo_joint_guard_known(q, q->cmd);
            else if (unc) qo_joint_guard_unknown(q);
        }
        sleep_us(gr->gap_us);
    }
    s->in_tick = 0;
    if (st == QO_OK) st = held;
    if (st == QO_OK && soft) {
        /* Not every target went out, but nothing failed: a reply is late. Counted as a
         * failed write; not towards fail_threshold (silence_us bounds the wait). */
        s->st.common.writes_failed++;
        s->st.common.consecutive_failures++;
        s->st.last_error = QO_E_TIMEOUT;
        return QO_E_TIMEOUT;
    }
    return tick_result(s, st);
}

qo_status qo_modbus_sink_service(qo_modbus_sink *s)
{
    qo_status st;
    if (s == NULL) return QO_E_NULL;
    if (s->closed) return QO_E_STATE;
    if (s->connected) return QO_OK;
    if (!qo_modbus_link_backoff_due(&s->backoff)) return QO_E_DISCONNECTED;
    s->st.reconnect_attempts++;
    st = do_connect(s);
    if (st == QO_OK) {
        s->st.common.reconnects++;
        return QO_OK;
    }
    s->st.backoff_us = qo_modbus_link_backoff_failed(&s->backoff);
    return st;
}

qo_status qo_modbus_sink_enable(qo_modbus_sink *s)
{
    qo_status st = QO_OK;
    if (s == NULL) return QO_E_NULL;
    if (s->closed) return QO_E_STATE;
    if (s->connected) {
        st = send_writes(s, 0);
        if (st != QO_OK) return st;
    }
    s->disabled = 0;
    s->st.disabled = 0;
    s->st.common.consecutive_failures = 0;
    s->bus_failures = 0;
    return QO_OK;
}

qo_status qo_modbus_sink_seed(qo_modbus_sink *s, const float *positions, size_t n)
{
    size_t i;
    if (s == NULL || positions == NULL) return QO_E_NULL;
    if (n != s->map->n_joints) return QO_E_RANGE;
    for (i = 0; i < n; i++)
        if (!isfinite(positions[i])) return QO_E_NONFINITE;
    for (i = 0; i < n; i++) {
        const qo_regmap_joint *j = &s->map->joints[i];
        uint16_t regs[2];
        double raw, packed;
        (void)qo_modbus_reg_raw_from_value(&j->fmt, (double)positions[i], &raw);
        (void)qo_modbus_reg_pack_raw(j->fmt.type, j->fmt.order, raw, regs, &packed);
        s->js[i].have = 1;
        s->js[i].lo = s->js[i].hi = packed;
    }
    return QO_OK;
}

qo_status qo_modbus_sink_read_feedback(qo_modbus_sink *s, float *out, size_t n)
{
    size_t i;
    qo_status st = QO_OK;
    if (out == NULL) return QO_E_NULL;
    for (i = 0; i < n; i++) out[i] = NAN;
    if (s == NULL) return QO_E_NULL;
    if (n != s->map->n_joints) return QO_E_RANGE;
    if (s->closed) return QO_E_STATE;
    if (!s->connected) return QO_E_DISCONNECTED;
    for (i = 0; i < n && st == QO_OK; i++) {
        double raw, v;
        if (!s->map->joints[i].has_feedback) continue;
        st = read_joint_feedback(s, i, &raw);
        if (st == QO_OK) st = qo_modbus_reg_value_from_raw(&s->map->joints[i].fmt, raw, &v);
        if (st == QO_OK) out[i] = (float)v;
    }
    if (st != QO_OK)
        for (i = 0; i < n; i++) out[i] = NAN;
    return st;
}

static double goal_raw(const qo_modbus_sink *s, size_t i, double v)
{
    return qo_joint_guard_goal(&s->js[i], &s->map->joints[i], v);
}

static int joint_holds(const qo_modbus_sink *s, size_t i, double goal)
{
    return qo_joint_guard_holds(&s->js[i], goal);
}

static int args_ok(const qo_modbus_sink *s, const float *final, size_t n)
{
    size_t i;
    if (s == NULL || final == NULL || n != s->map->n_joints) return 0;
    for (i = 0; i < n; i++)
        if (!isfinite(final[i])) return 0;
    return 1;
}

double qo_modbus_sink_settle_time(const qo_modbus_sink *s, const float *final, size_t n,
                                  double period_s)
{
    double ticks = 1.0;
    size_t i;
    if (!args_ok(s, final, n) || !(period_s > 0.0) || !isfinite(period_s))
        return QO_MODBUS_SINK_SETTLE_SLACK_S;
    for (i = 0; i < n; i++) {
        const qo_joint_guard *q = &s->js[i];
        double g = goal_raw(s, i, (double)final[i]), d, t;
        if (!q->have || q->step <= 0.0) continue;
        d = fmax(fabs(g - q->lo), fabs(g - q->hi));
        t = ceil(d / q->step) + 1.0;
        if (t > ticks) ticks = t;
    }
    return 2.0 * ticks * period_s + QO_MODBUS_SINK_SETTLE_SLACK_S;
}

static double since_s(const struct timespec *t0)
{
    struct timespec now;
    now_ts(&now);
    return (double)(now.tv_sec - t0->tv_sec) + (double)(now.tv_nsec - t0->tv_nsec) * 1e-9;
}

/* Reads every joint's target back (the read-back of a fault, forced): the value read is
 * what the drive holds. QO_OK or the first bus error. */
static qo_status confirm_targets(qo_modbus_sink *s)
{
    size_t g, i;
    for (i = 0; i < s->map->n_joints; i++) s->js[i].uncertain = 1;
    s->drained = 1; /* the last write was answered: nothing is late on the line */
    now_ts(&s->tick_deadline);
    add_us(&s->tick_deadline, s->set.response_timeout_us);
    for (g = 0; g < s->lay->n_requests; g++) {
        qo_status st;
        if (g > 0 && s->lay->req[g].slave == s->lay->req[g - 1].slave) continue;
        st = settle_slave(s, g);
        if (st != QO_OK) return st;
    }
    return QO_OK;
}

static void settle_report(const qo_modbus_sink *s, const double *goal,
                          qo_modbus_sink_settle_report *out)
{
    size_t i;
    out->reached = 1;
    for (i = 0; i < out->n; i++) {
        const qo_regmap_joint *j = &s->map->joints[i];
        const qo_joint_guard *q = &s->js[i];
        double v = NAN, gv = NAN;
        (void)qo_modbus_reg_value_from_raw(&j->fmt, goal[i], &gv);
        if (q->have && q->lo == q->hi) (void)qo_modbus_reg_value_from_raw(&j->fmt, q->lo, &v);
        out->goal[i] = gv;
        out->held[i] = v;
        out->short_of[i] = !joint_holds(s, i, goal[i]);
        if (out->short_of[i]) out->reached = 0;
    }
}

qo_status qo_modbus_sink_settle(qo_modbus_sink *s, const float *final, size_t n,
                                double period_s, double deadline_s,
                                qo_modbus_sink_settle_report *out)
{
    double goal[QO_REGMAP_MAX_JOINTS];
    struct timespec t0, next;
    int64_t period_ns;
    size_t i;
    if (out == NULL) return QO_E_NULL;
    memset(out, 0, sizeof *out);
    for (i = 0; i < QO_REGMAP_MAX_JOINTS; i++) out->goal[i] = out->held[i] = NAN;
    out->deadline_s = deadline_s;
    if (s == NULL || final == NULL) return QO_E_NULL;
    if (n != s->map->n_joints) return QO_E_RANGE;
    if (!args_ok(s, final, n)) return QO_E_NONFINITE;
    if (!(period_s > 0.0) || !isfinite(period_s) || !(deadline_s >= 0.0) || !isfinite(deadline_s))
        return QO_E_LIMIT;
    if (s->closed || s->disabled) return QO_E_STATE;
    out->n = n;
    for (i = 0; i < n; i++) goal[i] = goal_raw(s, i, (double)final[i]);
    period_ns = (int64_t)(period_s * 1e9 + 0.5);
    if (period_ns < 1) period_ns = 1;
    now_ts(&t0);
    next = t0;
    for (;;) {
        int all = s->connected;
        for (i = 0; i < n && all; i++) all = joint_holds(s, i, goal[i]);
        /* Acknowledged is not yet held: confirm by reading the targets back. */
        if (all && confirm_targets(s) == QO_OK) {
            for (i = 0; i < n && all; i++) all = joint_holds(s, i, goal[i]);
            if (all) break;
        }
        if (since_s(&t0) >= deadline_s) break;
        if (!s->connected) (void)qo_modbus_sink_service(s);
        if (s->connected) {
            (void)qo_modbus_sink_write(s, final, n, out->ticks);
            out->ticks++;
        }
        next.tv_nsec += (long)(period_ns % 1000000000);
        next.tv_sec += (time_t)(period_ns / 1000000000);
        if (next.tv_nsec >= 1000000000L) {
            next.tv_sec++;
            next.tv_nsec -= 1000000000L;
        }
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, NULL) == EINTR) {
        }
        if (s->closed || s->disabled) break;
    }
    out->elapsed_s = since_s(&t0);
    settle_report(s, goal, out);
    return out->reached ? QO_OK : QO_E_TIMEOUT;
}

qo_status qo_modbus_sink_get_stats(const qo_modbus_sink *s, qo_modbus_sink_stats *out)
{
    if (out == NULL) return QO_E_NULL;
    memset(out, 0, sizeof *out);
    if (s == NULL) return QO_E_NULL;
    *out = s->st;
    if (s->tcp != NULL) out->stale_replies += s->tcp->stale;
    return QO_OK;
}

void qo_modbus_sink_close(qo_modbus_sink *s)
{
    if (s == NULL || s->closed) return;
    if (s->ctx != NULL) modbus_close(s->ctx);
    s->connected = 0;
    s->closed = 1;
    s->st.common.connected = 0;
}

void qo_modbus_sink_free(qo_modbus_sink *s)
{
    if (s == NULL) return;
    qo_modbus_sink_close(s);
    if (s->ctx != NULL) modbus_free(s->ctx);
    free(s->lay);
    free(s->js);
    free(s->tcp);
    free(s);
}

static qo_status sink_write(void *ctx, const float *targets, size_t n, uint64_t tick)
{
    return qo_modbus_sink_write(ctx, targets, n, tick);
}

static qo_status sink_flush(void *ctx)
{
    qo_modbus_sink *s = ctx;
    if (s == NULL) return QO_E_NULL;
    if (s->closed) return QO_E_STATE;
    return QO_OK; /* every write is sent at once: nothing is buffered */
}

static void sink_close(void *ctx)
{
    qo_modbus_sink_close(ctx);
}

static void sink_service(void *ctx)
{
    /* Reconnection with backoff; its status shows up in the statistics, not here. */
    (void)qo_modbus_sink_service(ctx);
}

static qo_status sink_stats(void *ctx, qo_sink_stats *out)
{
    const qo_modbus_sink *s = ctx;
    return qo_sink_view_stats(s != NULL ? &s->st.common : NULL, out);
}

qo_status qo_modbus_sink_as_sink(qo_modbus_sink *s, qo_sink *out)
{
    static const qo_sink ops = { .write = sink_write, .flush = sink_flush, .close = sink_close,
                                 .stats = sink_stats, .service = sink_service };
    return qo_sink_view_fill(s, &ops, out);
}
