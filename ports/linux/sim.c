#include "linux/sim.h"

#include <errno.h>
#include <math.h>
#include <poll.h>
#include <pthread.h>
#include <sched.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <arpa/inet.h>
#include <time.h>
#include <unistd.h>

#include <modbus.h>

#include "linux/modbus_link.h"

const qo_sim_settings qo_sim_settings_default = {
    0.05, NULL, { QO_SIM_FAULT_NONE, 0, 0.0, 0, 0 }, 1, 0, { { 0.0, 0.0, 0.0 } }, 0, 0
};

struct sim_joint {
    double target, position;
};

struct qo_sim {
    const qo_regmap *map;
    qo_sim_settings set;
    qo_modbus_link_spec spec;
    modbus_t *ctx;
    int listen_fd, client_fd, dev_fd;
    int port;
    modbus_mapping_t *maps[256];
    struct sim_joint *joints;
    struct timespec t0, last;
    uint64_t rng;
    uint64_t lag_rng;    /* the reply latency's own stream */
    uint64_t fault_base; /* request count when the fault was set */
    uint64_t fault_n;    /* faults since the fault was set */
    qo_sim_stats st;
    int stop;
    pthread_t thread;
    pthread_mutex_t mu;
    pthread_cond_t cv;
};

static uint64_t splitmix64(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double seconds_between(const struct timespec *a, const struct timespec *b)
{
    return (double)(b->tv_sec - a->tv_sec) + (double)(b->tv_nsec - a->tv_nsec) * 1e-9;
}

static void sleep_ms(unsigned ms)
{
    struct timespec d;
    d.tv_sec = (time_t)(ms / 1000u);
    d.tv_nsec = (long)(ms % 1000u) * 1000000L;
    while (nanosleep(&d, &d) != 0 && errno == EINTR) {
    }
}

/* Advances every joint's lag to now and refreshes its feedback registers. Holds mu. */
static void physics(qo_sim *s)
{
    struct timespec now;
    double dt, a;
    size_t i;
    clock_gettime(CLOCK_MONOTONIC, &now);
    dt = seconds_between(&s->last, &now);
    s->last = now;
    if (dt < 0.0) dt = 0.0;
    a = s->set.lag_s > 0.0 ? 1.0 - exp(-dt / s->set.lag_s) : 1.0;
    for (i = 0; i < s->map->n_joints; i++) {
        const qo_regmap_joint *j = &s->map->joints[i];
        struct sim_joint *q = &s->joints[i];
        q->position += (q->target - q->position) * a;
        if (j->has_feedback) {
            uint16_t regs[2];
            /* saturation is what a drive does */
            (void)qo_modbus_reg_pack(&j->fmt, q->position, regs);
            s->maps[j->slave]->tab_registers[j->feedback] = regs[0];
            if (qo_modbus_reg_type_width(j->fmt.type) == 2)
                s->maps[j->slave]->tab_registers[j->feedback + 1] = regs[1];
        }
    }
}

/* After registers [addr, addr+n) of `slave` were written: new targets, logged. Holds mu. */
static void note_write(qo_sim *s, unsigned slave, unsigned addr, unsigned n, uint64_t req)
{
    size_t i;
    for (i = 0; i < s->map->n_joints; i++) {
        const qo_regmap_joint *j = &s->map->joints[i];
        unsigned w = (unsigned)qo_modbus_reg_type_width(j->fmt.type);
        double v;
        if (j->slave != slave || j->address + w <= addr || addr + n <= j->address) continue;
        if (qo_modbus_reg_unpack(&j->fmt, &s->maps[slave]->tab_registers[j->address], &v) != QO_OK)
            continue; /* a float NaN pattern: the drive keeps its old target */
        s->joints[i].target = v;
        s->st.target_writes++;
        if (s->set.log != NULL) {
            struct timespec now;
            clock_gettime(CLOCK_MONOTONIC, &now);
            fprintf(s->set.log, "%.6f,%llu,%u,%zu,%s,%.9g\n", seconds_between(&s->t0, &now),
                    (unsigned long long)req, slave, i, j->name, v);
        }
    }
}

/* The written range of a write request, or 0 when it is not one. */
static int write_range(const uint8_t *req, int off, int len, unsigned *addr, unsigned *n)
{
    int fc = req[off];
    if (len < off + 5) return 0;
    if (fc == MODBUS_FC_WRITE_SINGLE_REGISTER) {
        *addr = ((unsigned)req[off + 1] << 8) | req[off + 2];
        *n = 1;
        return 1;
    }
    if (fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS) {
        *addr = ((unsigned)req[off + 1] << 8) | req[off + 2];
        *n = ((unsigned)req[off + 3] << 8) | req[off + 4];
        return len >= off + 6 + (int)*n * 2 && *n >= 1 && *n <= 123;
    }
    if (fc == MODBUS_FC_WRITE_AND_READ_REGISTERS && len >= off + 10) {
        *addr = ((unsigned)req[off + 5] << 8) | req[off + 6];
        *n = ((unsigned)req[off + 7] << 8) | req[off + 8];
        return len >= off + 10 + (int)*n * 2 && *n >= 1 && *n <= 121;
    }
    return 0;
}

/* Applies a write without replying (a reply lost on the way back). Holds mu. */
static void apply_write(qo_sim *s, unsigned slave, const uint8_t *req, int off, unsigned addr,
                        unsigned n)
{
    unsigned k;
    int fc = req[off];
    uint16_t *tab = s->maps[slave]->tab_registers;
    if (addr + n > 65536u) return;
    if (fc == MODBUS_FC_WRITE_SINGLE_REGISTER) {
        tab[addr] = (uint16_t)(((unsigned)req[off + 3] << 8) | req[off + 4]);
        return;
    }
    for (k = 0; k < n; k++) {
        int p = off + (fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS ? 6 : 10) + 2 * (int)k;
        tab[addr + k] = (uint16_t)(((unsigned)req[p] << 8) | req[p + 1]);
    }
}

static double uniform01(uint64_t *state)
{
    return (double)(splitmix64(state) >> 11) * (1.0 / 9007199254740992.0);
}

static qo_sim_fault_kind decide(qo_sim *s, uint64_t k)
{
    const qo_sim_fault *f = &s->set.fault;
    uint64_t rel = k - s->fault_base;
    int hit = 0;
    if (f->kind == QO_SIM_FAULT_NONE) return QO_SIM_FAULT_NONE;
    if (f->after > 0 && rel > f->after && (f->count == 0 || rel <= f->after + f->count)) hit = 1;
    if (f->share > 0.0 && uniform01(&s->rng) < f->share) hit = 1;
    if (!hit || (f->count > 0 && s->fault_n >= f->count)) return QO_SIM_FAULT_NONE;
    s->fault_n++;
    s->st.faults++;
    return f->kind;
}

/* The reply delay of one request, microseconds (0 without a latency model). Holds mu. */
static unsigned draw_lag_us(qo_sim *s)
{
    double total = 0.0, u, acc = 0.0;
    size_t i;
    if (s->set.n_lag == 0) return 0;
    for (i = 0; i < s->set.n_lag; i++) total += s->set.lag[i].share;
    u = uniform01(&s->lag_rng) * total;
    for (i = 0; i + 1 < s->set.n_lag; i++) {
        acc += s->set.lag[i].share;
        if (u < acc) break;
    }
    {
        const qo_sim_lag *b = &s->set.lag[i];
        double ms = b->lo_ms + (b->hi_ms - b->lo_ms) * uniform01(&s->lag_rng);
        return (unsigned)(ms * 1000.0 + 0.5);
    }
}

static void sleep_us_sim(unsigned us)
{
    struct timespec d;
    d.tv_sec = (time_t)(us / 1000000u);
    d.tv_nsec = (long)(us % 1000000u) * 1000L;
    while (nanosleep(&d, &d) != 0 && errno == EINTR) {
    }
}

static int parse_ms(const char *p, const char *end, double *out)
{
    char buf[32];
    char *e;
    double scale = 1.0, v;
    size_t n = (size_t)(end - p);
    if (n >= 2 && strncmp(end - 2, "ms", 2) == 0) n -= 2;
    else if (n >= 2 && strncmp(end - 2, "us", 2) == 0) {
        n -= 2;
        scale = 1e-3;
    } else {
        return -1;
    }
    if (n == 0 || n >= sizeof buf) return -1;
    memcpy(buf, p, n);
    buf[n] = '\0';
    v = strtod(buf, &e);
    if (e == buf || *e != '\0' || !(v >= 0.0) || v * scale > 60000.0) return -1;
    *out = v * scale;
    return 0;
}

qo_status qo_sim_parse_lag_dist(const char *text, qo_sim_settings *set)
{
    const char *p = text;
    if (set == NULL) return QO_E_NULL;
    set->n_lag = 0;
    if (text == NULL) return QO_E_NULL;
    while (*p != '\0') {
        const char *end = strchr(p, ','), *colon, *dash;
        char buf[32];
        char *e;
        qo_sim_lag b;
        size_t n;
        if (end == NULL) end = p + strlen(p);
        colon = memchr(p, ':', (size_t)(end - p));
        if (colon == NULL || set->n_lag >= QO_SIM_LAG_MAX) goto bad;
        n = (size_t)(colon - p);
        if (n == 0 || n >= sizeof buf) goto bad;
        memcpy(buf, p, n);
        buf[n] = '\0';
        b.share = strtod(buf, &e);
        if (e == buf || *e != '\0' || !(b.share > 0.0) || !(b.share <= 1e6)) goto bad;
        dash = memchr(colon + 1, '-', (size_t)(end - colon - 1));
        if (dash == NULL) {
            if (parse_ms(colon + 1, end, &b.lo_ms) != 0) goto bad;
            b.hi_ms = b.lo_ms;
        } else {
            /* "5-12ms": the unit follows the upper bound and applies to both */
            char lo[40];
            size_t ul = 2, ln = (size_t)(dash - colon - 1);
            if (ln == 0 || ln + ul >= sizeof lo || end - dash < 3) goto bad;
            memcpy(lo, colon + 1, ln);
            memcpy(lo + ln, end - ul, ul);
            lo[ln + ul] = '\0';
            if (parse_ms(lo, lo + ln + ul, &b.lo_ms) != 0 || parse_ms(dash + 1, end, &b.hi_ms) != 0 ||
                b.lo_ms > b.hi_ms)
                goto bad;
        }
        set->lag[set->n_lag++] = b;
        p = *end == ',' ? end + 1 : end;
        if (*end == ',' && *p == '\0') goto bad;
    }
    if (set->n_lag > 0) return QO_OK;
bad:
    set->n_lag = 0;
    return QO_E_CONFIG;
}

/* 1 when req is an FC03 whose range covers a joint's target register. Holds nothing. */
static int reads_a_target(const qo_sim *s, unsigned slave, const uint8_t *req, int off, int len)
{
    unsigned addr, n;
    size_t i;
    if (len < off + 5 || req[off] != MODBUS_FC_READ_HOLDING_REGISTERS) return 0;
    addr = ((unsigned)req[off + 1] << 8) | req[off + 2];
    n = ((unsigned)req[off + 3] << 8) | req[off + 4];
    for (i = 0; i < s->map->n_joints; i++) {
        const qo_regmap_joint *j = &s->map->joints[i];
        unsigned w = (unsigned)qo_modbus_reg_type_width(j->fmt.type);
        if (j->slave == slave && j->address < addr + n && addr < j->address + w) return 1;
    }
    return 0;
}

/* Serves one framed request. `off` is the header length (TCP 7, RTU 1). */
static void serve(qo_sim *s, const uint8_t *req, int len)
{
    int off = modbus_get_header_length(s->ctx);
    unsigned slave = req[off - 1], addr = 0, n = 0;
    int is_write = write_range(req, off, len, &addr, &n);
    qo_sim_fault_kind fk;
    uint64_t k;
    unsigned delay, lag_us;
    pthread_mutex_lock(&s->mu);
    if (slave > 255 || s->maps[slave] == NULL) {
        pthread_mutex_unlock(&s->mu);
        if (s->spec.transport == QO_MODBUS_LINK_TCP)
            modbus_reply_exception(s->ctx, req, MODBUS_EXCEPTION_GATEWAY_TARGET);
        return;
    }
    k = ++s->st.requests;
    physics(s);
    fk = decide(s, k);
    delay = s->set.fault.delay_ms;
    lag_us = fk == QO_SIM_FAULT_NONE ? draw_lag_us(s) : 0;
    pthread_mutex_unlock(&s->mu);
    if (lag_us > 0) {
        /* a slow drive: it takes the request now and answers later */
        fk = QO_SIM_FAULT_DELAY;
        delay = 0;
    }

    if (fk == QO_SIM_FAULT_NONE && s->set.targets_unreadable && reads_a_target(s, slave, req, off, len)) {
        modbus_reply_exception(s->ctx, req, MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
        goto done;
    }
    switch (fk) {
    case QO_SIM_FAULT_EXCEPTION:
        modbus_reply_exception(s->ctx, req, MODBUS_EXCEPTION_SLAVE_OR_SERVER_FAILURE);
        break;
    case QO_SIM_FAULT_CLOSE:
        if (s->spec.transport == QO_MODBUS_LINK_TCP && s->client_fd >= 0) {
            close(s->client_fd);
            s->client_fd = -1;
        }
        break;
    case QO_SIM_FAULT_DROP:
        pthread_mutex_lock(&s->mu);
        if (is_write) {
            apply_write(s, slave, req, off, addr, n);
            note_write(s, slave, addr, n, k);
        }
        pthread_mutex_unlock(&s->mu);
        break;
    default:
        if (fk == QO_SIM_FAULT_DELAY) {
            /* Apply now, answer late: the master times out although the drive moved. */
            pthread_mutex_lock(&s->mu);
            if (is_write) {
                apply_write(s, slave, req, off, addr, n);
                note_write(s, slave, addr, n, k);
            }
            pthread_mutex_unlock(&s->mu);
            if (lag_us > 0) sleep_us_sim(lag_us);
            else sleep_ms(delay);
            pthread_mutex_lock(&s->mu);
            modbus_reply(s->ctx, req, len, s->maps[slave]);
            pthread_mutex_unlock(&s->mu);
            break;
        }
        pthread_mutex_lock(&s->mu);
        modbus_reply(s->ctx, req, len, s->maps[slave]);
        if (is_write) note_write(s, slave, addr, n, k);
        pthread_mutex_unlock(&s->mu);
        break;
    }
done:
    pthread_mutex_lock(&s->mu);
    pthread_cond_broadcast(&s->cv);
    pthread_mutex_unlock(&s->mu);
}

static int should_stop(qo_sim *s)
{
    int v;
    pthread_mutex_lock(&s->mu);
    v = s->stop;
    pthread_mutex_unlock(&s->mu);
    return v;
}

static void tcp_loop(qo_sim *s)
{
    uint8_t req[MODBUS_TCP_MAX_ADU_LENGTH];
    while (!should_stop(s)) {
        struct pollfd pf[2];
        int np = 1, rc;
        pf[0].fd = s->listen_fd;
        pf[0].events = POLLIN;
        pf[0].revents = 0;
        if (s->client_fd >= 0) {
            pf[1].fd = s->client_fd;
            pf[1].events = POLLIN;
            pf[1].revents = 0;
            np = 2;
        }
        rc = poll(pf, (nfds_t)np, 20);
        if (rc <= 0) continue;
        if (pf[0].revents & POLLIN) {
            int fd = accept(s->listen_fd, NULL, NULL);
            if (fd >= 0) {
                int one = 1;
                /* Replies go out at once, as a drive's: with Nagle a late reply could hold
                 * back the next one and leave the link one reply behind. */
                (void)setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
                /* One master at a time, as most drives: a reconnecting master replaces the
                 * old connection, which it may have abandoned without closing. */
                if (s->client_fd >= 0) close(s->client_fd);
                s->client_fd = fd;
                modbus_set_socket(s->ctx, fd);
                pthread_mutex_lock(&s->mu);
                s->st.connections++;
                pthread_mutex_unlock(&s->mu);
            }
            continue;
        }
        if (np == 2 && (pf[1].revents & (POLLIN | POLLHUP | POLLERR))) {
            rc = modbus_receive(s->ctx, req);
            if (rc < 0) {
                if (errno == ECONNRESET || errno == EBADF || errno == ETIMEDOUT || errno == EPIPE ||
                    errno == ENOTCONN) {
                    close(s->client_fd);
                    s->client_fd = -1;
                } else {
                    modbus_flush(s->ctx);
                }
                continue;
            }
            if (rc > 0) serve(s, req, rc);
        }
    }
}

static uint16_t crc16(const uint8_t *p, size_t n)
{
    uint16_t crc = 0xFFFF;
    size_t i;
    int b;
    for (i = 0; i < n; i++) {
        crc ^= p[i];
        for (b = 0; b < 8; b++) crc = (crc & 1u) ? (uint16_t)((crc >> 1) ^ 0xA001u) : (uint16_t)(crc >> 1);
    }
    return crc;
}

/* Expected RTU request length from what has arrived, 0 if not known yet, -1 if unknown FC. */
static int rtu_expected(const uint8_t *b, int n)
{
    if (n < 2) return 0;
    switch (b[1]) {
    case 0x01: case 0x02: case 0x03: case 0x04: case 0x05: case 0x06: return 8;
    case 0x0F: case 0x10: return n < 7 ? 0 : 9 + b[6];
    case 0x16: return 10;
    case 0x17: return n < 11 ? 0 : 13 + b[10];
    default: return -1;
    }
}

static void rtu_loop(qo_sim *s)
{
    uint8_t buf[MODBUS_RTU_MAX_ADU_LENGTH];
    int n = 0, drain = 0;
    while (!should_stop(s)) {
        struct pollfd pf;
        int rc, need;
        pf.fd = s->dev_fd;
        pf.events = POLLIN;
        pf.revents = 0;
        /* Silence ends a frame (and a drain after a bad one): 5 ms, as t3.5 at low baud. */
        rc = poll(&pf, 1, (n > 0 || drain) ? 5 : 20);
        if (rc == 0) {
            if (n > 0) {
                pthread_mutex_lock(&s->mu);
                s->st.bad_frames++;
                pthread_mutex_unlock(&s->mu);
            }
            n = 0;
            drain = 0;
            continue;
        }
        if (rc < 0) continue;
        if (drain) {
            uint8_t junk[64];
            if (read(s->dev_fd, junk, sizeof junk) <= 0) sleep_ms(1);
            continue;
        }
        rc = (int)read(s->dev_fd, buf + n, sizeof buf - (size_t)n);
        if (rc <= 0) {
            sleep_ms(1);
            continue;
        }
        n += rc;
        need = rtu_expected(buf, n);
        if (need < 0 || need > (int)sizeof buf) {
            drain = 1; /* unknown function or garbage: wait for silence */
            n = 0;
            pthread_mutex_lock(&s->mu);
            s->st.bad_frames++;
            pthread_mutex_unlock(&s->mu);
            continue;
        }
        if (need == 0 || n < need) continue;
        if (crc16(buf, (size_t)need - 2) != (uint16_t)(buf[need - 2] | (buf[need - 1] << 8))) {
            drain = 1;
            n = 0;
            pthread_mutex_lock(&s->mu);
            s->st.bad_frames++;
            pthread_mutex_unlock(&s->mu);
            continue;
        }
        if (s->maps[buf[0]] != NULL) serve(s, buf, need);
        /* Bytes after the frame belong to no request we sent an answer for: drop them. */
        n = 0;
    }
}

static void *thread_main(void *arg)
{
    qo_sim *s = arg;
    if (s->spec.transport == QO_MODBUS_LINK_TCP) tcp_loop(s);
    else rtu_loop(s);
    return NULL;
}

static void destroy(qo_sim *s)
{
    size_t i;
    if (s->client_fd >= 0) close(s->client_fd);
    if (s->listen_fd >= 0) close(s->listen_fd);
    if (s->ctx != NULL) {
        if (s->spec.transport == QO_MODBUS_LINK_RTU) modbus_close(s->ctx);
        modbus_free(s->ctx);
    }
    for (i = 0; i < 256; i++)
        if (s->maps[i] != NULL) modbus_mapping_free(s->maps[i]);
    free(s->joints);
    pthread_cond_destroy(&s->cv);
    pthread_mutex_destroy(&s->mu);
    free(s);
}

static int lag_ok(const qo_sim_settings *set)
{
    size_t i;
    if (set->n_lag > QO_SIM_LAG_MAX) return 0;
    for (i = 0; i < set->n_lag; i++) {
        const qo_sim_lag *b = &set->lag[i];
        if (!(b->share > 0.0) || !isfinite(b->share) || !(b->lo_ms >= 0.0) || !(b->lo_ms <= b->hi_ms) ||
            !(b->hi_ms <= 60000.0))
            return 0;
    }
    return 1;
}

static int fault_ok(const qo_sim_fault *f)
{
    return f->kind <= QO_SIM_FAULT_CLOSE && f->share >= 0.0 && f->share <= 1.0 &&
           f->delay_ms <= 60000u;
}

qo_status qo_sim_start(const char *spec, const qo_regmap *map, const qo_sim_settings *settings,
                       qo_sim **out)
{
    qo_sim *s;
    qo_status st;
    size_t i;
    pthread_condattr_t ca;
    if (out == NULL) return QO_E_NULL;
    *out = NULL;
    if (spec == NULL || map == NULL) return QO_E_NULL;
    if (settings == NULL) settings = &qo_sim_settings_default;
    if (map->n_joints == 0 || !(settings->lag_s >= 0.0) || !isfinite(settings->lag_s) ||
        settings->rt_priority < 0 || settings->rt_priority > 99 ||
        !fault_ok(&settings->fault) || !lag_ok(settings))
        return QO_E_CONFIG;
    s = calloc(1, sizeof *s);
    if (s == NULL) return QO_E_CAPACITY;
    s->listen_fd = s->client_fd = s->dev_fd = -1;
    pthread_mutex_init(&s->mu, NULL);
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
    pthread_cond_init(&s->cv, &ca);
    pthread_condattr_destroy(&ca);
    s->map = map;
    s->set = *settings;
    s->rng = settings->seed;
    s->lag_rng = settings->seed ^ 0x5A5A5A5A5A5A5A5Aull;
    st = qo_modbus_link_parse_spec(spec, &s->spec);
    if (st != QO_OK) goto fail;
    if (s->spec.transport == QO_MODBUS_LINK_TCP) {
        struct in_addr ia;
        struct in6_addr ia6;
        /* "localhost" is the IPv4 loopback here: one address to bind, one to print */
        if (strcmp(s->spec.host, "localhost") == 0) strcpy(s->spec.host, "127.0.0.1");
        if (inet_pton(AF_INET, s->spec.host, &ia) != 1 && inet_pton(AF_INET6, s->spec.host, &ia6) != 1) {
            st = QO_E_CONFIG;
            goto fail;
        }
    }
    s->joints = calloc(map->n_joints, sizeof *s->joints);
    if (s->joints == NULL) { st = QO_E_CAPACITY; goto fail; }
    for (i = 0; i < map->n_slaves; i++) {
        unsigned id = map->slaves[i].id;
        if (id > 255 || s->maps[id] != NULL) continue;
        s->maps[id] = modbus_mapping_new(0, 0, 65536, 0);
        if (s->maps[id] == NULL) { st = QO_E_CAPACITY; goto fail; }
    }
    for (i = 0; i < map->n_joints; i++) {
        const qo_regmap_joint *j = &map->joints[i];
        double v = 0.0;
        if (s->maps[j->slave] == NULL) { st = QO_E_CONFIG; goto fail; }
        (void)qo_modbus_reg_unpack(&j->fmt, &s->maps[j->slave]->tab_registers[j->address], &v);
        s->joints[i].target = s->joints[i].position = v;
    }
    s->ctx = qo_modbus_link_new_ctx(&s->spec);
    if (s->ctx == NULL) { st = QO_E_CONFIG; goto fail; }
    modbus_set_indication_timeout(s->ctx, 0, 200000);
    modbus_set_byte_timeout(s->ctx, 0, 100000);
    if (s->spec.transport == QO_MODBUS_LINK_TCP) {
        struct sockaddr_storage a;
        socklen_t al = sizeof a;
        struct in_addr ia;
        /* modbus_tcp_listen takes IPv4 only; an IPv6 literal goes through the _pi API */
        if (inet_pton(AF_INET, s->spec.host, &ia) == 1) s->listen_fd = modbus_tcp_listen(s->ctx, 2);
        else s->listen_fd = modbus_tcp_pi_listen(s->ctx, 2);
        if (s->listen_fd < 0) { st = QO_E_IO; goto fail; }
        if (getsockname(s->listen_fd, (struct sockaddr *)&a, &al) != 0) { st = QO_E_IO; goto fail; }
        s->port = a.ss_family == AF_INET6 ? ntohs(((struct sockaddr_in6 *)&a)->sin6_port)
                                          : ntohs(((struct sockaddr_in *)&a)->sin_port);
    } else {
        if (modbus_connect(s->ctx) != 0) { st = QO_E_IO; goto fail; }
        s->dev_fd = modbus_get_socket(s->ctx);
    }
    clock_gettime(CLOCK_MONOTONIC, &s->t0);
    s->last = s->t0;
    if (s->set.log != NULL) fputs("t_s,request,slave,joint_index,joint,value\n", s->set.log);
    {
        int started = 0;
        if (settings->rt_priority > 0) {
            pthread_attr_t at;
            struct sched_param sp;
            memset(&sp, 0, sizeof sp);
            sp.sched_priority = settings->rt_priority;
            pthread_attr_init(&at);
            if (pthread_attr_setinheritsched(&at, PTHREAD_EXPLICIT_SCHED) == 0 &&
                pthread_attr_setschedpolicy(&at, SCHED_FIFO) == 0 &&
                pthread_attr_setschedparam(&at, &sp) == 0)
                started = pthread_create(&s->thread, &at, thread_main, s) == 0;
            pthread_attr_destroy(&at);
        }
        /* without the privilege (EPERM): a normal thread */
        if (!started && pthread_create(&s->thread, NULL, thread_main, s) != 0) { st = QO_E_IO; goto fail; }
    }
    *out = s;
    return QO_OK;
fail:
    destroy(s);
    return st;
}

int qo_sim_port(const qo_sim *sim)
{
    return sim != NULL ? sim->port : 0;
}

qo_status qo_sim_set_fault(qo_sim *sim, const qo_sim_fault *fault)
{
    if (sim == NULL || fault == NULL) return QO_E_NULL;
    if (!fault_ok(fault)) return QO_E_CONFIG;
    pthread_mutex_lock(&sim->mu);
    sim->set.fault = *fault;
    sim->fault_base = sim->st.requests;
    sim->fault_n = 0;
    pthread_mutex_unlock(&sim->mu);
    return QO_OK;
}

qo_status qo_sim_get_joint(qo_sim *sim, size_t i, double *target, double *position)
{
    if (target != NULL) *target = 0.0;
    if (position != NULL) *position = 0.0;
    if (sim == NULL || target == NULL || position == NULL) return QO_E_NULL;
    if (i >= sim->map->n_joints) return QO_E_RANGE;
    pthread_mutex_lock(&sim->mu);
    physics(sim);
    *target = sim->joints[i].target;
    *position = sim->joints[i].position;
    pthread_mutex_unlock(&sim->mu);
    return QO_OK;
}

qo_status qo_sim_get_register(qo_sim *sim, unsigned slave, uint16_t address, uint16_t *value)
{
    if (value == NULL) return QO_E_NULL;
    *value = 0;
    if (sim == NULL) return QO_E_NULL;
    if (slave > 255 || sim->maps[slave] == NULL) return QO_E_RANGE;
    pthread_mutex_lock(&sim->mu);
    physics(sim);
    *value = sim->maps[slave]->tab_registers[address];
    pthread_mutex_unlock(&sim->mu);
    return QO_OK;
}

qo_status qo_sim_get_stats(qo_sim *sim, qo_sim_stats *out)
{
    if (out == NULL) return QO_E_NULL;
    memset(out, 0, sizeof *out);
    if (sim == NULL) return QO_E_NULL;
    pthread_mutex_lock(&sim->mu);
    *out = sim->st;
    pthread_mutex_unlock(&sim->mu);
    return QO_OK;
}

qo_status qo_sim_wait_requests(qo_sim *sim, uint64_t n, unsigned timeout_ms)
{
    struct timespec dl;
    qo_status st = QO_OK;
    if (sim == NULL) return QO_E_NULL;
    clock_gettime(CLOCK_MONOTONIC, &dl);
    dl.tv_sec += (time_t)(timeout_ms / 1000u);
    dl.tv_nsec += (long)(timeout_ms % 1000u) * 1000000L;
    if (dl.tv_nsec >= 1000000000L) {
        dl.tv_sec++;
        dl.tv_nsec -= 1000000000L;
    }
    pthread_mutex_lock(&sim->mu);
    while (sim->st.requests < n) {
        if (pthread_cond_timedwait(&sim->cv, &sim->mu, &dl) == ETIMEDOUT) {
            st = sim->st.requests >= n ? QO_OK : QO_E_TIMEOUT;
            break;
        }
    }
    pthread_mutex_unlock(&sim->mu);
    return st;
}

void qo_sim_stop(qo_sim *sim)
{
    if (sim == NULL) return;
    pthread_mutex_lock(&sim->mu);
    sim->stop = 1;
    pthread_mutex_unlock(&sim->mu);
    pthread_join(sim->thread, NULL);
    if (sim->set.log != NULL) fflush(sim->set.log);
    destroy(sim);
}
