/* The planning half shared by `qorient plan` and `qorient stream`: one options struct and
 * option table, one reader of input lines, one builder of the qorient/traj.h trajectory. The
 * two commands differ only in where the samples go (standard output, or a sink). */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void qo_cli_plan_opts_default(struct qo_cli_plan_opts *o)
{
    memset(o, 0, sizeof *o);
    o->sprofile = QO_SPLINE_CUBIC_C2;
    o->end = QO_SPLINE_END_CLAMPED;
    o->derivs = QO_SPLINE_DERIVS_ESTIMATED;
    o->mprofile = QO_MOTION_SCURVE;
    o->sync = QO_MOTION_SYNC_TIME;
    o->rate = 100.0;
    o->max_samples = QO_CLI_MAX_SAMPLES_DEFAULT;
}

static int pick(const char *who, const char *opt, const char *arg, const char *const *names,
                const char *expect, int *out)
{
    int i;
    for (i = 0; names[i]; i++)
        if (strcmp(arg, names[i]) == 0) {
            *out = i;
            return 0;
        }
    fprintf(stderr, "qorient %s: %s: %s is not %s\n", who, opt, QO_CLI_QUOTED(arg), expect);
    return 2;
}

/* A --sync list "time,none,phase,if-necessary": writes up to cap values to out (may be
 * NULL); returns the count, or -1 after a message naming the bad item. */
static int sync_items(const char *who, const char *arg, size_t cap, qo_motion_sync *out)
{
    static const char *const names[] = { "none", "time", "phase", "if-necessary" };
    const char *p = arg;
    int count = 0;
    for (;;) {
        size_t len = strcspn(p, ","), i;
        for (i = 0; i < 4; i++)
            if (strlen(names[i]) == len && strncmp(p, names[i], len) == 0) break;
        if (i == 4) {
            char q[QO_CLI_QUOTE_CAP];
            fprintf(stderr, "qorient %s: --sync: item %d %s is not time, phase, none or if-necessary\n",
                    who, count + 1, qo_cli_quote(q, sizeof q, p, (long)len));
            return -1;
        }
        if (out != NULL && (size_t)count < cap) out[count] = (qo_motion_sync)i;
        count++;
        if (p[len] == '\0') return count;
        p += len + 1;
    }
}

int qo_cli_plan_opt(const char *who, struct qo_cli_plan_opts *o, int opt, const char *arg)
{
    static const char *const profiles[] = { "linear", "cubic", "catmull", "spline", "quintic",
                                            "trapezoid", "scurve", NULL };
    static const char *const ends[] = { "rest", "natural", NULL };
    static const char *const cols[] = { "p", "pv", "pva", NULL };
    static const char *const derivs[] = { "estimated", "zero", NULL };
    static const char *const syncs[] = { "none", "time", "phase", "if-necessary", NULL };
    int k = 0;
    double v;
    switch (opt) {
    case QO_CLI_OPT_PROFILE:
        if (pick(who, "--profile", arg, profiles,
                 "linear, cubic, catmull, spline, quintic, trapezoid or scurve", &k))
            return 2;
        o->motion = k >= 5;
        if (o->motion) o->mprofile = k == 5 ? QO_MOTION_TRAPEZOID : QO_MOTION_SCURVE;
        else o->sprofile = (qo_spline_profile)k;
        return 0;
    case QO_CLI_OPT_RATE:
        return qo_cli_number(who, "--rate", arg, QO_CLI_RATE_MIN, QO_CLI_RATE_MAX, "Hz", &o->rate);
    case QO_CLI_OPT_MAX_SAMPLES:
        if (qo_cli_count(who, "--max-samples", arg, 1.0, QO_CLI_MAX_SAMPLES_LIMIT, &v))
            return 2;
        o->max_samples = floor(v);
        return 0;
    case QO_CLI_OPT_END:
        if (pick(who, "--end", arg, ends, "rest or natural", &k)) return 2;
        o->end = (qo_spline_end)k;
        o->key_opt = "--end";
        return 0;
    case QO_CLI_OPT_COLUMNS:
        if (pick(who, "--columns", arg, cols, "p, pv or pva", &k)) return 2;
        o->columns = k + 1;
        o->key_opt = "--columns";
        return 0;
    case QO_CLI_OPT_DERIVS:
        if (pick(who, "--derivs", arg, derivs, "estimated or zero", &k)) return 2;
        o->derivs = (qo_spline_derivs)k;
        o->key_opt = "--derivs";
        return 0;
    case QO_CLI_OPT_SYNC:
        if (!o->motion_opt) o->motion_opt = "--sync";
        o->sync_list = NULL;
        o->sync = QO_MOTION_SYNC_TIME;
        if (strchr(arg, ',') == NULL) {
            if (pick(who, "--sync", arg, syncs, "time, phase, none or if-necessary", &k)) return 2;
            o->sync = (qo_motion_sync)k;
            return 0;
        }
        /* one per joint: the names checked now, the count once the joints are known */
        if (sync_items(who, arg, 0, NULL) < 0) return 2;
        o->sync_list = arg;
        return 0;
    case QO_CLI_OPT_VMIN: o->vmin = arg; if (!o->motion_opt) o->motion_opt = "--vmin"; return 0;
    case QO_CLI_OPT_AMIN: o->amin = arg; if (!o->motion_opt) o->motion_opt = "--amin"; return 0;
    case QO_CLI_OPT_TARGET_VELOCITIES:
        o->target_vel = 1;
        if (!o->motion_opt) o->motion_opt = "--target-velocities";
        return 0;
    case QO_CLI_OPT_MIN_DURATION:
        if (qo_cli_number(who, "--min-duration", arg, 0.0, QO_MOTION_DURATION_MAX, "s", &o->min_duration))
            return 2;
        if (!o->motion_opt) o->motion_opt = "--min-duration";
        return 0;
    case QO_CLI_OPT_DISCRETE: o->discrete = 1; if (!o->motion_opt) o->motion_opt = "--discrete"; return 0;
    case QO_CLI_OPT_VMAX: o->vmax = arg; if (!o->motion_opt) o->motion_opt = "--vmax"; return 0;
    case QO_CLI_OPT_AMAX: o->amax = arg; if (!o->motion_opt) o->motion_opt = "--amax"; return 0;
    case QO_CLI_OPT_JMAX: o->jmax = arg; if (!o->motion_opt) o->motion_opt = "--jmax"; return 0;
    case QO_CLI_OPT_MIN: o->min = arg; return 0;
    case QO_CLI_OPT_MAX: o->max = arg; return 0;
    case QO_CLI_OPT_WRAP: o->wrap = arg; return 0;
    case QO_CLI_OPT_UNWRAPPED: o->unwrapped = 1; o->key_opt = "--unwrapped"; return 0;
    case QO_CLI_OPT_DEGREES: o->degrees = 1; return 0;
    case QO_CLI_OPT_FIXED: o->fixed = 1; return 0;
    default: return 2;
    }
}

int qo_cli_plan_opts_check(const char *who, struct qo_cli_plan_opts *o)
{
    if (o->motion) {
        if (o->key_opt) {
            fprintf(stderr, "qorient %s: %s applies to keyframe profiles only, not --profile %s\n", who,
                    o->key_opt, o->mprofile == QO_MOTION_SCURVE ? "scurve" : "trapezoid");
            return 2;
        }
        if (!o->vmax || !o->amax || (o->mprofile == QO_MOTION_SCURVE && !o->jmax)) {
            fprintf(stderr, "qorient %s: --profile %s needs %s\n", who,
                    o->mprofile == QO_MOTION_SCURVE ? "scurve" : "trapezoid",
                    !o->vmax ? "--vmax" : !o->amax ? "--amax" : "--jmax");
            return 2;
        }
        o->columns = o->target_vel ? 2 : 1;
        return 0;
    }
    if (o->motion_opt) {
        fprintf(stderr, "qorient %s: %s applies to --profile trapezoid|scurve only; keyframe "
                "profiles take their timing from the keyframes\n", who, o->motion_opt);
        return 2;
    }
    if (o->columns == 0) o->columns = o->sprofile == QO_SPLINE_CUBIC_HERMITE ? 2 : 1;
    if (o->sprofile == QO_SPLINE_CUBIC_HERMITE && o->columns < 2) {
        fprintf(stderr, "qorient %s: --profile cubic needs key velocities: --columns pv\n", who);
        return 2;
    }
    if (o->columns > 1 && o->sprofile != QO_SPLINE_CUBIC_HERMITE && o->sprofile != QO_SPLINE_QUINTIC) {
        fprintf(stderr, "qorient %s: --columns pv|pva only with --profile cubic or quintic\n", who);
        return 2;
    }
    return 0;
}

/* ---- input lines ---- */

void qo_cli_rows_free(struct qo_cli_rows *r)
{
    free(r->v);
    free(r->line);
    free(r->t);
    memset(r, 0, sizeof *r);
}

int qo_cli_rows_add(const char *who, const char *name, const struct qo_cli_plan_opts *o, int has_time,
                    long lineno, char *text, long len, struct qo_cli_rows *r)
{
    double v[QO_CLI_MAX_FIELDS + 1];
    size_t n = 0, width;
    int pr;
    struct qo_cli_field bad;
    char why[QO_CLI_REASON_CAP];
    qo_traj_ns t = 0;
    if (len >= 0 && strlen(text) != (size_t)len) {
        fprintf(stderr, "qorient %s: %s: line %ld: contains a NUL byte\n", who, name, lineno);
        return 1;
    }
    pr = qo_cli_parse_fields(text, v, QO_CLI_MAX_FIELDS + 1, &n, &bad);
    if (pr == QO_CLI_NUM_MANY) {
        fprintf(stderr, "qorient %s: %s: line %ld: more than %d columns\n", who, name, lineno,
                QO_CLI_MAX_FIELDS + 1);
        return 1;
    }
    if (pr != 0) {
        /* the field, quoted (at most QO_CLI_QUOTE_MAX bytes, escaped), never the raw line */
        fprintf(stderr, "qorient %s: %s: line %ld: %s\n", who, name, lineno,
                qo_cli_field_reason(pr, &bad, "column", why, sizeof why));
        return 1;
    }
    if (n == 0) return 0;
    width = n - (size_t)has_time;
    if (r->rows == 0) {
        size_t per = (size_t)o->columns;
        if (width < 1 || width % per != 0 || (o->motion && width / per > QO_MOTION_MAX_JOINTS)) {
            fprintf(stderr, "qorient %s: %s: line %ld: %zu columns: expected %s%s per joint%s%s\n", who,
                    name, lineno, n, has_time ? "t and " : "",
                    per == 1 ? "1 number" : per == 2 ? "2 numbers" : "3 numbers",
                    o->motion && o->target_vel ? " (p1..pN,v1..vN: --target-velocities)" : "",
                    o->motion ? " (at most 32 joints)" : "");
            return 1;
        }
        r->width = width;
        r->first_line = lineno;
    } else if (width != r->width) {
        fprintf(stderr, "qorient %s: %s: line %ld: %zu columns, expected %zu as on line %ld\n", who, name,
                lineno, n, r->width + (size_t)has_time, r->first_line);
        return 1;
    }
    if (has_time) {
        if (qo_traj_ns_from_s(v[0], &t) != QO_OK) {
            fprintf(stderr, "qorient %s: %s: line %ld: time %.9g s is beyond the +-4.6e9 s supported\n",
                    who, name, lineno, v[0]);
            return 1;
        }
        if (r->rows > 0) {
            qo_traj_ns prev = r->t[r->rows - 1];
            if (o->motion ? t < prev : t <= prev) {
                fprintf(stderr, "qorient %s: %s: line %ld: time %.9g is %s the previous line's (line %ld): "
                        "times must %s\n", who, name, lineno, v[0], o->motion ? "before" : "not after",
                        r->line[r->rows - 1], o->motion ? "not decrease" : "increase strictly");
                return 1;
            }
        }
    }
    if (r->rows == r->cap) {
        size_t nc = r->cap ? 2 * r->cap : 64;
        double *nv = realloc(r->v, nc * r->width * sizeof *nv);
        long *nl;
        qo_traj_ns *nt;
        if (nv == NULL) goto oom;
        r->v = nv;
        nl = realloc(r->line, nc * sizeof *nl);
        if (nl == NULL) goto oom;
        r->line = nl;
        nt = realloc(r->t, nc * sizeof *nt);
        if (nt == NULL) goto oom;
        r->t = nt;
        r->cap = nc;
    }
    memcpy(r->v + r->rows * r->width, v + has_time, r->width * sizeof *v);
    r->t[r->rows] = t;
    r->line[r->rows] = lineno;
    r->rows++;
    return 0;
oom:
    fprintf(stderr, "qorient %s: out of memory\n", who);
    return 1;
}

int qo_cli_rows_read(const char *who, const struct qo_cli_plan_opts *o, const char *path,
                     struct qo_cli_rows *r)
{
    FILE *in = stdin;
    const char *name = path ? path : "-";
    char *line = NULL;
    size_t cap = 0, left = QO_CLI_INPUT_MAX;
    long len = -1, lineno = 0;
    int rc = 0;
    if (path && strcmp(path, "-") != 0) {
        in = fopen(path, "r");
        if (in == NULL) {
            fprintf(stderr, "qorient %s: %s: %s\n", who, path, strerror(errno));
            return 1;
        }
    }
    while (rc == 0 && (len = qo_cli_getline(&line, &cap, in, &left)) >= 0) {
        size_t had = r->rows;
        rc = qo_cli_rows_add(who, name, o, 1, ++lineno, line, len, r);
        if (rc != 0 || r->rows == had) continue;
        /* Bounded as it is read, at the line that crosses the bound: what is refused after
         * reading (--max-samples) is refused before the rest is read. */
        if (r->rows * r->width > QO_CLI_MAX_VALUES) {
            fprintf(stderr, "qorient %s: %s: line %ld: more than %lu numbers (keyframes or targets x columns): "
                    "nothing more is read\n", who, name, lineno, QO_CLI_MAX_VALUES);
            rc = 1;
        } else if ((double)r->rows > o->max_samples) {
            fprintf(stderr, "qorient %s: %s: line %ld: more than --max-samples %.0f %s: nothing more is read "
                    "(raise --max-samples)\n", who, name, lineno, o->max_samples, o->motion ? "targets" : "keyframes");
            rc = 1;
        } else if (o->sampled && qo_cli_grid_rows(r->t[0], r->t[r->rows - 1], o->rate) > o->max_samples) {
            fprintf(stderr, "qorient %s: %s: line %ld: the plan is at least %.0f samples at %g Hz by this line's "
                    "time, more than --max-samples %.0f: lower --rate or raise --max-samples\n", who, name, lineno,
                    qo_cli_grid_rows(r->t[0], r->t[r->rows - 1], o->rate), o->rate, o->max_samples);
            rc = 1;
        }
    }
    if (rc == 0 && len < -1) {
        fprintf(stderr, "qorient %s: %s: line %ld: %s\n", who, name, lineno + 1, qo_cli_line_problem(len));
        rc = 1;
    } else if (rc == 0 && ferror(in)) {
        /* e.g. a directory: reading it fails with EISDIR, which is not an empty input */
        fprintf(stderr, "qorient %s: %s: read error: %s\n", who, name, strerror(errno));
        rc = 1;
    }
    free(line);
    if (in != stdin) fclose(in);
    if (rc == 0 && r->rows < (o->motion ? 1u : 2u)) {
        fprintf(stderr, "qorient %s: %s: %s, got %zu\n", who, name,
                o->motion ? "need a start line t,p1,...,pN" : "need at least 2 keyframes", r->rows);
        rc = 1;
    }
    return rc;
}

/* ---- the trajectory ---- */

void qo_cli_plan_free(struct qo_cli_plan *p)
{
    free(p->t);
    free(p->store);
    free(p->lo);
    free(p->hi);
    free(p->wrap);
    memset(p, 0, sizeof *p);
}

int qo_cli_plan_build(const char *who, const struct qo_cli_plan_opts *o, size_t n, size_t cap,
                      struct qo_cli_plan *p)
{
    double buf[QO_CLI_MAX_FIELDS];
    size_t j, len;
    qo_status st;
    memset(p, 0, sizeof *p);
    p->n = n;
    p->period = o->degrees ? 360.0 : 6.283185307179586;
    p->lo = malloc(n * sizeof *p->lo);
    p->hi = malloc(n * sizeof *p->hi);
    p->wrap = calloc(n, 1);
    if (!p->lo || !p->hi || !p->wrap) goto oom;
    if (qo_cli_list(who, "--min", o->min, n, -INFINITY, INFINITY, buf) != 0) return 2;
    for (j = 0; j < n; j++) p->lo[j] = o->min ? (float)buf[j] : -INFINITY;
    if (qo_cli_list(who, "--max", o->max, n, -INFINITY, INFINITY, buf) != 0) return 2;
    for (j = 0; j < n; j++) {
        p->hi[j] = o->max ? (float)buf[j] : INFINITY;
        if (p->lo[j] > p->hi[j]) {
            fprintf(stderr, "qorient %s: --min/--max: joint %zu: min %.9g > max %.9g\n", who, j + 1,
                    (double)p->lo[j], (double)p->hi[j]);
            return 2;
        }
    }
    if (qo_cli_joint_set(who, "--wrap", o->wrap, n, p->wrap) != 0) return 2;
    p->t = malloc(cap * sizeof *p->t);
    if (!o->motion) {
        qo_spline_settings_f32 *s = &p->sset;
        *s = qo_spline_settings_default;
        s->profile = o->sprofile;
        s->end = o->end;
        s->derivs = o->derivs;
        s->pos_min = o->min ? p->lo : NULL;
        s->pos_max = o->max ? p->hi : NULL;
        s->wrap = p->wrap;
        s->wrap_period = (float)p->period;
        s->wrap_output = !o->unwrapped;
        len = qo_traj_store_len(QO_TRAJ_KEYS, n, cap, (unsigned)o->columns);
        p->store = len ? malloc(len * sizeof *p->store) : NULL;
        if (!p->t || !p->store) goto oom;
        st = qo_traj_init_keys(&p->tr, n, s, (unsigned)o->columns, p->t, cap, p->store, len);
    } else {
        qo_motion_settings_f32 ms = qo_motion_settings_default;
        double v[QO_MOTION_MAX_JOINTS], a[QO_MOTION_MAX_JOINTS], jm[QO_MOTION_MAX_JOINTS];
        double vn[QO_MOTION_MAX_JOINTS], an[QO_MOTION_MAX_JOINTS];
        qo_motion_sync sy[QO_MOTION_MAX_JOINTS];
        int ns = 0;
        if (qo_cli_list(who, "--vmax", o->vmax, n, QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX, v) ||
            qo_cli_list(who, "--amax", o->amax, n, QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX, a) ||
            qo_cli_list(who, "--jmax", o->jmax, n, QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX, jm) ||
            qo_cli_list(who, "--vmin", o->vmin, n, -QO_MOTION_LIMIT_MAX, -QO_MOTION_LIMIT_MIN, vn) ||
            qo_cli_list(who, "--amin", o->amin, n, -QO_MOTION_LIMIT_MAX, -QO_MOTION_LIMIT_MIN, an))
            return 2;
        if (o->sync_list) {
            ns = sync_items(who, o->sync_list, QO_MOTION_MAX_JOINTS, sy);
            if (ns != (int)n) {
                fprintf(stderr, "qorient %s: --sync: %d values for %zu joints: give one, or one per joint\n", who,
                        ns, n);
                return 2;
            }
        }
        /* The planner refuses an asymmetry beyond QO_MOTION_LIMIT_RATIO (motion.h: what its
         * oracle verifies) with QO_E_LIMIT; say which option and joint, not only the status. */
        for (j = 0; j < n; j++) {
            const double r = QO_MOTION_LIMIT_RATIO;
            if (o->vmin && (-vn[j] > r * v[j] || v[j] > r * -vn[j])) {
                fprintf(stderr, "qorient %s: --vmin: joint %zu: %g is not within a factor %g of -vmax (%g)\n", who,
                        j + 1, vn[j], r, -v[j]);
                return 2;
            }
            if (o->amin && (-an[j] > r * a[j] || a[j] > r * -an[j])) {
                fprintf(stderr, "qorient %s: --amin: joint %zu: %g is not within a factor %g of -amax (%g)\n", who,
                        j + 1, an[j], r, -a[j]);
                return 2;
            }
        }
        for (j = 0; j < n; j++) {
            p->lim[j] = qo_motion_limits_default;
            p->lim[j].vmax = (float)v[j];
            p->lim[j].amax = (float)a[j];
            if (o->jmax) p->lim[j].jmax = (float)jm[j];
            if (o->vmin) p->lim[j].vmin = (float)vn[j];
            if (o->amin) p->lim[j].amin = (float)an[j];
            p->lim[j].pmin = p->lo[j];
            p->lim[j].pmax = p->hi[j];
            if (p->wrap[j]) p->lim[j].wrap = (float)p->period;
        }
        ms.profile = o->mprofile;
        ms.sync = o->sync;
        /* --target-velocities: storage for a velocity per target is what makes the queue
         * carry them (qo_traj_init_targets) */
        len = qo_traj_store_len(QO_TRAJ_TARGETS, n, cap, o->target_vel ? 2u : 1u);
        p->store = len ? malloc(len * sizeof *p->store) : NULL;
        if (!p->t || !p->store) goto oom;
        st = qo_traj_init_targets(&p->tr, n, p->lim, &ms, p->joints, p->t, cap, p->store, len);
        for (j = 0; st == QO_OK && j < (size_t)ns; j++) st = qo_traj_set_joint_sync(&p->tr, j, sy[j]);
        /* --discrete: the sample period is the control period, so a move issued on a sample
         * ends on one (1/rate is within the planner's period range for every --rate). */
        if (st == QO_OK)
            st = qo_traj_set_timing(&p->tr, (float)o->min_duration, o->discrete ? (float)(1.0 / o->rate) : 0.0f);
    }
    if (st != QO_OK) {
        fprintf(stderr, "qorient %s: cannot set up the plan: %s\n", who, qo_status_str(st));
        return 1;
    }
    return 0;
oom:
    fprintf(stderr, "qorient %s: out of memory\n", who);
    return 1;
}

int qo_cli_plan_push(const char *who, const char *name, struct qo_cli_plan *p, qo_traj_ns t,
                     const double *row, long lineno)
{
    /* zeroed: only the first n * per fields are filled, and gcc 12 for arm64/armhf (not x86-64)
     * warns that the const pointers passed to qo_traj_push may read the rest */
    float f[QO_CLI_MAX_FIELDS] = { 0 };
    size_t j, per = p->tr.kind == QO_TRAJ_KEYS ? p->tr.key_cols : p->tr.target_cols, n = p->n;
    int start = p->tr.kind == QO_TRAJ_TARGETS && !p->tr.started;
    qo_status st;
    for (j = 0; j < n * per; j++) {
        double x = row[j];
        /* A continuous joint's position is reduced in double first: float32 cannot hold 1e10
         * degrees to better than 1024, so wrapping it there lands anywhere. */
        if (j < n && p->wrap[j]) x = remainder(x, p->period);
        f[j] = (float)x;
    }
    /* A target velocity the limits refuse is named here, where its line is known (a live line
     * is applied later, at a tick): with zero acceleration, reachable = within [vmin, vmax]. */
    for (j = 0; p->tr.kind == QO_TRAJ_TARGETS && per >= 2 && j < n; j++) {
        float hi = p->lim[j].vmax, lo = p->lim[j].vmin != 0.0f ? p->lim[j].vmin : -hi;
        if (f[n + j] > hi || f[n + j] < lo) {
            fprintf(stderr, "qorient %s: %s: line %ld: joint %zu: target velocity %.9g is outside [%.9g, %.9g] "
                    "(--vmin, --vmax): refused\n", who, name, lineno, j + 1, (double)f[n + j], (double)lo, (double)hi);
            return 1;
        }
    }
    st = qo_traj_push(&p->tr, t, f, per >= 2 ? f + n : NULL, per >= 3 ? f + 2 * n : NULL);
    if (st == QO_E_ARG && start) {
        fprintf(stderr, "qorient %s: %s: line %ld: the start line is at rest: its velocities must be 0\n", who,
                name, lineno);
        return 1;
    }
    if (st != QO_OK) {
        fprintf(stderr, "qorient %s: %s: line %ld: %s\n", who, name, lineno,
                st == QO_E_ORDER ? "time too close to the previous key for float32 offsets from the "
                                   "first key (times must increase strictly)"
                                 : qo_status_str(st));
        return 1;
    }
    return 0;
}

int qo_cli_plan_trial(const char *who, const char *name, const struct qo_cli_plan_opts *o,
                      const struct qo_cli_rows *r, qo_traj_ns *end)
{
    struct qo_cli_plan p;
    float f[QO_MOTION_MAX_JOINTS];
    size_t k;
    int rc = qo_cli_plan_from_rows(who, name, o, r, &p);
    *end = r->t[0];
    for (k = 1; rc == 0 && k < r->rows; k++) {
        qo_status st = qo_traj_sample(&p.tr, r->t[k], f, NULL, NULL, NULL);
        if (k + 1 < r->rows && r->t[k + 1] == r->t[k]) continue; /* applied together */
        if (st == QO_E_LIMIT || st == QO_E_ARG) {
            fprintf(stderr, "qorient %s: %s: line %ld: the target state cannot be reached or held within the "
                    "limits (qo_motion_set_target_state_f32: %s): refused, nothing %s\n", who, name, r->line[k],
                    qo_status_str(st), who[0] == 'p' ? "printed" : "sent");
            rc = 1;
        }
    }
    if (rc == 0) (void)qo_traj_end_time(&p.tr, end);
    qo_cli_plan_free(&p);
    return rc;
}

int qo_cli_plan_from_rows(const char *who, const char *name, const struct qo_cli_plan_opts *o,
                          const struct qo_cli_rows *r, struct qo_cli_plan *p)
{
    size_t k, n = r->width / (size_t)o->columns;
    int rc = qo_cli_plan_build(who, o, n, r->rows, p);
    for (k = 0; rc == 0 && k < r->rows; k++)
        rc = qo_cli_plan_push(who, name, p, r->t[k], r->v + k * r->width, r->line[k]);
    if (rc == 0 && !o->motion) {
        qo_status st = qo_traj_prepare(&p->tr);
        if (st != QO_OK) {
            fprintf(stderr, "qorient %s: %s: the keyframes cannot be planned: %s\n", who, name,
                    qo_status_str(st));
            rc = 1;
        }
    }
    return rc;
}
