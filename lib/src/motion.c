/* Online point-to-point motion for N joints, float32: the planner (capture, synchronisation,
 * target states, safety logic). The one-joint solver is motion_solver.c, the Q16.16 export
 * motion_export.c. See qorient/motion.h for the contract and the design. */
#include "motion_internal.h"

#include <math.h>

const qo_motion_settings_f32 qo_motion_settings_default = { QO_MOTION_SCURVE, QO_MOTION_SYNC_TIME };
const qo_motion_limits_f32 qo_motion_limits_default = { 1.0f, 1.0f, 1.0f, -INFINITY, INFINITY, 0.0f, 0.0f, 0.0f };

mlim qo_motion_mlim(const qo_motion_limits_f32 *l)
{
    mlim m;
    m.vp = l->vmax;
    m.vn = l->vmin != 0.0f ? -l->vmin : l->vmax;
    m.ap = l->amax;
    m.an = l->amin != 0.0f ? -l->amin : l->amax;
    m.j = l->jmax;
    return m;
}

/* Turns segments from state (p, v, a) into the joint's phases (zero-length ones dropped). */
static void load(qo_motion_joint_f32 *jt, float p, float v, float a, const mseg *g, unsigned n, float final)
{
    mstate s;
    unsigned i;
    float t = 0.0f;
    s.p = p;
    s.v = v;
    s.a = a;
    jt->nph = 0;
    for (i = 0; i < n; i++) {
        if (g[i].seta) s.a = g[i].a;
        if (g[i].setv) s.v = g[i].v;
        if (!(g[i].d > 0.0f)) continue;
        jt->ph[jt->nph].t = t;
        jt->ph[jt->nph].p = s.p;
        jt->ph[jt->nph].v = s.v;
        jt->ph[jt->nph].a = s.a;
        jt->ph[jt->nph].j = g[i].j;
        jt->nph++;
        jt->ph[jt->nph - 1].d = g[i].d;
        mseg_integ(&s, &g[i]);
        t += g[i].d;
    }
    jt->final = final;
    jt->duration = t;
}

/* After the end of a plan (tau >= 0 seconds after it): a target acceleration aend ramps to zero
 * at jmax, then the joint moves on at constant velocity (vend + aend * ta / 2). p is the offset
 * from `final`. SCURVE only has aend != 0. */
mstate qo_motion_after_end(const qo_motion_joint_f32 *jt, float tau)
{
    mstate s;
    float a = jt->aend, v = jt->vend;
    if (!(tau > 0.0f)) tau = 0.0f;
    if (a == 0.0f) {
        s.p = v * tau;
        s.v = v;
        s.a = 0.0f;
    } else {
        float jr = a > 0.0f ? -jt->lim.jmax : jt->lim.jmax, ta = fabsf(a) / jt->lim.jmax, x = fminf(tau, ta);
        s.p = x * (v + x * (0.5f * a + x * jr * (1.0f / 6.0f)));
        s.v = v + x * (a + 0.5f * x * jr);
        s.a = x < ta ? a + x * jr : 0.0f;
        if (tau > ta) s.p += s.v * (tau - ta);
    }
    return s;
}

mstate qo_motion_joint_state(const qo_motion_joint_f32 *jt, float tau)
{
    mstate s;
    unsigned k;
    const qo_motion_phase_f32 *ph;
    if (jt->nph == 0 || tau >= jt->duration) {
        /* at rest at `final`, or moving on from it (velocity interface, target states) */
        s = qo_motion_after_end(jt, tau - jt->duration);
        s.p += jt->final;
        return s;
    }
    if (tau < 0.0f) tau = 0.0f;
    k = jt->nph - 1;
    while (k > 0 && jt->ph[k].t > tau) k--;
    ph = &jt->ph[k];
    /* Local time within the phase's own (exact) duration: the float start times are rounded
     * sums, the states at phase ends are not. */
    tau -= ph->t;
    if (tau > ph->d) tau = ph->d;
    s.p = ph->p + tau * (ph->v + tau * (0.5f * ph->a + tau * ph->j * (1.0f / 6.0f)));
    s.v = ph->v + tau * (ph->a + 0.5f * tau * ph->j);
    s.a = ph->a + tau * ph->j;
    return s;
}

/* Within [QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX] (NaN fails): keeps every ratio and product
 * of limits, positions and durations the planner forms inside float32. */
static int limit_in_range(float x)
{
    return x >= QO_MOTION_LIMIT_MIN && x <= QO_MOTION_LIMIT_MAX;
}

/* A negative limit vmin / amin: 0 (symmetric) or in [-QO_MOTION_LIMIT_MAX, -QO_MOTION_LIMIT_MIN]
 * and within a factor QO_MOTION_LIMIT_RATIO of its positive counterpart pos (what the oracle
 * verifies; motion.h). */
static int neg_limit_ok(float x, float pos)
{
    return x == 0.0f || (limit_in_range(-x) && -x <= QO_MOTION_LIMIT_RATIO * pos && pos <= QO_MOTION_LIMIT_RATIO * -x);
}

static int limits_ok(const qo_motion_limits_f32 *l)
{
    if (!limit_in_range(l->vmax) || !limit_in_range(l->amax) || !limit_in_range(l->jmax)) return 0;
    if (!neg_limit_ok(l->vmin, l->vmax) || !neg_limit_ok(l->amin, l->amax)) return 0;
    if (isnan(l->pmin) || isnan(l->pmax) || l->pmin > l->pmax) return 0;
    if (l->pmin == INFINITY || l->pmax == -INFINITY) return 0;
    if (!(l->wrap >= 0.0f && l->wrap <= QO_MOTION_POS_MAX)) return 0;
    return 1;
}

static int pos_in_range(float p)
{
    return fabsf(p) <= QO_MOTION_POS_MAX; /* NaN fails */
}

/* Every phase of every joint, its end state and the durations finite, positions in range:
 * checked after each plan so that a sample of an accepted plan cannot overflow. */
static int plan_ok(const qo_motion_planner_f32 *pl)
{
    size_t i;
    unsigned k;
    if (!isfinite(pl->duration)) return 0;
    for (i = 0; i < pl->n; i++) {
        const qo_motion_joint_f32 *jt = &pl->joints[i];
        if (!pos_in_range(jt->final) || !isfinite(jt->duration) || !isfinite(jt->vend) || !isfinite(jt->aend))
            return 0;
        for (k = 0; k < jt->nph; k++) {
            const qo_motion_phase_f32 *ph = &jt->ph[k];
            float d = ph->d;
            float v1 = ph->v + d * (ph->a + 0.5f * d * ph->j);
            if (!(pos_in_range(ph->p) && isfinite(ph->t) && isfinite(d) && isfinite(ph->v) &&
                  isfinite(ph->a) && isfinite(ph->j) && isfinite(v1) && isfinite(ph->a + d * ph->j) &&
                  isfinite(ph->p + d * (ph->v + d * (0.5f * ph->a + d * ph->j * (1.0f / 6.0f))))))
                return 0;
        }
    }
    return 1;
}

/* Safe state when no finite plan exists: every joint held at rest where it is (its captured
 * position, which is in range because it came from a checked plan or init). */
static void plan_hold(qo_motion_planner_f32 *pl)
{
    size_t i;
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        jt->nph = 0;
        jt->final = jt->goal = jt->p0;
        jt->duration = 0.0f;
        jt->vend = jt->aend = jt->goal_v = jt->goal_a = 0.0f;
    }
    pl->duration = 0.0f;
    pl->sync_used = QO_MOTION_SYNC_NONE;
    pl->unsynced = 0;
    pl->braking = 1;
    pl->vel_mode = 0;
}

/* Short way round for a continuous joint: d in (-w/2, w/2]. */
static float wrap_delta(float d, float w)
{
    float r = fmodf(d, w);
    if (r > 0.5f * w) r -= w;
    else if (r <= -0.5f * w) r += w;
    return r;
}

/* Samples every joint at t_now into its start state (p0, v0, a0) and moves t0 there. */
static void capture(qo_motion_planner_f32 *pl, float t_now)
{
    size_t i;
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        mstate s = qo_motion_joint_state(jt, t_now - pl->t0);
        if (!(pos_in_range(s.p) && isfinite(s.v) && isfinite(s.a))) {
            s.p = jt->final; /* not expected for a checked plan: its end, at rest */
            s.v = s.a = 0.0f;
        }
        jt->p0 = s.p;
        jt->v0 = s.v;
        jt->a0 = pl->settings.profile == QO_MOTION_SCURVE ? s.a : 0.0f;
        jt->vend = jt->aend = 0.0f; /* every plan made from here sets its own end state */
    }
    pl->t0 = t_now;
}

/* Velocity interface and safety stop: every joint from its start state to (goal_v, 0) as fast
 * as its limits allow, then on at goal_v (a brake: goal_v = 0, at rest there). No sync. The end
 * positions become the goals. */
static void plan_velocity(qo_motion_planner_f32 *pl)
{
    size_t i;
    int sc = pl->settings.profile == QO_MOTION_SCURVE;
    float dur = 0.0f;
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        mlim l = qo_motion_mlim(&jt->lim);
        mseg g[3];
        mstate s;
        unsigned k, n;
        s.p = jt->p0;
        s.v = jt->v0;
        s.a = jt->a0;
        jt->goal_a = 0.0f;
        n = (jt->v0 == jt->goal_v && jt->a0 == 0.0f) ? 0 : qo_motion_vchange(sc, jt->v0, jt->a0, jt->goal_v, &l, g);
        for (k = 0; k < n; k++) mseg_integ(&s, &g[k]);
        load(jt, jt->p0, jt->v0, jt->a0, g, n, s.p);
        jt->vend = jt->goal_v;
        jt->aend = 0.0f;
        jt->goal = s.p;
        if (jt->duration > dur) dur = jt->duration;
    }
    pl->duration = dur;
    pl->sync_used = QO_MOTION_SYNC_NONE;
    pl->unsynced = 0;
    pl->braking = 0;
    pl->vel_mode = 1;
}

static void plan_brake(qo_motion_planner_f32 *pl)
{
    size_t i;
    for (i = 0; i < pl->n; i++) pl->joints[i].goal_v = 0.0f;
    plan_velocity(pl);
    pl->braking = 1;
    pl->vel_mode = 0;
}

/* Brake; hold if even the stop would not be finite. */
static void plan_brake_safe(qo_motion_planner_f32 *pl)
{
    plan_brake(pl);
    if (!plan_ok(pl)) plan_hold(pl);
}

/* A minimum duration T >= 0 after qo_motion_set_timing_f32's rules: at least min_duration,
 * rounded up to a whole number of periods. T within 4e-7 relative above a whole number counts
 * as that number: 1 s with a period of 0.01f (0.0099999998) is 100 periods, not 101. */
static float timed(const qo_motion_planner_f32 *pl, float T)
{
    if (T > 0.0f && T < pl->min_duration) T = pl->min_duration;
    if (T > 0.0f && pl->period > 0.0f) T = fmaxf(ceilf(T / pl->period * (1.0f - 4e-7f)), 1.0f) * pl->period;
    return T;
}

/* Signed extremes of a loaded plan's velocity and acceleration and its largest |jerk|: at phase
 * ends, and the velocity also where the acceleration crosses zero inside a phase (its only
 * interior extremum). */
typedef struct mpeaks {
    float vhi, vlo, ahi, alo, j;
} mpeaks;

static mpeaks peaks(const qo_motion_joint_f32 *jt)
{
    mpeaks r = { 0.0f, 0.0f, 0.0f, 0.0f, 0.0f };
    unsigned k;
    for (k = 0; k < jt->nph; k++) {
        const qo_motion_phase_f32 *ph = &jt->ph[k];
        float d = ph->d, a1 = ph->a + d * ph->j, v1 = ph->v + d * (ph->a + 0.5f * d * ph->j);
        r.j = fmaxf(r.j, fabsf(ph->j));
        r.ahi = fmaxf(r.ahi, fmaxf(ph->a, a1));
        r.alo = fminf(r.alo, fminf(ph->a, a1));
        r.vhi = fmaxf(r.vhi, fmaxf(ph->v, v1));
        r.vlo = fminf(r.vlo, fminf(ph->v, v1));
        if ((ph->a < 0.0f) != (a1 < 0.0f) && ph->j != 0.0f) {
            float tz = -ph->a / ph->j;
            if (tz > 0.0f && tz < d) {
                float vz = ph->v + tz * (ph->a + 0.5f * tz * ph->j);
                r.vhi = fmaxf(r.vhi, vz);
                r.vlo = fminf(r.vlo, vz);
            }
        }
    }
    return r;
}

/* The synchronisation joint jt takes part in: its own (qo_motion_set_joint_sync_f32) or the
 * settings'; TIME_IF_NECESSARY resolved to TIME for a moving target state, else NONE. */
static qo_motion_sync joint_sync(const qo_motion_planner_f32 *pl, const qo_motion_joint_f32 *jt)
{
    qo_motion_sync s = jt->sync >= 0 ? (qo_motion_sync)jt->sync : pl->settings.sync;
    if (s == QO_MOTION_SYNC_TIME_IF_NECESSARY)
        s = (jt->goal_v != 0.0f || jt->goal_a != 0.0f) ? QO_MOTION_SYNC_TIME : QO_MOTION_SYNC_NONE;
    return s;
}

/* Displacement from the start position to the goal (short way round for a continuous joint). */
static float joint_delta(const qo_motion_joint_f32 *jt)
{
    float d = jt->goal - jt->p0;
    if (jt->lim.wrap > 0.0f) d = wrap_delta(d, jt->lim.wrap);
    return d;
}

static mprob joint_prob(const qo_motion_planner_f32 *pl, const qo_motion_joint_f32 *jt)
{
    mprob p;
    p.l = qo_motion_mlim(&jt->lim);
    p.v0 = jt->v0;
    p.a0 = jt->a0;
    p.dp = joint_delta(jt);
    p.vf = jt->goal_v;
    p.af = jt->goal_a;
    p.scurve = pl->settings.profile == QO_MOTION_SCURVE;
    return p;
}

/* The straight line of the PHASE joints: a unit profile s: 0 -> 1 with p_i = p0_i + d_i s.
 * Possible if every PHASE joint's start (v0, a0) and target (v, a) are proportional to its
 * displacement (the reference joint r: largest |d|). On success `unit` holds the profile (of
 * duration >= T if T > its minimum) and *dr the reference displacement. */
typedef struct mline {
    float kv, ka, kvf, kaf;
    mlim l;
} mline;

static int line_make(const qo_motion_planner_f32 *pl, mline *ln)
{
    size_t i, r = 0;
    float dr = 0.0f;
    for (i = 0; i < pl->n; i++) {
        const qo_motion_joint_f32 *jt = &pl->joints[i];
        float d = joint_delta(jt);
        if (joint_sync(pl, jt) == QO_MOTION_SYNC_PHASE && fabsf(d) > dr) {
            dr = fabsf(d);
            r = i;
        }
    }
    if (dr == 0.0f) return 0;
    {
        const qo_motion_joint_f32 *jr = &pl->joints[r];
        float d = joint_delta(jr);
        ln->kv = jr->v0 / d;
        ln->ka = jr->a0 / d;
        ln->kvf = jr->goal_v / d;
        ln->kaf = jr->goal_a / d;
    }
    ln->l.vp = ln->l.vn = ln->l.ap = ln->l.an = ln->l.j = INFINITY;
    for (i = 0; i < pl->n; i++) {
        const qo_motion_joint_f32 *jt = &pl->joints[i];
        mlim m = qo_motion_mlim(&jt->lim);
        float d = joint_delta(jt), ad = fabsf(d);
        /* the step a straight line may introduce: 1e-6 of the tighter bound (the larger one,
         * 12x vmax in make check-motion wide PHASE case 4862, let a re-plan jump by 0.06 and
         * 2.06 u/s, 1e-6 of vmin but 1e-6 and 4e-6 of vmax) */
        float vs = fmaxf(fminf(m.vp, m.vn), fabsf(jt->v0)), as = fmaxf(fminf(m.ap, m.an), fabsf(jt->a0));
        if (joint_sync(pl, jt) != QO_MOTION_SYNC_PHASE) continue;
        if (fabsf(jt->v0 - ln->kv * d) > 1e-6f * vs || fabsf(jt->a0 - ln->ka * d) > 1e-6f * as) return 0;
        if (fabsf(jt->goal_v - ln->kvf * d) > 1e-6f * vs || fabsf(jt->goal_a - ln->kaf * d) > 1e-6f * as) return 0;
        if (ad == 0.0f) continue;
        /* s' d_i in [-vn_i, vp_i]: the bounds swap for a negative displacement */
        ln->l.vp = fminf(ln->l.vp, (d > 0.0f ? m.vp : m.vn) / ad);
        ln->l.vn = fminf(ln->l.vn, (d > 0.0f ? m.vn : m.vp) / ad);
        ln->l.ap = fminf(ln->l.ap, (d > 0.0f ? m.ap : m.an) / ad);
        ln->l.an = fminf(ln->l.an, (d > 0.0f ? m.an : m.ap) / ad);
        ln->l.j = fminf(ln->l.j, m.j / ad);
    }
    /* The scalar profile's limits are ratios limit / |d|: a tiny d makes them so large that
     * the unit solve's products (amax^2 / jmax...) overflow; such a plan goes per joint. */
    return limit_in_range(ln->l.vp) && limit_in_range(ln->l.vn) && limit_in_range(ln->l.ap) &&
           limit_in_range(ln->l.an) && limit_in_range(ln->l.j);
}

/* The unit profile of the line, of its minimum duration (T = 0) or of exactly T, loaded into
 * `unit`; then checked against every PHASE joint's own limits (or its start values beyond
 * them): from a moving start the shared jerk min(jmax_i / |d_i|) may brake a joint's initial
 * acceleration too late (issue 11: 3.84x vmax). Returns 0 if no such profile is within them.
 * An excess of float32 rounding only (below LINE_ROUNDING) is solved again within limits
 * shrunk by it: a line whose velocity swings far past a small bound (vmin 1/18 of vmax, the
 * start near vmax, the cruise at vmin) ends that swing a few ulps of it beyond the bound,
 * 3.1e-6 relative in make check-motion wide PHASE case 87, and fell back to TIME. */
#define LINE_ROUNDING 1e-4f
#define LINE_PASSES 3
static int line_profile(const qo_motion_planner_f32 *pl, const mline *ln, float T, qo_motion_joint_f32 *unit)
{
    mprob p;
    msol s;
    mseg g[MSEGS];
    mpeaks pk;
    size_t i;
    int sc = pl->settings.profile == QO_MOTION_SCURVE, pass;
    const float tol = 1.0f + 1e-6f;
    float shrink = 1.0f;
    p.v0 = ln->kv;
    p.a0 = ln->ka;
    p.dp = 1.0f;
    p.vf = ln->kvf;
    p.af = ln->kaf;
    p.scurve = sc;
    for (pass = 0; pass < LINE_PASSES; pass++) {
        float w = 0.0f; /* the largest ratio of a PHASE joint's peak to its bound */
        p.l = ln->l;
        p.l.vp /= shrink;
        p.l.vn /= shrink;
        p.l.ap /= shrink;
        p.l.an /= shrink;
        p.l.j /= shrink;
        qo_motion_solve_min(&p, &s);
        if (T > s.t) {
            float vcs = s.fam == 0 ? s.x : fminf(fmaxf(p.v0 + p.a0 * fabsf(p.a0) / (2.0f * p.l.j), -p.l.vn), p.l.vp);
            if (!qo_motion_solve_time(&p, &s, vcs, T, &s)) return 0;
        } else if (pass > 0 && T > 0.0f && s.t > T) {
            return 0; /* shrunk past the duration asked for */
        }
        unit->lim = qo_motion_limits_default;
        load(unit, 0.0f, p.v0, p.a0, g, qo_motion_build(&p, &s, g), 1.0f);
        pk = peaks(unit);
        for (i = 0; i < pl->n; i++) {
            const qo_motion_joint_f32 *jt = &pl->joints[i];
            mlim m = qo_motion_mlim(&jt->lim);
            float d = joint_delta(jt), reach = jt->a0 * jt->a0 / (2.0f * m.j);
            float vhi = fmaxf(m.vp, jt->v0 + reach), vlo = fmaxf(m.vn, -jt->v0 + reach);
            float ahi = fmaxf(m.ap, jt->a0), alo = fmaxf(m.an, -jt->a0);
            float pvh = d > 0.0f ? d * pk.vhi : d * pk.vlo, pvl = d > 0.0f ? d * pk.vlo : d * pk.vhi;
            float pah = d > 0.0f ? d * pk.ahi : d * pk.alo, pal = d > 0.0f ? d * pk.alo : d * pk.ahi;
            if (joint_sync(pl, jt) != QO_MOTION_SYNC_PHASE || d == 0.0f) continue;
            w = fmaxf(w, fmaxf(fmaxf(pvh / vhi, -pvl / vlo), fmaxf(pah / ahi, -pal / alo)));
            if (sc) w = fmaxf(w, fabsf(d) * pk.j / m.j);
        }
        if (w <= tol) return 1;
        if (!(w < 1.0f + LINE_ROUNDING)) return 0;
        shrink *= w * tol;
    }
    return 0;
}

/* Loads the straight line `unit` into every PHASE joint. */
static void line_load(qo_motion_planner_f32 *pl, const qo_motion_joint_f32 *unit)
{
    size_t i;
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        float d = joint_delta(jt);
        unsigned k;
        if (joint_sync(pl, jt) != QO_MOTION_SYNC_PHASE) continue;
        if (d == 0.0f) {
            jt->nph = 0;
            jt->final = jt->p0;
            jt->duration = 0.0f;
            continue;
        }
        jt->nph = unit->nph;
        for (k = 0; k < unit->nph; k++) {
            jt->ph[k].t = unit->ph[k].t;
            jt->ph[k].d = unit->ph[k].d;
            jt->ph[k].p = jt->p0 + d * unit->ph[k].p;
            jt->ph[k].v = d * unit->ph[k].v;
            jt->ph[k].a = d * unit->ph[k].a;
            jt->ph[k].j = d * unit->ph[k].j;
        }
        jt->final = jt->p0 + d;
        jt->duration = unit->duration;
    }
}

/* 1 if the joint is at its target state already: no phases, never moves (or moves on). */
static int joint_arrived(const qo_motion_joint_f32 *jt, float d)
{
    return d == 0.0f && jt->v0 == jt->goal_v && jt->a0 == jt->goal_a;
}

/* Pass 1 of a plan: joint jt's minimum-time solve, kept in its first phase slot (x in v, tc in
 * d, the family in j, -1 = already at its target state; f0 in p, t0 in a) with its duration, until pass 2 loads
 * the profile. The phase array is the planner's storage and holds no plan in between, so a
 * re-plan needs no per-joint scratch beyond what the joint owns. */
static void plan_min(const qo_motion_planner_f32 *pl, qo_motion_joint_f32 *jt)
{
    mprob p = joint_prob(pl, jt);
    msol s;
    jt->nph = 0;
    jt->final = jt->p0 + p.dp;
    if (joint_arrived(jt, p.dp)) {
        s.x = s.tc = s.t = 0.0f;
        s.f0 = s.t0 = NAN;
        s.fam = -1;
    } else {
        qo_motion_solve_min(&p, &s);
    }
    jt->ph[0].v = s.x;
    jt->ph[0].d = s.tc;
    jt->ph[0].j = (float)s.fam;
    jt->ph[0].p = s.f0;
    jt->ph[0].a = s.t0;
    jt->duration = s.t;
}

/* Pass 2: joint jt's profile of duration Tj (its minimum if Tj is not longer), loaded. Returns 0
 * if no profile of the family has exactly Tj (the joint keeps its minimum time). */
static int plan_load(const qo_motion_planner_f32 *pl, qo_motion_joint_f32 *jt, float Tj)
{
    mprob p = joint_prob(pl, jt);
    msol s;
    mseg g[MSEGS];
    int ok = 1;
    s.x = jt->ph[0].v;
    s.tc = jt->ph[0].d;
    s.fam = (int)jt->ph[0].j;
    s.f0 = jt->ph[0].p;
    s.t0 = jt->ph[0].a;
    s.t = jt->duration;
    if (s.fam < 0) {
        jt->final = jt->p0;
        jt->duration = 0.0f;
        return 1;
    }
    if (s.t < Tj) {
        msol st;
        /* the exact-duration search starts from the minimum's extremum velocity; a dip meets
         * the extremum-velocity family at the velocity the start reaches (vs) */
        float vcs = s.fam == 0 ? s.x : p.scurve ? p.v0 + p.a0 * fabsf(p.a0) / (2.0f * p.l.j) : p.v0;
        vcs = fminf(fmaxf(vcs, -p.l.vn), p.l.vp);
        if (qo_motion_solve_time(&p, &s, vcs, Tj, &st)) s = st;
        else ok = 0;
    }
    load(jt, jt->p0, jt->v0, jt->a0, g, qo_motion_build(&p, &s, g), jt->p0 + p.dp);
    return ok;
}

/* Plans every joint from its start state toward its goal state with the planner's settings and
 * the per-joint synchronisation: PHASE joints on one straight line if feasible (else TIME),
 * TIME joints (and TIME_IF_NECESSARY joints with a moving target) to the common duration,
 * NONE joints at their own minimum time. Pass 1 solves each joint's minimum time, pass 2
 * stretches the synchronised ones to the common duration and loads every profile. */
static void plan_goals(qo_motion_planner_f32 *pl)
{
    size_t i;
    int line = 0, any_sync = 0;
    float T = 0.0f;
    mline ln;
    qo_motion_joint_f32 unit;
    pl->braking = 0;
    pl->vel_mode = 0;
    pl->unsynced = 0;
    for (i = 0; i < pl->n; i++) {
        qo_motion_sync s = joint_sync(pl, &pl->joints[i]);
        if (s != QO_MOTION_SYNC_NONE) any_sync = 1;
        if (s == QO_MOTION_SYNC_PHASE) line = 1;
    }
    /* a straight line has one duration: with duration rules that would change it, use TIME */
    if (line)
        line = line_make(pl, &ln) && line_profile(pl, &ln, 0.0f, &unit) && timed(pl, unit.duration) == unit.duration;
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        qo_motion_sync js = joint_sync(pl, jt);
        jt->vend = jt->goal_v;
        jt->aend = jt->goal_a;
        if (line && js == QO_MOTION_SYNC_PHASE) continue;
        plan_min(pl, jt);
        if (js != QO_MOTION_SYNC_NONE && jt->duration > T) T = jt->duration;
    }
    if (line && unit.duration > T) T = unit.duration;
    T = timed(pl, T);
    if (line && T > unit.duration && !line_profile(pl, &ln, T, &unit)) {
        /* the line cannot be stretched to the others' duration within the limits: the PHASE
         * joints go as TIME joints (their own minimum first, then the common duration) */
        line = 0;
        for (i = 0; i < pl->n; i++) {
            qo_motion_joint_f32 *jt = &pl->joints[i];
            if (joint_sync(pl, jt) != QO_MOTION_SYNC_PHASE) continue;
            plan_min(pl, jt);
            if (jt->duration > T) T = timed(pl, jt->duration);
        }
    }
    if (line) line_load(pl, &unit);
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        qo_motion_sync js = joint_sync(pl, jt);
        float Tj;
        if (line && js == QO_MOTION_SYNC_PHASE) continue;
        Tj = js != QO_MOTION_SYNC_NONE ? T : timed(pl, jt->duration);
        if (!plan_load(pl, jt, Tj)) pl->unsynced |= (uint32_t)1 << i;
    }
    pl->duration = 0.0f;
    for (i = 0; i < pl->n; i++)
        if (pl->joints[i].duration > pl->duration) pl->duration = pl->joints[i].duration;
    pl->sync_used = line ? QO_MOTION_SYNC_PHASE : any_sync ? QO_MOTION_SYNC_TIME : QO_MOTION_SYNC_NONE;
}

/* Plans toward the goals; QO_E_RANGE with the safe brake if the plan is not finite. */
static qo_status plan_goals_checked(qo_motion_planner_f32 *pl)
{
    plan_goals(pl);
    if (plan_ok(pl)) return QO_OK;
    plan_brake_safe(pl);
    return QO_E_RANGE;
}

/* Velocity plan; QO_E_RANGE with the safe brake if it is not finite. */
static qo_status plan_velocity_checked(qo_motion_planner_f32 *pl)
{
    plan_velocity(pl);
    if (plan_ok(pl)) return QO_OK;
    plan_brake_safe(pl);
    return QO_E_RANGE;
}

static int sync_valid(int s)
{
    return s == QO_MOTION_SYNC_NONE || s == QO_MOTION_SYNC_TIME || s == QO_MOTION_SYNC_PHASE ||
           s == QO_MOTION_SYNC_TIME_IF_NECESSARY;
}

qo_status qo_motion_init_f32(qo_motion_planner_f32 *pl, qo_motion_joint_f32 *joints, size_t n,
                             const qo_motion_limits_f32 *limits, const float *start, float t0,
                             const qo_motion_settings_f32 *settings)
{
    size_t i;
    qo_motion_settings_f32 st = settings ? *settings : qo_motion_settings_default;
    if (pl == NULL) return QO_E_NULL;
    pl->joints = joints;
    pl->n = 0;
    pl->settings = qo_motion_settings_default;
    pl->t0 = 0.0f;
    pl->duration = 0.0f;
    pl->sync_used = QO_MOTION_SYNC_NONE;
    pl->unsynced = 0;
    pl->braking = 0;
    pl->min_duration = 0.0f;
    pl->period = 0.0f;
    pl->vel_mode = 0;
    if (joints == NULL || limits == NULL || start == NULL) return QO_E_NULL;
    if (n == 0) return QO_E_TOO_FEW;
    if (n > QO_MOTION_MAX_JOINTS) return QO_E_CAPACITY;
    if ((st.profile != QO_MOTION_TRAPEZOID && st.profile != QO_MOTION_SCURVE) || !sync_valid((int)st.sync))
        return QO_E_ARG;
    for (i = 0; i < n; i++)
        if (!limits_ok(&limits[i])) return QO_E_LIMIT;
    if (!isfinite(t0)) return QO_E_NONFINITE;
    for (i = 0; i < n; i++)
        if (!isfinite(start[i])) return QO_E_NONFINITE;
    for (i = 0; i < n; i++)
        if (!pos_in_range(start[i])) return QO_E_RANGE;
    for (i = 0; i < n; i++) {
        qo_motion_joint_f32 *jt = &joints[i];
        jt->lim = limits[i];
        jt->goal = jt->final = jt->p0 = start[i];
        jt->duration = 0.0f;
        jt->nph = 0;
        jt->v0 = jt->a0 = 0.0f;
        jt->vend = jt->aend = 0.0f;
        jt->goal_v = jt->goal_a = 0.0f;
        jt->sync = -1;
    }
    pl->settings = st;
    pl->t0 = t0;
    pl->n = n;
    return QO_OK;
}

/* Common checks of the re-planning calls. */
static qo_status check_time(const qo_motion_planner_f32 *pl, float t_now)
{
    if (pl->n == 0 || pl->joints == NULL) return QO_E_STATE;
    if (!isfinite(t_now)) return QO_E_NONFINITE;
    if (t_now < pl->t0) return QO_E_ORDER;
    return QO_OK;
}

/* Whether (v, a) is a target state joint jt can reach and then hold within its limits: inside
 * the bounds, and the velocities a jerk ramp from / to a = 0 passes (v -+ a|a|/(2 jmax)) too.
 * QO_E_ARG for an acceleration with TRAPEZOID (no jerk limit, no defined ramp). */
static qo_status state_ok(const qo_motion_joint_f32 *jt, int scurve, float v, float a)
{
    mlim m = qo_motion_mlim(&jt->lim);
    float h;
    if (!scurve && a != 0.0f) return QO_E_ARG;
    if (v > m.vp || v < -m.vn || a > m.ap || a < -m.an) return QO_E_LIMIT;
    h = a * fabsf(a) / (2.0f * m.j);
    if (v + h > m.vp || v + h < -m.vn || v - h > m.vp || v - h < -m.vn) return QO_E_LIMIT;
    return QO_OK;
}

qo_status qo_motion_set_target_state_f32(qo_motion_planner_f32 *pl, float t_now, const float *pos,
                                         const float *vel, const float *acc, uint32_t *clamped)
{
    size_t i;
    uint32_t mask = 0;
    qo_status st;
    int sc;
    if (clamped) *clamped = 0;
    if (pl == NULL || pos == NULL) return QO_E_NULL;
    st = check_time(pl, t_now);
    if (st != QO_OK) return st;
    for (i = 0; i < pl->n; i++) {
        if (!isfinite(pos[i]) || (vel && !isfinite(vel[i])) || (acc && !isfinite(acc[i]))) {
            capture(pl, t_now);
            plan_brake_safe(pl);
            return QO_E_NONFINITE;
        }
    }
    sc = pl->settings.profile == QO_MOTION_SCURVE;
    /* refused target states change nothing: checked before the capture */
    for (i = 0; (vel || acc) && i < pl->n; i++) {
        st = state_ok(&pl->joints[i], sc, vel ? vel[i] : 0.0f, acc ? acc[i] : 0.0f);
        if (st != QO_OK) return st;
    }
    capture(pl, t_now);
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        float g = pos[i];
        if (g < jt->lim.pmin) {
            g = jt->lim.pmin;
            mask |= (uint32_t)1 << i;
        } else if (g > jt->lim.pmax) {
            g = jt->lim.pmax;
            mask |= (uint32_t)1 << i;
        }
        if (!pos_in_range(g)) {
            plan_brake_safe(pl);
            return QO_E_RANGE;
        }
        jt->goal = g;
        jt->goal_v = vel ? vel[i] : 0.0f;
        jt->goal_a = acc ? acc[i] : 0.0f;
    }
    st = plan_goals_checked(pl);
    if (clamped && st == QO_OK) *clamped = mask;
    return st;
}

qo_status qo_motion_set_target_f32(qo_motion_planner_f32 *pl, float t_now, const float *targets,
                                   uint32_t *clamped)
{
    return qo_motion_set_target_state_f32(pl, t_now, targets, NULL, NULL, clamped);
}

qo_status qo_motion_set_joint_sync_f32(qo_motion_planner_f32 *pl, size_t i, qo_motion_sync sync)
{
    if (pl == NULL) return QO_E_NULL;
    if (pl->n == 0 || pl->joints == NULL) return QO_E_STATE;
    if (i >= pl->n) return QO_E_RANGE;
    if (!sync_valid((int)sync)) return QO_E_ARG;
    pl->joints[i].sync = (int)sync;
    return QO_OK;
}

qo_status qo_motion_set_velocity_f32(qo_motion_planner_f32 *pl, float t_now, const float *vel)
{
    size_t i;
    qo_status st;
    if (pl == NULL || vel == NULL) return QO_E_NULL;
    st = check_time(pl, t_now);
    if (st != QO_OK) return st;
    for (i = 0; i < pl->n; i++) {
        if (!isfinite(vel[i])) {
            capture(pl, t_now);
            plan_brake_safe(pl);
            return QO_E_NONFINITE;
        }
    }
    for (i = 0; i < pl->n; i++) {
        mlim m = qo_motion_mlim(&pl->joints[i].lim);
        if (vel[i] > m.vp || vel[i] < -m.vn) return QO_E_RANGE; /* refused: nothing changes */
    }
    capture(pl, t_now);
    for (i = 0; i < pl->n; i++) pl->joints[i].goal_v = vel[i];
    return plan_velocity_checked(pl);
}

qo_status qo_motion_set_limits_f32(qo_motion_planner_f32 *pl, float t_now, size_t i,
                                   const qo_motion_limits_f32 *limits)
{
    size_t k;
    qo_status st;
    int sc;
    if (pl == NULL || limits == NULL) return QO_E_NULL;
    st = check_time(pl, t_now);
    if (st != QO_OK) return st;
    if (i >= pl->n) return QO_E_RANGE;
    capture(pl, t_now);
    if (!limits_ok(limits)) {
        plan_brake_safe(pl);
        return QO_E_LIMIT;
    }
    pl->joints[i].lim = *limits;
    sc = pl->settings.profile == QO_MOTION_SCURVE;
    for (k = 0; k < pl->n; k++) {
        /* a target velocity (velocity interface, target state) beyond the new limits is clamped
         * into them, and a target acceleration they cannot hold is dropped */
        qo_motion_joint_f32 *jt = &pl->joints[k];
        mlim m = qo_motion_mlim(&jt->lim);
        jt->goal_v = fminf(fmaxf(jt->goal_v, -m.vn), m.vp);
        if (state_ok(jt, sc, jt->goal_v, jt->goal_a) != QO_OK) jt->goal_a = 0.0f;
    }
    if (pl->vel_mode) return plan_velocity_checked(pl);
    for (k = 0; k < pl->n; k++) {
        qo_motion_joint_f32 *jt = &pl->joints[k];
        if (jt->goal < jt->lim.pmin) jt->goal = jt->lim.pmin;
        if (jt->goal > jt->lim.pmax) jt->goal = jt->lim.pmax;
        if (!pos_in_range(jt->goal)) {
            plan_brake_safe(pl); /* a range end beyond the supported range */
            return QO_E_RANGE;
        }
    }
    return plan_goals_checked(pl);
}

qo_status qo_motion_brake_f32(qo_motion_planner_f32 *pl, float t_now)
{
    qo_status st;
    if (pl == NULL) return QO_E_NULL;
    st = check_time(pl, t_now);
    if (st != QO_OK) return st;
    capture(pl, t_now);
    plan_brake(pl);
    if (plan_ok(pl)) return QO_OK;
    plan_hold(pl);
    return QO_E_RANGE;
}

qo_status qo_motion_sample_f32(const qo_motion_planner_f32 *pl, float t, float *pos, float *vel, float *acc)
{
    size_t i;
    qo_status st = QO_OK;
    float tau;
    if (pl == NULL || pos == NULL) return QO_E_NULL;
    if (pl->n == 0 || pl->joints == NULL) return QO_E_STATE;
    if (!isfinite(t)) {
        st = QO_E_NONFINITE;
        tau = 0.0f;
    } else if (t < pl->t0) {
        st = QO_E_RANGE;
        tau = 0.0f;
    } else {
        tau = t - pl->t0;
    }
    for (i = 0; i < pl->n; i++) {
        mstate s = qo_motion_joint_state(&pl->joints[i], tau);
        if (!(isfinite(s.p) && isfinite(s.v) && isfinite(s.a))) {
            /* last line of defence (plans are checked, so not expected): the plan's final
             * position at rest */
            s.p = pl->joints[i].final;
            s.v = s.a = 0.0f;
            st = QO_E_RANGE;
        }
        pos[i] = s.p;
        if (vel) vel[i] = s.v;
        if (acc) acc[i] = s.a;
    }
    return st;
}

float qo_motion_duration_f32(const qo_motion_planner_f32 *pl)
{
    if (pl == NULL || pl->n == 0) return 0.0f;
    return pl->duration;
}

float qo_motion_end_time_f32(const qo_motion_planner_f32 *pl)
{
    float e;
    if (pl == NULL || pl->n == 0) return 0.0f;
    /* Rounded up so that sampling at the returned time is at rest (t - t0 >= duration). */
    e = pl->t0 + pl->duration;
    if (e - pl->t0 < pl->duration) e = nextafterf(e, INFINITY);
    return e;
}

int qo_motion_done_f32(const qo_motion_planner_f32 *pl, float t)
{
    if (pl == NULL || pl->n == 0) return 1;
    if (isnan(t)) return 0;
    return t - pl->t0 >= pl->duration;
}

qo_status qo_motion_shift_time_f32(qo_motion_planner_f32 *pl, float dt)
{
    if (pl == NULL) return QO_E_NULL;
    if (pl->n == 0 || pl->joints == NULL) return QO_E_STATE;
    if (!isfinite(dt)) return QO_E_NONFINITE;
    pl->t0 -= dt;
    return QO_OK;
}

qo_status qo_motion_set_timing_f32(qo_motion_planner_f32 *pl, float min_duration, float period)
{
    if (pl == NULL) return QO_E_NULL;
    if (pl->n == 0 || pl->joints == NULL) return QO_E_STATE;
    if (!(min_duration >= 0.0f && min_duration <= QO_MOTION_DURATION_MAX) ||
        !(period >= 0.0f && period <= QO_MOTION_DURATION_MAX) || (period > 0.0f && period < QO_MOTION_PERIOD_MIN))
        return QO_E_ARG;
    pl->min_duration = min_duration;
    pl->period = period;
    return QO_OK;
}

qo_motion_sync qo_motion_sync_used(const qo_motion_planner_f32 *pl)
{
    return pl ? pl->sync_used : QO_MOTION_SYNC_NONE;
}

