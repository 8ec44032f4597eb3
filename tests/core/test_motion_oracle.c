/*
 * qo_motion_*: the planner judged by an independent minimum-time reference
 * (tests/common/motion_ref.c, double precision, exhaustive search over switching times).
 *
 * Random joints (fixed seed; limits as in issue 11: vmax U[0.5,5], amax U[1,20],
 * jmax U[10,500], displacement U[-3,3], moving starts with |v0| <= vmax, |a0| <= amax and
 * |v0 + a0|a0|/(2 jmax)| <= vmax) planned in 7-joint groups in every sync mode (NONE, TIME,
 * PHASE, TIME_IF_NECESSARY). The oracle runs add asymmetric limits (vmin, amin, each with
 * probability 1/2) and moving target states (probability 1/2, through
 * qo_motion_set_target_state_f32). Each plan is checked for: a joint (NONE; TIME_IF_NECESSARY
 * with a target at rest) or plan (TIME, and PHASE where it fell back to TIME; the moving-target
 * joints of TIME_IF_NECESSARY) more than 0.1 % slower than the reference, or more than 0.1 %
 * faster (the reference would be missing a profile); a plan that reports PHASE off the
 * straight line at a dense sample, or more than 0.1 % from the reference's minimum for the
 * line's scalar profile, or a feasible line that fell back to TIME (PHASE groups are drawn with
 * states proportional to the displacements: phase_line); any limit exceeded by more than 1e-5 relative in the phase coefficients
 * (jerk, acceleration at phase ends, velocity at phase ends and interior extrema) and in dense
 * samples, including the motion after the end; the end state equal to the target state;
 * continuity across a re-plan mid-way (to new target states). Two more groups: test_oracle_wide
 * (limits over the whole accepted range, asymmetric up to the accepted ratio) and
 * test_oracle_stress (asymmetric limits and moving target states with nonzero accelerations on
 * every joint, a quarter at the edge of what the limits hold).
 *
 * Also unit checks of asymmetric limits, full target states (refused ones leave the planner
 * bit-for-bit unchanged; the motion after the end against its closed form, float32 and Q16.16),
 * per-joint synchronisation and TIME_IF_NECESSARY against the reference's minimum times.
 *
 * The count is QO_MOTION_ORACLE_JOINTS (default 10,500 per sync mode); `make check-motion` and
 * `make check-motion-long` build this program with larger counts.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "qorient/motion.h"
#include "qorient/motion_fx.h"
#include "common/motion_ref.h"
#include "common/ref.h"

#define NJ 7
#ifndef QO_MOTION_ORACLE_JOINTS
#define QO_MOTION_ORACLE_JOINTS 10500
#endif
/* The other random loops scale with the count: n groups at the default 10,500, at least 1 (the
 * emulated Cortex-M targets run a small sample: tests/qemu/cortexm.mk). */
/* in long long: n * 10,000,000 (make check-motion-long) does not fit an int */
#define ORACLE_GROUPS(n) \
    ((long long)(n) * QO_MOTION_ORACLE_JOINTS / 10500 > 0 \
         ? (int)((long long)(n) * QO_MOTION_ORACLE_JOINTS / 10500) : 1)
#define RELTIME 1e-3 /* 0.1 % */
#define RELLIM 1e-5

static mref_lim ref_lim_of(const qo_motion_limits_f32 *l)
{
    mref_lim r;
    r.vmax = l->vmax;
    r.vmin = l->vmin != 0.0f ? (double)l->vmin : -(double)l->vmax;
    r.amax = l->amax;
    r.amin = l->amin != 0.0f ? (double)l->amin : -(double)l->amax;
    r.jmax = l->jmax;
    return r;
}

/* Puts joint i into the moving state (p, v, a) at time 0: a synthetic plan of one long phase. */
static void put_state(qo_motion_planner_f32 *pl, size_t i, float p, float v, float a)
{
    qo_motion_joint_f32 *jt = &pl->joints[i];
    qo_motion_phase_f32 ph = { 0.0f, 1e6f, 0.0f, 0.0f, 0.0f, 0.0f };
    ph.p = p;
    ph.v = v;
    ph.a = a;
    jt->ph[0] = ph;
    jt->nph = 1;
    jt->duration = ph.d;
    jt->final = p;
}

/* |x| over its bound on x's side: velocity (acc 0) or acceleration (acc 1). */
static double vratio(const mref_lim *r, double x, int acc)
{
    double hi = acc ? r->amax : r->vmax, lo = acc ? r->amin : r->vmin;
    return x >= 0.0 ? x / hi : x / lo;
}

/* Worst relative limit excess of joint i's plan: phase coefficients (jerk; acceleration at
 * phase ends; velocity at phase ends and where the acceleration crosses zero) and `ns` dense
 * samples of the planner. Returns the excess ratio - 1 (<= 0 when within the limits). */
static double limit_excess(const qo_motion_planner_f32 *pl, size_t i, int ns)
{
    const qo_motion_joint_f32 *jt = &pl->joints[i];
    mref_lim r = ref_lim_of(&jt->lim);
    double J = jt->lim.jmax, w = 0.0;
    unsigned k;
    int s;
    for (k = 0; k < jt->nph; k++) {
        const qo_motion_phase_f32 *ph = &jt->ph[k];
        double d = ph->d, a1 = ph->a + d * ph->j, v1 = ph->v + d * (ph->a + 0.5 * d * ph->j);
        w = fmax(w, fabs(ph->j) / J);
        w = fmax(w, fmax(vratio(&r, ph->a, 1), vratio(&r, a1, 1)));
        w = fmax(w, fmax(vratio(&r, ph->v, 0), vratio(&r, v1, 0)));
        if (ph->j != 0.0f) {
            double tz = -(double)ph->a / ph->j;
            if (tz > 0.0 && tz < d) w = fmax(w, vratio(&r, ph->v + tz * (ph->a + 0.5 * tz * ph->j), 0));
        }
    }
    /* dense samples of the plan and of the motion after its end (target states: the
     * acceleration's ramp to zero, then constant velocity) */
    for (s = 0; s <= ns + ns / 4; s++) {
        float pos[NJ], vel[NJ], acc[NJ];
        float t = pl->t0 + (pl->duration + 0.25f) * (float)s / (float)ns;
        qo_motion_sample_f32(pl, t, pos, vel, acc);
        w = fmax(w, vratio(&r, vel[i], 0));
        w = fmax(w, vratio(&r, acc[i], 1));
    }
    return w - 1.0;
}

typedef struct jcase {
    qo_motion_limits_f32 lim;
    float p0, v0, a0, target, vf, af; /* vf, af: target velocity and acceleration */
} jcase;

/* 1 while a test feeds a check plans it must reject (test_line_checks_fail): no printing. */
static int g_quiet;

static void print_case(const char *what, int cs, size_t i, const jcase *c, double got, double ref)
{
    if (g_quiet) return;
    print_error("%s case %d joint %zu: got %.9g ref %.9g | vmax %.9g amax %.9g jmax %.9g vmin %.9g amin %.9g "
                "p0 %.9g v0 %.9g a0 %.9g target %.9g vf %.9g af %.9g\n",
                what, cs, i, got, ref, (double)c->lim.vmax, (double)c->lim.amax, (double)c->lim.jmax,
                (double)c->lim.vmin, (double)c->lim.amin, (double)c->p0, (double)c->v0, (double)c->a0,
                (double)c->target, (double)c->vf, (double)c->af);
}

/* Plans n joints from their cases with `sync`; returns the planner's status. */
static qo_status plan_cases(qo_motion_planner_f32 *pl, qo_motion_joint_f32 *jts, const jcase *c, size_t n,
                            qo_motion_sync sync)
{
    qo_motion_settings_f32 st = { QO_MOTION_SCURVE, QO_MOTION_SYNC_TIME };
    qo_motion_limits_f32 l[NJ];
    float p[NJ], tg[NJ], vf[NJ], af[NJ];
    size_t i;
    st.sync = sync;
    memset(l, 0, sizeof l);
    memset(p, 0, sizeof p);
    memset(tg, 0, sizeof tg);
    memset(vf, 0, sizeof vf);
    memset(af, 0, sizeof af);
    for (i = 0; i < n; i++) {
        l[i] = c[i].lim;
        p[i] = c[i].p0;
        tg[i] = c[i].target;
        vf[i] = c[i].vf;
        af[i] = c[i].af;
    }
    assert_int_equal(qo_motion_init_f32(pl, jts, n, l, p, 0.0f, &st), QO_OK);
    for (i = 0; i < n; i++) put_state(pl, i, c[i].p0, c[i].v0, c[i].a0);
    return qo_motion_set_target_state_f32(pl, 0.0f, tg, vf, af, NULL);
}

static double ref_time(const jcase *c)
{
    mref_lim r = ref_lim_of(&c->lim);
    return mref_min_time(&r, c->p0, c->v0, c->a0, c->target, c->vf, c->af);
}

/* A random state (v, a) within r: a start from which the limits can be kept (v + a|a|/(2J)
 * within the velocity bounds) or, with end = 1, a target state the planner accepts (v -+
 * a|a|/(2J) both within them). */
static void rand_state(ref_rng *g, const mref_lim *r, int end, float *v, float *a)
{
    for (;;) {
        double vv = (double)(float)ref_rng_range(g, r->vmin, r->vmax), aa = (double)(float)ref_rng_range(g, r->amin, r->amax);
        double h = aa * fabs(aa) / (2.0 * r->jmax);
        if (vv + h > r->vmax || vv + h < r->vmin) continue;
        if (end && (vv - h > r->vmax || vv - h < r->vmin)) continue;
        *v = (float)vv;
        *a = (float)aa;
        return;
    }
}

/* With v = 0, a target acceleration a is holdable if a|a|/(2J) stays within both velocity bounds:
 * scales a down until it does. */
static void rand_state_zero_v(const mref_lim *r, float *a)
{
    while (fabs((double)*a * fabs(*a) / (2.0 * r->jmax)) > fmin(r->vmax, -r->vmin)) *a *= 0.5f;
}

/* A target state at an edge of what the planner accepts: the acceleration at a bound (amin or
 * amax) with the velocity at the end of its holdable range, or the velocity at a bound with
 * the largest holdable acceleration (v -+ a|a|/(2J) within [vmin, vmax]), in float32. */
static void edge_state(ref_rng *g, const mref_lim *r, float *v, float *a)
{
    double J = r->jmax, u = ref_rng_unit(g), aa, h, vv;
    if (u < 0.5) {
        aa = u < 0.25 ? r->amax : r->amin;
        h = fabs(aa * fabs(aa) / (2.0 * J));
        /* shrink until some velocity holds it */
        while (r->vmax - h < r->vmin + h) {
            aa *= 0.5;
            h *= 0.25;
        }
        vv = ref_rng_unit(g) < 0.5 ? r->vmax - h : r->vmin + h;
    } else {
        vv = u < 0.75 ? r->vmax : r->vmin;
        aa = 0.0;
    }
    *v = (float)vv;
    *a = (float)aa;
    /* float32 rounding may have put the pair a hair outside what the planner accepts (its
     * check is in float32, motion.c state_ok) or outside what is reachable exactly (the
     * reference's check, in double): pull it in until both hold */
    for (;;) {
        float hf = *a * fabsf(*a) / (2.0f * (float)J), vp = (float)r->vmax, vn = (float)r->vmin;
        double hd = (double)*a * fabs(*a) / (2.0 * J);
        if (!(*v + hf > vp || *v + hf < vn || *v - hf > vp || *v - hf < vn || *v > vp || *v < vn ||
              *a > (float)r->amax || *a < (float)r->amin || *v + hd > r->vmax || *v + hd < r->vmin ||
              *v - hd > r->vmax || *v - hd < r->vmin))
            break;
        *v = nextafterf(*v, 0.0f);
        *a = nextafterf(*a, 0.0f);
    }
}

/* The stress group (test_oracle_stress): every joint with asymmetric velocity and acceleration
 * limits (ratios up to 10) and a moving target state with a nonzero acceleration, a quarter of
 * them at an edge of what the limits allow (issue 11: the missing shapes of check-motion case
 * 5781 were all of this kind). */
static int g_stress;

/* A random joint as in issue 11 (moving start with probability 3/4). With `mix`, also
 * asymmetric limits (vmin U[-5,-0.5], amin U[-20,-1], each with probability 1/2) and a moving
 * target state (probability 1/2; of those a third with a = 0, a sixth with v = 0). */
/* The wide group (test_oracle_wide): limits log-uniform over the whole range the planner
 * accepts, [WIDE_LO, WIDE_HI] = [QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX], half of the joints
 * with vmin and half with amin a factor log-uniform in [1/WIDE_RATIO, WIDE_RATIO] =
 * QO_MOTION_LIMIT_RATIO from -vmax / -amax, and random states drawn from state_box, so that
 * positions stay meaningful in float32. Wider (compile with -DWIDE_LO=1e-6 -DWIDE_HI=1e12, or
 * -DWIDE_RATIO=1000) the planner was seen up to 3.1x slower than the reference, and limits
 * exceeded by up to 6e-5 relative: the planner refuses those limits (motion.h). */
static int g_wide;
#ifndef WIDE_LO
#define WIDE_LO ((double)QO_MOTION_LIMIT_MIN)
#endif
#ifndef WIDE_HI
#define WIDE_HI ((double)QO_MOTION_LIMIT_MAX)
#endif
#ifndef WIDE_RATIO
#define WIDE_RATIO ((double)QO_MOTION_LIMIT_RATIO)
#endif
#define WIDE_REACH 4.0 /* largest stopping distance of a random state */

static double log_uniform(ref_rng *g, double lo, double hi)
{
    return exp(ref_rng_range(g, log(lo), log(hi)));
}

/* A negative limit a factor log-uniform in [1/WIDE_RATIO, WIDE_RATIO] from -pos, within
 * [WIDE_LO, WIDE_HI], pulled toward -pos by float32 ulps where rounding of the factor put it
 * outside the ratio the planner accepts (its float32 check, motion.c neg_limit_ok). */
static float wide_neg(ref_rng *g, float pos)
{
    float x = (float)fmin(fmax(pos * log_uniform(g, 1.0 / WIDE_RATIO, WIDE_RATIO), WIDE_LO), WIDE_HI);
    const float R = (float)WIDE_RATIO;
    while (!(x <= R * pos && pos <= R * x)) x = nextafterf(x, pos);
    return -x;
}

/* Where random start and target states are drawn: the limits, or in the wide group the part of
 * them from which the joint can stop within about WIDE_REACH (a start at 1e9 units/s would fly
 * 1e18 units before braking: float32 positions would say nothing about the plan). */
static mref_lim state_box(const qo_motion_limits_f32 *l)
{
    mref_lim r = ref_lim_of(l);
    if (g_wide) {
        double J = r.jmax, vb = fmin(sqrt(WIDE_REACH * fmin(r.amax, -r.amin)), pow(WIDE_REACH * sqrt(J), 2.0 / 3.0));
        double ab = sqrt(J * vb);
        r.vmax = fmin(r.vmax, vb);
        r.vmin = fmax(r.vmin, -vb);
        r.amax = fmin(r.amax, ab);
        r.amin = fmax(r.amin, -ab);
    }
    return r;
}

static void rand_case_mix(ref_rng *g, jcase *c, int mix)
{
    mref_lim r;
    c->lim = qo_motion_limits_default;
    if (g_wide) {
        c->lim.vmax = (float)log_uniform(g, WIDE_LO, WIDE_HI);
        c->lim.amax = (float)log_uniform(g, WIDE_LO, WIDE_HI);
        c->lim.jmax = (float)log_uniform(g, WIDE_LO, WIDE_HI);
        /* asymmetric on half the joints, each limit, kept within the range */
        if (ref_rng_unit(g) < 0.5) c->lim.vmin = wide_neg(g, c->lim.vmax);
        if (ref_rng_unit(g) < 0.5) c->lim.amin = wide_neg(g, c->lim.amax);
    } else {
        c->lim.vmax = (float)ref_rng_range(g, 0.5, 5.0);
        c->lim.amax = (float)ref_rng_range(g, 1.0, 20.0);
        c->lim.jmax = (float)ref_rng_range(g, 10.0, 500.0);
        if (mix && (g_stress || ref_rng_unit(g) < 0.5)) c->lim.vmin = (float)-ref_rng_range(g, 0.5, 5.0);
        if (mix && (g_stress || ref_rng_unit(g) < 0.5)) c->lim.amin = (float)-ref_rng_range(g, 1.0, 20.0);
    }
    r = state_box(&c->lim);
    c->p0 = (float)ref_rng_range(g, -2.0, 2.0);
    c->v0 = c->a0 = c->vf = c->af = 0.0f;
    if (ref_rng_unit(g) < 0.75) {
        if (mix) {
            rand_state(g, &r, 0, &c->v0, &c->a0);
        } else {
            for (;;) {
                double v = ref_rng_range(g, -1.0, 1.0) * c->lim.vmax, a = ref_rng_range(g, -1.0, 1.0) * c->lim.amax;
                if (fabs(v + a * fabs(a) / (2.0 * c->lim.jmax)) <= c->lim.vmax) {
                    c->v0 = (float)v;
                    c->a0 = (float)a;
                    break;
                }
            }
        }
    }
    c->target = (float)(c->p0 + ref_rng_range(g, -3.0, 3.0));
    if (g_stress) {
        rand_state(g, &r, 1, &c->vf, &c->af);
        if (ref_rng_unit(g) < 0.25) edge_state(g, &r, &c->vf, &c->af);
    } else if (mix && ref_rng_unit(g) < 0.5) {
        double u = ref_rng_unit(g);
        rand_state(g, &r, 1, &c->vf, &c->af);
        if (u < 1.0 / 3.0) c->af = 0.0f;
        else if (u < 0.5) c->vf = 0.0f;
        if (c->vf == 0.0f) rand_state_zero_v(&r, &c->af);
    }
}

static void rand_case(ref_rng *g, jcase *c)
{
    rand_case_mix(g, c, 0);
}

/* PHASE (test_oracle_phase, the PHASE part of test_oracle_wide). motion.h's straight line
 * p_i = p0_i + d_i s(t) exists only when every joint's start and target states are proportional
 * to its displacement d_i, which random moving states never are: drawn as they are, every PHASE
 * plan would fall back to TIME. So a quarter of the PHASE groups keep their random states (the
 * fallback, judged as TIME), a quarter go rest to rest, and half start from (v0, a0) =
 * (kv, ka) d_i, half of those also to the target state (kvf, kaf) d_i, with (kv, ka) and
 * (kvf, kaf) drawn within the line's own limits (line_lim). A plan that reports PHASE is then
 * checked for being that line: every joint on it at every dense sample (position, velocity and
 * acceleration the d_i-scaled copy of one profile), one duration, and that duration the
 * reference's minimum for the scalar profile s: 0 -> 1 within line_lim (never below the
 * slowest joint's own minimum). */
#define LINE_SAMPLES 256

/* Counts of the PHASE groups of one run (printed by run_mode and test_oracle_wide). */
static struct {
    int plans, used, fell, fell_line, slower;
    double worst; /* largest T / tmax of a line */
} g_line;

/* The joint's displacement as the planner takes it (float32 target - p0). */
static double case_d(const jcase *c)
{
    return (double)(c->target - c->p0);
}

/* The straight line's scalar limits: s' d_i within [vmin_i, vmax_i] (the bounds swap for a
 * negative d_i), the same for the acceleration, and the jerk times |d_i| within jmax_i; from
 * the joints' limits (box 0) or from the part of them random states are drawn from (box 1,
 * state_box). 0 if no joint moves. */
static int line_lim(const jcase *c, int box, mref_lim *out)
{
    double vp = INFINITY, vn = INFINITY, ap = INFINITY, an = INFINITY, j = INFINITY;
    int any = 0;
    size_t i;
    for (i = 0; i < NJ; i++) {
        double d = case_d(&c[i]), ad = fabs(d);
        mref_lim r = box ? state_box(&c[i].lim) : ref_lim_of(&c[i].lim);
        if (d == 0.0) continue;
        any = 1;
        vp = fmin(vp, (d > 0.0 ? r.vmax : -r.vmin) / ad);
        vn = fmin(vn, (d > 0.0 ? -r.vmin : r.vmax) / ad);
        ap = fmin(ap, (d > 0.0 ? r.amax : -r.amin) / ad);
        an = fmin(an, (d > 0.0 ? -r.amin : r.amax) / ad);
        j = fmin(j, r.jmax / ad);
    }
    out->vmax = vp;
    out->vmin = -vn;
    out->amax = ap;
    out->amin = -an;
    out->jmax = j;
    return any;
}

/* Rewrites a PHASE group's states as the comment above says; returns 1 for a line group
 * (rest to rest or proportional), 0 for one left random. */
static int phase_line(ref_rng *g, jcase *c)
{
    double u = ref_rng_unit(g), kv = 0.0, ka = 0.0, kvf = 0.0, kaf = 0.0;
    mref_lim b;
    size_t i;
    if (u < 0.25) return 0;
    if (u >= 0.5 && line_lim(c, 1, &b)) {
        float v, a;
        /* 1e-6 inside: the float32 products (kv d_i) stay within each joint's limits */
        b.vmax *= 1.0 - 1e-6;
        b.vmin *= 1.0 - 1e-6;
        b.amax *= 1.0 - 1e-6;
        b.amin *= 1.0 - 1e-6;
        b.jmax *= 1.0 - 1e-6;
        rand_state(g, &b, 0, &v, &a);
        kv = v;
        ka = a;
        if (ref_rng_unit(g) < 0.5) {
            rand_state(g, &b, 1, &v, &a);
            kvf = v;
            kaf = a;
        }
    }
    for (i = 0; i < NJ; i++) {
        double d = case_d(&c[i]);
        c[i].v0 = (float)(kv * d);
        c[i].a0 = (float)(ka * d);
        c[i].vf = (float)(kvf * d);
        c[i].af = (float)(kaf * d);
    }
    return 1;
}

/* Largest |velocity| and |acceleration| of joint i's phases (ends, and the velocity's interior
 * extremum): the scale of its float32 rounding. */
static void joint_peaks(const qo_motion_joint_f32 *jt, double *vpk, double *apk)
{
    unsigned k;
    *vpk = *apk = 0.0;
    for (k = 0; k < jt->nph; k++) {
        const qo_motion_phase_f32 *ph = &jt->ph[k];
        double d = ph->d, tz = ph->j != 0.0f ? -(double)ph->a / ph->j : -1.0;
        *vpk = fmax(*vpk, fmax(fabs(ph->v), fabs(ph->v + d * (ph->a + 0.5 * d * ph->j))));
        if (tz > 0.0 && tz < d) *vpk = fmax(*vpk, fabs(ph->v + tz * (ph->a + 0.5 * tz * ph->j)));
        *apk = fmax(*apk, fmax(fabs(ph->a), fabs(ph->a + d * ph->j)));
    }
}

/* 1 if a line group's straight line is one the planner must take (motion.h): its scalar limits
 * within the accepted range (by 0.1 %: the planner's are float32 quotients) and the reference
 * finds the scalar profile. A line group that falls back to TIME although it is feasible is a
 * failure (a planner that never took the line would pass every other check). */
static int line_feasible(const jcase *c)
{
    mref_lim sl;
    const double lo = (double)QO_MOTION_LIMIT_MIN * 1.001, hi = (double)QO_MOTION_LIMIT_MAX / 1.001;
    size_t i, r = 0;
    double dr;
    for (i = 0; i < NJ; i++)
        if (fabs(case_d(&c[i])) > fabs(case_d(&c[r]))) r = i;
    dr = case_d(&c[r]);
    if (!line_lim(c, 0, &sl) || sl.vmax < lo || sl.vmax > hi || -sl.vmin < lo || -sl.vmin > hi || sl.amax < lo ||
        sl.amax > hi || -sl.amin < lo || -sl.amin > hi || sl.jmax < lo || sl.jmax > hi)
        return 0;
    return mref_min_time(&sl, 0.0, c[r].v0 / dr, c[r].a0 / dr, 1.0, c[r].vf / dr, c[r].af / dr) >= 0.0;
}

/* A plan that reports PHASE: every joint on the straight line of the joint r with the largest
 * |d| (position, velocity, acceleration at LINE_SAMPLES + 1 dense samples: the d_i / d_r-scaled
 * copy of joint r's, to 1e-5 of the joint's own scale), one duration, and that duration the
 * reference's minimum of the scalar line (0.1 %), not below the slowest joint's own minimum
 * tmax. Returns the number of failures (each printed). */
static int check_line(const qo_motion_planner_f32 *pl, int cs, const jcase *c, double tmax)
{
    const qo_motion_joint_f32 *jts = pl->joints;
    double d[NJ], vpk[NJ], apk[NJ], T = pl->duration, tl, dr;
    mref_lim sl;
    size_t i, r = 0;
    int s, bad = 0;
    for (i = 0; i < NJ; i++) {
        d[i] = case_d(&c[i]);
        if (fabs(d[i]) > fabs(d[r])) r = i;
        joint_peaks(&jts[i], &vpk[i], &apk[i]);
    }
    dr = d[r];
    for (i = 0; i < NJ; i++)
        if (d[i] != 0.0 && jts[i].duration != jts[r].duration) {
            print_case("PHASE: joint duration not the line's", cs, i, &c[i], jts[i].duration, jts[r].duration);
            bad++;
        }
    if (!line_lim(c, 0, &sl)) {
        if (!g_quiet) print_error("case %d: PHASE used with no joint moving\n", cs);
        return bad + 1;
    }
    tl = mref_min_time(&sl, 0.0, c[r].v0 / dr, c[r].a0 / dr, 1.0, c[r].vf / dr, c[r].af / dr);
    if (tl < 0.0 || fabs(T - tl) > RELTIME * tl + 1e-6) {
        print_case("PHASE: duration vs the line's reference", cs, r, &c[r], T, tl);
        bad++;
    }
    if (T < tmax * (1.0 - RELTIME) - 1e-6) {
        if (!g_quiet) print_error("case %d: PHASE T %.9g below the slowest joint's minimum %.9g\n", cs, T, tmax);
        bad++;
    }
    if (T > tmax * (1.0 + RELTIME) + 1e-6) g_line.slower++;
    if (tmax > 0.0) g_line.worst = fmax(g_line.worst, T / tmax);
    for (s = 0; s <= LINE_SAMPLES; s++) {
        float pos[NJ], vel[NJ], acc[NJ];
        double sp, sv, sa;
        qo_motion_sample_f32(pl, pl->t0 + (float)(T * s / LINE_SAMPLES), pos, vel, acc);
        sp = ((double)pos[r] - c[r].p0) / dr;
        sv = vel[r] / dr;
        sa = acc[r] / dr;
        for (i = 0; i < NJ; i++) {
            double ep = fabs(pos[i] - (c[i].p0 + d[i] * sp)), ev = fabs(vel[i] - d[i] * sv), ea = fabs(acc[i] - d[i] * sa);
            if (ep > 1e-5 * (fabs(c[i].p0) + fabs(d[i])) || ev > 1e-5 * vpk[i] || ea > 1e-5 * apk[i]) {
                if (!g_quiet)
                    print_error("case %d joint %zu: PHASE off the line at t %g: p %.9g v %.9g a %.9g, line %.9g %.9g %.9g\n",
                            cs, i, T * s / LINE_SAMPLES, (double)pos[i], (double)vel[i], (double)acc[i],
                            c[i].p0 + d[i] * sp, d[i] * sv, d[i] * sa);
                return bad + 1;
            }
        }
    }
    return bad;
}

/* No position jump: on dense samples |p(t + dt) - p(t)| <= 1.05 max|v| dt + 1e-5 (1 + |p|), max|v|
 * over the samples (the plan's true velocities; not the limit, which may be 1e9). A plan that
 * loses its target and snaps to it (issue 11, vmax 1e8) moves far more than its velocity allows.
 * Returns the number of joints with a jump (each printed). */
#define CONT_SAMPLES 512
static int check_continuity(const qo_motion_planner_f32 *pl, int cs, const jcase *c)
{
    size_t i;
    int s, bad = 0;
    for (i = 0; i < pl->n; i++) {
        /* over the joint's own plan and as long again after it (the motion after the end); two
         * passes rather than a stored copy (small stacks: tests/qemu/cortexm.mk) */
        const qo_motion_joint_f32 *jt = &pl->joints[i];
        double vm = 0.0, dt = 2.0 * jt->duration / CONT_SAMPLES + 1e-6, prev = 0.0;
        float pos[NJ], v[NJ], a[NJ];
        unsigned k;
        /* max|v| of the phases (ends and interior extrema; a narrow peak falls between samples) */
        for (k = 0; k < jt->nph; k++) {
            const qo_motion_phase_f32 *ph = &jt->ph[k];
            double d = ph->d, tz = ph->j != 0.0f ? -(double)ph->a / ph->j : -1.0;
            vm = fmax(vm, fmax(fabs(ph->v), fabs(ph->v + d * (ph->a + 0.5 * d * ph->j))));
            if (tz > 0.0 && tz < d) vm = fmax(vm, fabs(ph->v + tz * (ph->a + 0.5 * tz * ph->j)));
        }
        for (s = 0; s <= CONT_SAMPLES; s++) {
            qo_motion_sample_f32(pl, pl->t0 + (float)(dt * s), pos, v, a);
            vm = fmax(vm, fabs(v[i]));
        }
        for (s = 0; s <= CONT_SAMPLES; s++) {
            qo_motion_sample_f32(pl, pl->t0 + (float)(dt * s), pos, v, a);
            if (s > 0 && fabs(pos[i] - prev) > 1.05 * vm * dt + 1e-5 * (1.0 + fabs(prev))) {
                print_case("position jump", cs, i, &c[i], fabs(pos[i] - prev), vm * dt);
                bad++;
                break;
            }
            prev = pos[i];
        }
    }
    return bad;
}

/* One 7-joint plan of random cases in mode `sync`, checked as the file header says.
 * Returns the number of failures (each printed). */
static int check_group(ref_rng *g, int cs, qo_motion_sync sync, double *tref_out)
{
    qo_motion_planner_f32 pl;
    qo_motion_joint_f32 jts[NJ];
    jcase c[NJ];
    double tref[NJ], tmax = 0.0, T;
    float pos[NJ], vel[NJ], acc[NJ], pos2[NJ], vel2[NJ], acc2[NJ], tg[NJ];
    size_t i;
    int bad = 0, line = 0, timed;
    for (i = 0; i < NJ; i++) rand_case_mix(g, &c[i], 1);
    if (sync == QO_MOTION_SYNC_PHASE) line = phase_line(g, c);
    for (i = 0; i < NJ; i++) {
        tref[i] = ref_time(&c[i]);
        if (tref[i] < 0.0) {
            print_case("reference found no profile", cs, i, &c[i], 0.0, tref[i]);
            bad++;
        }
        /* TIME_IF_NECESSARY: only the joints with a moving target share the duration */
        if (sync != QO_MOTION_SYNC_TIME_IF_NECESSARY || c[i].vf != 0.0f || c[i].af != 0.0f) tmax = fmax(tmax, tref[i]);
    }
    if (plan_cases(&pl, jts, c, NJ, sync) != QO_OK) {
        print_error("case %d: plan refused\n", cs);
        return bad + 1;
    }
    T = pl.duration;
    /* PHASE: the straight line where the plan says so; else the TIME fallback, judged as TIME */
    timed = sync == QO_MOTION_SYNC_TIME || (sync == QO_MOTION_SYNC_PHASE && pl.sync_used != QO_MOTION_SYNC_PHASE);
    if (sync == QO_MOTION_SYNC_PHASE) {
        g_line.plans++;
        if (pl.sync_used == QO_MOTION_SYNC_PHASE) {
            g_line.used++;
            bad += check_line(&pl, cs, c, tmax);
        } else {
            g_line.fell++;
            g_line.fell_line += line;
            if (line && line_feasible(c)) {
                print_error("case %d: PHASE fell back to TIME on a feasible straight line\n", cs);
                bad++;
            }
        }
    }
    for (i = 0; i < NJ; i++) {
        double e = limit_excess(&pl, i, 64);
        if (e > RELLIM) {
            print_case("limit exceeded", cs, i, &c[i], e, 0.0);
            bad++;
        }
        if (sync == QO_MOTION_SYNC_NONE ||
            (sync == QO_MOTION_SYNC_TIME_IF_NECESSARY && c[i].vf == 0.0f && c[i].af == 0.0f)) {
            double t = jts[i].duration;
            if (t > tref[i] * (1.0 + RELTIME) + 1e-6 || t < tref[i] * (1.0 - RELTIME) - 1e-6) {
                print_case("joint time vs reference", cs, i, &c[i], t, tref[i]);
                bad++;
            }
        } else if ((timed || sync == QO_MOTION_SYNC_TIME_IF_NECESSARY) && !(pl.unsynced >> i & 1u) && jts[i].nph > 0 &&
                   fabs(jts[i].duration - tmax) > RELTIME * tmax + 1e-6) {
            print_case("joint not given the common duration", cs, i, &c[i], jts[i].duration, tmax);
            bad++;
        }
        {
            /* the end state is the target state */
            float te = pl.t0 + jts[i].duration;
            qo_motion_sample_f32(&pl, te, pos, vel, acc);
            if (fabs(pos[i] - c[i].target) > 1e-5 * (1.0 + fabs(c[i].target)) ||
                fabs(vel[i] - c[i].vf) > 1e-4 * c[i].lim.vmax || fabs(acc[i] - c[i].af) > 1e-4 * c[i].lim.amax) {
                print_error("case %d joint %zu: end state p %g v %g a %g, target %g %g %g\n", cs, i, (double)pos[i],
                            (double)vel[i], (double)acc[i], (double)c[i].target, (double)c[i].vf, (double)c[i].af);
                bad++;
            }
        }
    }
    bad += check_continuity(&pl, cs, c);
    /* TIME: the plan takes the slowest joint's minimum time; TIME_IF_NECESSARY: at least the
     * slowest moving-target joint's (a joint with a target at rest may take longer alone) */
    if ((timed && (T > tmax * (1.0 + RELTIME) + 1e-6 || T < tmax * (1.0 - RELTIME) - 1e-6)) ||
        (sync == QO_MOTION_SYNC_TIME_IF_NECESSARY && T < tmax * (1.0 - RELTIME) - 1e-6)) {
        print_error("time sync case %d: T %.9g ref %.9g\n", cs, T, tmax);
        bad++;
    }
    /* Re-plan mid-way to new targets: the state is continuous across the re-plan. */
    {
        float tm = 0.5f * T;
        qo_motion_sample_f32(&pl, tm, pos, vel, acc);
        float vf[NJ], af[NJ];
        for (i = 0; i < NJ; i++) {
            mref_lim r = state_box(&c[i].lim);
            tg[i] = (float)(c[i].target + ref_rng_range(g, -1.0, 1.0));
            vf[i] = af[i] = 0.0f;
            if (ref_rng_unit(g) < 0.5) rand_state(g, &r, 1, &vf[i], &af[i]);
        }
        if (qo_motion_set_target_state_f32(&pl, tm, tg, vf, af, NULL) != QO_OK) {
            print_error("case %d: re-plan refused\n", cs);
            return bad + 1;
        }
        qo_motion_sample_f32(&pl, tm, pos2, vel2, acc2);
        for (i = 0; i < NJ; i++) {
            if (fabs(pos2[i] - pos[i]) > 1e-6 * (1.0 + fabs(pos[i])) || fabs(vel2[i] - vel[i]) > 1e-6 * c[i].lim.vmax ||
                fabs(acc2[i] - acc[i]) > 1e-6 * c[i].lim.amax) {
                print_error("case %d joint %zu: re-plan jump p %g->%g v %g->%g a %g->%g\n", cs, i, (double)pos[i],
                            (double)pos2[i], (double)vel[i], (double)vel2[i], (double)acc[i], (double)acc2[i]);
                bad++;
            }
            if (limit_excess(&pl, i, 32) > RELLIM) {
                print_error("case %d joint %zu: re-plan exceeds a limit\n", cs, i);
                bad++;
            }
        }
    }
    if (tref_out) *tref_out = tmax;
    return bad;
}

/* Draws what check_group draws for one group, checking nothing (to reach a case by index). */
static void skip_group(ref_rng *g, qo_motion_sync sync)
{
    jcase c[NJ];
    float v, a;
    size_t i;
    for (i = 0; i < NJ; i++) rand_case_mix(g, &c[i], 1);
    if (sync == QO_MOTION_SYNC_PHASE) (void)phase_line(g, c);
    for (i = 0; i < NJ; i++) {
        mref_lim r = state_box(&c[i].lim);
        (void)ref_rng_range(g, -1.0, 1.0);
        if (ref_rng_unit(g) < 0.5) rand_state(g, &r, 1, &v, &a);
    }
}

/* QO_MOTION_ORACLE_FIRST=n QO_MOTION_ORACLE_NUM=m run groups n..n+m-1 of each mode only (the
 * same cases as a full run: e.g. one failure of check-motion by its case number).
 * QO_MOTION_ORACLE_SYNC=s runs only sync mode s of test_oracle_wide and test_oracle_stress (the
 * other modes' cases drawn and skipped, so the cases are those of a full run). */
static int env_int(const char *name, int dflt)
{
    const char *e = getenv(name);
    return e ? atoi(e) : dflt;
}

/* 0 if QO_MOTION_ORACLE_SYNC names a mode other than `sync`. */
static int mode_wanted(qo_motion_sync sync)
{
    int s = env_int("QO_MOTION_ORACLE_SYNC", -1);
    return s < 0 || s == (int)sync;
}

/* The PHASE counts of g_line (see phase_line), and what each PHASE plan was checked with. */
static void print_line_counts(const char *what)
{
    print_message("%sPHASE: %d plans, %d on the straight line (%d of them slower than TIME's minimum, at most "
                  "%.3gx), %d fell back to TIME (%d of them line cases); per joint %d dense samples for the limits, "
                  "%d for continuity, %d on the line\n",
                  what, g_line.plans, g_line.used, g_line.slower, g_line.worst, g_line.fell, g_line.fell_line, 64 + 64 / 4 + 1,
                  2 * (CONT_SAMPLES + 1), LINE_SAMPLES + 1);
}

static void run_mode(qo_motion_sync sync, uint64_t seed)
{
    ref_rng g;
    int cs, bad = 0, groups = (QO_MOTION_ORACLE_JOINTS + NJ - 1) / NJ, first = env_int("QO_MOTION_ORACLE_FIRST", 0);
    int num = env_int("QO_MOTION_ORACLE_NUM", groups);
    g.s = seed;
    memset(&g_line, 0, sizeof g_line);
    for (cs = 0; cs < first && cs < groups; cs++) skip_group(&g, sync);
    if (num < groups - cs) groups = cs + num;
    for (; cs < groups && bad < 20; cs++) bad += check_group(&g, cs, sync, NULL);
    print_message("sync %d: %d groups of %d joints, %d failures\n", (int)sync, cs - first, NJ, bad);
    if (sync == QO_MOTION_SYNC_PHASE) print_line_counts("");
    assert_int_equal(bad, 0);
}

static void test_oracle_none(void **state)
{
    (void)state;
    run_mode(QO_MOTION_SYNC_NONE, 1101);
}

static void test_oracle_time(void **state)
{
    (void)state;
    run_mode(QO_MOTION_SYNC_TIME, 1102);
}

static void test_oracle_phase(void **state)
{
    (void)state;
    run_mode(QO_MOTION_SYNC_PHASE, 1103);
}

static void test_oracle_time_if_necessary(void **state)
{
    (void)state;
    run_mode(QO_MOTION_SYNC_TIME_IF_NECESSARY, 1106);
}

/* Limits log-uniform over the accepted range [1e-3, 1e9] (vmax, amax, jmax; vmin, amin within
 * a factor 20), moving starts and target states within state_box, in every sync mode, 700
 * joints each (issue 11: with vmax 1e8 a re-plan lost
 * its target and jumped to it). */
static void test_oracle_wide(void **state)
{
    static const qo_motion_sync modes[] = { QO_MOTION_SYNC_NONE, QO_MOTION_SYNC_TIME, QO_MOTION_SYNC_PHASE,
                                            QO_MOTION_SYNC_TIME_IF_NECESSARY };
    ref_rng g;
    int cs, m, bad = 0, groups = ORACLE_GROUPS(100);
    (void)state;
    g_wide = 1;
    g.s = 1107;
    for (m = 0; m < 4; m++) {
        int b = 0, first = env_int("QO_MOTION_ORACLE_FIRST", 0), end = groups, num = env_int("QO_MOTION_ORACLE_NUM", groups);
        memset(&g_line, 0, sizeof g_line);
        if (!mode_wanted(modes[m])) first = groups;
        for (cs = 0; cs < first && cs < groups; cs++) skip_group(&g, modes[m]);
        if (num < end - cs) end = cs + num;
        for (; cs < end && b < 20; cs++) b += check_group(&g, cs, modes[m], NULL);
        for (; cs < groups; cs++) skip_group(&g, modes[m]); /* the next mode's cases as in a full run */
        if (!mode_wanted(modes[m])) continue;
        print_message("wide limits, sync %d: %d groups of %d joints, %d failures\n", (int)modes[m], end - first, NJ, b);
        if (modes[m] == QO_MOTION_SYNC_PHASE) print_line_counts("wide limits, ");
        bad += b;
    }
    g_wide = 0;
    assert_int_equal(bad, 0);
}

/* Asymmetric limits and moving target states with nonzero accelerations on every joint
 * (g_stress), in NONE, TIME and TIME_IF_NECESSARY: 2,100 joints each in make test, 200,000
 * each at QO_MOTION_ORACLE_JOINTS=1000000; QO_MOTION_ORACLE_FIRST / _NUM as for the modes. */
static void test_oracle_stress(void **state)
{
    static const qo_motion_sync modes[] = { QO_MOTION_SYNC_NONE, QO_MOTION_SYNC_TIME,
                                            QO_MOTION_SYNC_TIME_IF_NECESSARY };
    ref_rng g;
    int cs, m, bad = 0, groups = ORACLE_GROUPS(300);
    (void)state;
    g_stress = 1;
    for (m = 0; m < 3; m++) {
        int b = 0, first = env_int("QO_MOTION_ORACLE_FIRST", 0), end = groups, num = env_int("QO_MOTION_ORACLE_NUM", groups);
        g.s = 1108 + (uint64_t)m;
        if (!mode_wanted(modes[m])) continue;
        for (cs = 0; cs < first && cs < groups; cs++) skip_group(&g, modes[m]);
        if (num < end - cs) end = cs + num;
        for (; cs < end && b < 20; cs++) b += check_group(&g, cs, modes[m], NULL);
        print_message("stress, sync %d: %d groups of %d joints, %d failures\n", (int)modes[m], end - first, NJ, b);
        bad += b;
    }
    g_stress = 0;
    assert_int_equal(bad, 0);
}

/* How far a synchronised joint may end from the common duration T [s]: motion.h's
 * QO_MOTION_SYNC_END_ULPS float32 ulps of T. */
static double sync_tol(double T)
{
    float f = (float)T;
    return QO_MOTION_SYNC_END_ULPS * (double)(nextafterf(f, INFINITY) - f);
}

/* Largest |joint duration - T| in float32 ulps of T seen by test_timing (printed). */
static double g_sync_ulps;

/* 1 if T is a whole number of periods to float32 rounding: the planner's T is the float32
 * product k * period (half an ulp) and the joints end within sync_tol of it. */
static int on_tick(double T, double period)
{
    double k = floor(T / period + 0.5);
    return fabs(T - k * period) <= sync_tol(T) + 0.5 * sync_tol(T) / QO_MOTION_SYNC_END_ULPS;
}

/* qo_motion_set_timing_f32: minimum duration and durations rounded up to a control period, in
 * every sync mode, from moving starts; the duration is the smallest allowed one above the
 * reference minimum, limits hold, every synchronised joint ends on the tick.
 * QO_MOTION_ORACLE_FIRST / _NUM select cases (the same cases as a full run). */
static void test_timing(void **state)
{
    ref_rng g;
    int cs, bad = 0, nuns = 0, first = env_int("QO_MOTION_ORACLE_FIRST", 0), num = env_int("QO_MOTION_ORACLE_NUM", ORACLE_GROUPS(600));
    (void)state;
    g.s = 1104;
    for (cs = 0; cs < ORACLE_GROUPS(600) && cs - first < num && bad < 10; cs++) {
        qo_motion_planner_f32 pl;
        qo_motion_joint_f32 jts[NJ];
        jcase c[NJ];
        qo_motion_sync sync = (qo_motion_sync)(cs % 3);
        double period = cs % 4 == 0 ? 0.0 : ref_rng_range(&g, 1e-3, 0.2);
        double mind = cs % 5 == 0 ? 0.0 : ref_rng_range(&g, 0.0, 3.0), tref[NJ], tmax = 0.0, T;
        float pos[NJ];
        size_t i;
        for (i = 0; i < NJ; i++) rand_case(&g, &c[i]);
        if (cs < first) continue;
        for (i = 0; i < NJ; i++) {
            tref[i] = ref_time(&c[i]);
            tmax = fmax(tmax, tref[i]);
        }
        assert_int_equal(plan_cases(&pl, jts, c, NJ, sync), QO_OK);
        assert_int_equal(qo_motion_set_timing_f32(&pl, (float)mind, (float)period), QO_OK);
        /* the rules apply from the next re-plan: re-plan the same targets at time 0 */
        for (i = 0; i < NJ; i++) {
            put_state(&pl, i, c[i].p0, c[i].v0, c[i].a0);
            pos[i] = c[i].target;
        }
        assert_int_equal(qo_motion_set_target_f32(&pl, 0.0f, pos, NULL), QO_OK);
        mind = (float)mind;
        period = (float)period;
        T = pl.duration;
        for (i = 0; i < NJ; i++) {
            double Ti = jts[i].duration, lo = fmax(sync == QO_MOTION_SYNC_NONE ? tref[i] : tmax, mind);
            int synced = !(pl.unsynced >> i & 1u);
            if (limit_excess(&pl, i, 64) > RELLIM) {
                print_case("timing: limit exceeded", cs, i, &c[i], Ti, 0.0);
                bad++;
            }
            if (sync != QO_MOTION_SYNC_NONE && synced && T > 0.0)
                g_sync_ulps = fmax(g_sync_ulps, fabs(Ti - T) / (sync_tol(T) / QO_MOTION_SYNC_END_ULPS));
            if (sync != QO_MOTION_SYNC_NONE && synced && fabs(Ti - T) > sync_tol(T)) {
                print_case("timing: joint not synchronised", cs, i, &c[i], Ti, T);
                bad++;
            }
            /* motion.h: a joint the exact-duration search cannot stretch keeps its own minimum,
             * arrives early and waits at rest (targets here are at rest): that minimum must be
             * the reference's (case 645's joint took 6 ticks from a minimum 3.6 % too slow) */
            if (!synced) {
                nuns++;
                if (jts[i].nph == 0 || fabs(Ti - tref[i]) > RELTIME * tref[i] || c[i].vf != 0.0f || c[i].af != 0.0f) {
                    print_case("timing: unsynced joint not at its minimum", cs, i, &c[i], Ti, tref[i]);
                    bad++;
                }
            }
            if (sync == QO_MOTION_SYNC_NONE && synced && jts[i].nph > 0) {
                if (Ti < lo * (1.0 - 1e-6) || (period > 0.0 && !on_tick(Ti, period)) ||
                    Ti > (period > 0.0 ? lo + period : lo) * (1.0 + RELTIME) + 1e-6) {
                    print_case("timing: joint duration", cs, i, &c[i], Ti, lo);
                    bad++;
                }
            }
        }
        if (sync != QO_MOTION_SYNC_NONE) {
            double lo = fmax(tmax, mind);
            if (T < lo * (1.0 - 1e-6) || (period > 0.0 && pl.unsynced == 0 && !on_tick(T, period)) ||
                T > (period > 0.0 ? lo + period : lo) * (1.0 + RELTIME) + 1e-6) {
                print_error("timing case %d sync %d: T %.9g, min %.9g, period %g, min duration %g, used %d\n", cs,
                            (int)sync, T, tmax, period, mind, (int)pl.sync_used);
                bad++;
            }
        }
    }
    print_message("timing: %d cases, synchronised joints end within %.2f ulps of T (bound %d), %d joints "
                  "unsynced (at their minimum), %d failures\n",
                  cs - first, g_sync_ulps, QO_MOTION_SYNC_END_ULPS, nuns, bad);
    assert_int_equal(bad, 0);
}

static void test_timing_args(void **state)
{
    qo_motion_planner_f32 pl;
    qo_motion_joint_f32 jts[1];
    qo_motion_limits_f32 l = qo_motion_limits_default;
    float p = 0.0f;
    (void)state;
    assert_int_equal(qo_motion_set_timing_f32(NULL, 0.0f, 0.0f), QO_E_NULL);
    assert_int_equal(qo_motion_init_f32(&pl, jts, 0, &l, &p, 0.0f, NULL), QO_E_TOO_FEW);
    assert_int_equal(qo_motion_set_timing_f32(&pl, 0.0f, 0.0f), QO_E_STATE);
    assert_int_equal(qo_motion_init_f32(&pl, jts, 1, &l, &p, 0.0f, NULL), QO_OK);
    assert_true(pl.min_duration == 0.0f && pl.period == 0.0f);
    assert_int_equal(qo_motion_set_timing_f32(&pl, 1.0f, 0.01f), QO_OK);
    assert_int_equal(qo_motion_set_timing_f32(&pl, -1.0f, 0.0f), QO_E_ARG);
    assert_int_equal(qo_motion_set_timing_f32(&pl, NAN, 0.0f), QO_E_ARG);
    assert_int_equal(qo_motion_set_timing_f32(&pl, INFINITY, 0.0f), QO_E_ARG);
    assert_int_equal(qo_motion_set_timing_f32(&pl, 0.0f, -0.01f), QO_E_ARG);
    assert_int_equal(qo_motion_set_timing_f32(&pl, 0.0f, NAN), QO_E_ARG);
    assert_int_equal(qo_motion_set_timing_f32(&pl, 0.0f, 1e-9f), QO_E_ARG);
    assert_int_equal(qo_motion_set_timing_f32(&pl, 0.0f, 1e5f), QO_E_ARG);
    /* rules unchanged by the refused calls */
    assert_true(pl.min_duration == 1.0f && pl.period == 0.01f);
    /* a move of 0.01 u (minimum 0.684 s) takes the minimum duration, 1 s = 100 periods */
    p = 0.01f;
    assert_int_equal(qo_motion_set_target_f32(&pl, 0.0f, &p, NULL), QO_OK);
    assert_true(fabs(pl.duration - 1.0) < 1e-6);
    assert_int_equal(qo_motion_brake_f32(&pl, 0.5f), QO_OK);
    assert_true(pl.joints[0].duration < 0.5f); /* a safety stop ignores the rules */
}

/* Velocity interface: from random moving states (asymmetric limits, the joints on their way to
 * moving target states) to random target velocities in [vmin, vmax] in the minimum time of the
 * velocity change (reference), within the limits, continuous at the call, then on at the
 * target velocity; a later set_target leaves velocity mode without a jump; bad input. */
static void test_velocity(void **state)
{
    ref_rng g;
    int cs, bad = 0;
    (void)state;
    g.s = 1105;
    for (cs = 0; cs < ORACLE_GROUPS(400) && bad < 10; cs++) {
        qo_motion_planner_f32 pl;
        qo_motion_joint_f32 jts[NJ];
        jcase c[NJ];
        float vt[NJ], p1[NJ], v1[NJ], a1[NJ], p2[NJ], v2[NJ], a2[NJ], tg[NJ];
        float tm, te;
        size_t i;
        qo_motion_sync sync = (qo_motion_sync)(cs % 3);
        for (i = 0; i < NJ; i++) {
            mref_lim r;
            /* asymmetric limits on about half the joints (vmin, amin), moving target states
             * before the call; the target velocity anywhere in [vmin, vmax] */
            rand_case_mix(&g, &c[i], 1);
            r = ref_lim_of(&c[i].lim);
            vt[i] = (float)ref_rng_range(&g, r.vmin, r.vmax);
            if (cs % 7 == 0) vt[i] = 0.0f;
        }
        assert_int_equal(plan_cases(&pl, jts, c, NJ, sync), QO_OK);
        tm = 0.3f * pl.duration;
        qo_motion_sample_f32(&pl, tm, p1, v1, a1);
        assert_int_equal(qo_motion_set_velocity_f32(&pl, tm, vt), QO_OK);
        assert_int_equal(pl.vel_mode, 1);
        qo_motion_sample_f32(&pl, tm, p2, v2, a2);
        for (i = 0; i < NJ; i++) {
            mref_lim r = ref_lim_of(&c[i].lim);
            /* the sampled a may exceed amax by float32 rounding: the reference takes it at amax */
            double as = fmin(fmax(a1[i], r.amin), r.amax);
            double tr = mref_vel_time(&r, v1[i], as, vt[i], 0.0), Ti = jts[i].duration;
            if (fabs(p2[i] - p1[i]) > 1e-6 * (1.0 + fabs(p1[i])) || fabs(v2[i] - v1[i]) > 1e-6 * c[i].lim.vmax ||
                fabs(a2[i] - a1[i]) > 1e-6 * c[i].lim.amax) {
                print_case("velocity: jump at the call", cs, i, &c[i], v2[i], v1[i]);
                bad++;
            }
            if (fabs(Ti - tr) > RELTIME * tr + 1e-6) {
                print_case("velocity: time of the velocity change", cs, i, &c[i], Ti, tr);
                bad++;
            }
            if (limit_excess(&pl, i, 64) > RELLIM) {
                print_case("velocity: limit exceeded", cs, i, &c[i], Ti, 0.0);
                bad++;
            }
        }
        /* after the end: on at the target velocity, on a straight line */
        te = qo_motion_end_time_f32(&pl);
        qo_motion_sample_f32(&pl, te + 0.5f, p1, v1, a1);
        qo_motion_sample_f32(&pl, te + 1.5f, p2, v2, a2);
        for (i = 0; i < NJ; i++) {
            if (v1[i] != vt[i] || v2[i] != vt[i] || a1[i] != 0.0f || a2[i] != 0.0f ||
                fabs((p2[i] - p1[i]) - vt[i]) > 1e-5 * (1.0 + fabs(p1[i]))) {
                print_case("velocity: not moving on at the target", cs, i, &c[i], v2[i], vt[i]);
                bad++;
            }
            tg[i] = c[i].target;
        }
        /* back to a position target: continuous, ends at rest */
        qo_motion_sample_f32(&pl, te + 1.5f, p1, v1, a1);
        assert_int_equal(qo_motion_set_target_f32(&pl, te + 1.5f, tg, NULL), QO_OK);
        assert_int_equal(pl.vel_mode, 0);
        qo_motion_sample_f32(&pl, te + 1.5f, p2, v2, a2);
        for (i = 0; i < NJ; i++) {
            if (fabs(p2[i] - p1[i]) > 1e-6 * (1.0 + fabs(p1[i])) || fabs(v2[i] - v1[i]) > 1e-6 * c[i].lim.vmax ||
                jts[i].vend != 0.0f) {
                print_case("velocity: jump back to position mode", cs, i, &c[i], v2[i], v1[i]);
                bad++;
            }
        }
        qo_motion_sample_f32(&pl, qo_motion_end_time_f32(&pl) + 1.0f, p2, v2, a2);
        for (i = 0; i < NJ; i++)
            /* final = start + (goal - start) in float32: the goal to an ulp of the positions */
            if (fabs(p2[i] - tg[i]) > 2.4e-7 * (fabs(tg[i]) + fabs(p1[i])) || v2[i] != 0.0f) {
                print_case("velocity: position target not reached", cs, i, &c[i], p2[i], tg[i]);
                bad++;
            }
    }
    print_message("velocity: %d groups of %d joints, %d failures\n", cs, NJ, bad);
    assert_int_equal(bad, 0);
}

static void test_velocity_args(void **state)
{
    qo_motion_planner_f32 pl;
    qo_motion_joint_f32 jts[2];
    qo_motion_limits_f32 l[2];
    qo_motion_table_q16 tab;
    qo_motion_seg_q16 segs[2 * QO_MOTION_Q16_SEGS];
    qo_q16 qp[2], qv[2];
    float p[2] = { 0.0f, 1.0f }, v[2] = { 0.5f, -0.25f }, d0, pos[2], vel[2];
    (void)state;
    l[0] = l[1] = qo_motion_limits_default;
    l[0].pmax = 0.5f; /* the range does not stop a joint in velocity mode */
    assert_int_equal(qo_motion_set_velocity_f32(NULL, 0.0f, v), QO_E_NULL);
    assert_int_equal(qo_motion_init_f32(&pl, jts, 0, l, p, 0.0f, NULL), QO_E_TOO_FEW);
    assert_int_equal(qo_motion_set_velocity_f32(&pl, 0.0f, v), QO_E_STATE);
    assert_int_equal(qo_motion_init_f32(&pl, jts, 2, l, p, 1.0f, NULL), QO_OK);
    assert_int_equal(qo_motion_set_velocity_f32(&pl, 1.0f, NULL), QO_E_NULL);
    assert_int_equal(qo_motion_set_velocity_f32(&pl, 0.5f, v), QO_E_ORDER);
    assert_int_equal(qo_motion_set_velocity_f32(&pl, NAN, v), QO_E_NONFINITE);
    v[1] = -1.5f; /* beyond vmax: refused, nothing moves */
    assert_int_equal(qo_motion_set_velocity_f32(&pl, 1.0f, v), QO_E_RANGE);
    assert_int_equal(pl.vel_mode, 0);
    assert_true(pl.duration == 0.0f);
    v[1] = -0.25f;
    assert_int_equal(qo_motion_set_velocity_f32(&pl, 1.0f, v), QO_OK);
    d0 = pl.duration;
    assert_true(d0 > 0.0f);
    /* ten seconds later joint 0 is far past its pmax, moving on */
    assert_int_equal(qo_motion_sample_f32(&pl, 11.0f, pos, vel, NULL), QO_OK);
    assert_true(pos[0] > 4.0f && vel[0] == 0.5f && vel[1] == -0.25f);
    /* the Q16.16 export moves on the same way */
    assert_int_equal(qo_motion_export_q16(&pl, &tab, segs, 2 * QO_MOTION_Q16_SEGS), QO_OK);
    assert_int_equal(qo_motion_sample_q16(&tab, 10 << 16, qp, qv, NULL), QO_OK);
    assert_true(fabs(qp[0] / 65536.0 - pos[0]) < 1e-3 && qv[0] == 32768 && qv[1] == -16384);
    /* set_limits keeps velocity mode, clamped to the new vmax */
    l[1].vmax = 0.1f;
    assert_int_equal(qo_motion_set_limits_f32(&pl, 11.0f, 1, &l[1]), QO_OK);
    assert_int_equal(pl.vel_mode, 1);
    assert_true(jts[1].vend == -0.1f);
    /* a NaN velocity brakes every joint to rest */
    v[0] = NAN;
    assert_int_equal(qo_motion_set_velocity_f32(&pl, 12.0f, v), QO_E_NONFINITE);
    assert_int_equal(pl.braking, 1);
    assert_int_equal(pl.vel_mode, 0);
    assert_int_equal(qo_motion_sample_f32(&pl, 100.0f, pos, vel, NULL), QO_OK);
    assert_true(vel[0] == 0.0f && vel[1] == 0.0f);
}

/* The reference itself against the closed form, rest to rest (symmetric limits). */
static void test_reference_closed_form(void **state)
{
    ref_rng g;
    int cs;
    (void)state;
    g.s = 1100;
    for (cs = 0; cs < ORACLE_GROUPS(300); cs++) {
        mref_lim l;
        double D = ref_rng_range(&g, -3.0, 3.0), t, tc;
        l.vmax = ref_rng_range(&g, 0.5, 5.0);
        l.vmin = -l.vmax;
        l.amax = ref_rng_range(&g, 1.0, 20.0);
        l.amin = -l.amax;
        l.jmax = ref_rng_range(&g, 10.0, 500.0);
        t = mref_min_time(&l, 0.3, 0.0, 0.0, 0.3 + D, 0.0, 0.0);
        tc = mref_rest_time(D, l.vmax, l.amax, l.jmax);
        if (fabs(t - tc) > 1e-6 * tc) {
            print_error("case %d: D %g V %g A %g J %g: search %.12g closed form %.12g\n", cs, D, l.vmax, l.amax, l.jmax,
                        t, tc);
            fail();
        }
    }
}

/* Issue 11 (position jump): vmax 1e8, amax 24, jmax 1000, velocity interface to 2.14 at t = 0,
 * then set_target(0) at t = 0.2. The solver's tolerance scaled with vmax, so a 0.4 miss of the
 * profile through the start's own stop velocity passed for rounding: the plan stopped at 0.41
 * after 0.089 s and the sample snapped to 0. Checked against closed forms (TRAPEZOID: stop,
 * then a triangle back) and the reference (SCURVE), with the ordinary vmax 5 for comparison,
 * and no jump on dense samples. */
static void test_issue_large_vmax_jump(void **state)
{
    /* up to the largest accepted vmax (1e12 before the range was narrowed to what is verified) */
    static const float vmaxs[] = { 5.0f, 1e6f, 1e8f, QO_MOTION_LIMIT_MAX };
    int prof, k, s;
    (void)state;
    for (prof = 0; prof < 2; prof++) {
        for (k = 0; k < 4; k++) {
            qo_motion_joint_f32 j[1];
            qo_motion_planner_f32 pl;
            qo_motion_limits_f32 l = qo_motion_limits_default;
            qo_motion_settings_f32 st = qo_motion_settings_default;
            float p0 = 0.0f, v = 2.14f, tg = 0.0f, p, vv, a, prev = 0.0f;
            double T, ref, vm = 0.0;
            mref_lim r;
            l.vmax = vmaxs[k];
            l.amax = 24.0f;
            l.jmax = 1000.0f;
            st.profile = prof ? QO_MOTION_SCURVE : QO_MOTION_TRAPEZOID;
            assert_int_equal(qo_motion_init_f32(&pl, j, 1, &l, &p0, 0.0f, &st), QO_OK);
            assert_int_equal(qo_motion_set_velocity_f32(&pl, 0, &v), QO_OK);
            qo_motion_sample_f32(&pl, 0.2f, &p, &vv, &a);
            assert_int_equal(qo_motion_set_target_f32(&pl, 0.2f, &tg, NULL), QO_OK);
            T = qo_motion_duration_f32(&pl);
            if (prof == 0) {
                /* stop from (p, v) at a = 0, then the triangle from rest back to 0 */
                double A = 24.0, ps = p + (double)vv * vv / (2.0 * A);
                ref = vv / A + 2.0 * sqrt(ps / A);
            } else {
                r = ref_lim_of(&l);
                ref = mref_min_time(&r, p, vv, a, 0.0, 0.0, 0.0);
            }
            if (fabs(T - ref) > 1e-4 * ref) {
                print_error("profile %d vmax %g: duration %.9g, reference %.9g\n", prof, (double)l.vmax, T, ref);
                fail();
            }
            for (s = 0; s <= 1000; s++) {
                qo_motion_sample_f32(&pl, 0.2f + (float)(s * 1e-3), &p, &vv, &a);
                /* |dp| <= max|v| dt, max|v| on the step <= the larger end's + amax dt / 2 */
                if (s > 0 && fabs(p - prev) > (fmax(vm, fabs(vv)) + 12.0 * 1e-3) * 1e-3 * 1.01 + 1e-6) {
                    print_error("profile %d vmax %g: jump %g -> %g at t %g\n", prof, (double)l.vmax, (double)prev,
                                (double)p, 0.2 + s * 1e-3);
                    fail();
                }
                prev = p;
                vm = fabs(vv);
            }
            assert_true(fabs(prev) <= 1e-6f); /* at the goal */
        }
    }
}

/* check_line and line_feasible reject what they must: a PHASE plan of a line group passes,
 * and fails with one joint's jerk 0.1 % off, with its duration 1 % long, against a slowest
 * joint's minimum above it, and as the TIME plan of the same group; line_feasible holds for it
 * (a planner that fell back on it would fail). 20 line groups with moving starts. */
static void test_line_checks_fail(void **state)
{
    ref_rng g;
    int n = 0;
    (void)state;
    g.s = 1109;
    while (n < ORACLE_GROUPS(20)) {
        qo_motion_planner_f32 pl, bad;
        qo_motion_joint_f32 jts[NJ], jb[NJ];
        jcase c[NJ];
        size_t i;
        unsigned k;
        for (i = 0; i < NJ; i++) rand_case_mix(&g, &c[i], 1);
        if (!phase_line(&g, c) || c[0].v0 == 0.0f) continue;
        n++;
        assert_int_equal(plan_cases(&pl, jts, c, NJ, QO_MOTION_SYNC_PHASE), QO_OK);
        assert_int_equal(pl.sync_used, QO_MOTION_SYNC_PHASE);
        assert_true(line_feasible(c));
        assert_int_equal(check_line(&pl, n, c, 0.0), 0);
        g_quiet = 1;
        /* one joint off the line */
        bad = pl;
        memcpy(jb, jts, sizeof jb);
        bad.joints = jb;
        for (k = 0; k < jb[0].nph; k++) jb[0].ph[k].j *= 1.001f;
        assert_true(check_line(&bad, n, c, 0.0) > 0);
        /* a line slower than its minimum */
        memcpy(jb, jts, sizeof jb);
        bad.duration = pl.duration * 1.01f;
        assert_true(check_line(&bad, n, c, 0.0) > 0);
        /* a joint's own minimum above the plan's */
        assert_true(check_line(&pl, n, c, 1.01 * pl.duration) > 0);
        /* the TIME plan: one duration, not one line */
        assert_int_equal(plan_cases(&pl, jts, c, NJ, QO_MOTION_SYNC_TIME), QO_OK);
        assert_true(check_line(&pl, n, c, 0.0) > 0);
        g_quiet = 0;
    }
}

/* Issue 11, defect 1: phase sync from a moving start broke vmax by up to 3.84x. */
static void test_issue_phase_sync_moving(void **state)
{
    static const float vmax[NJ] = { 1.72672474f, 3.19527483f, 0.540558755f, 1.56946921f, 2.55408978f, 3.71123886f, 2.81213045f };
    static const float amax[NJ] = { 15.9911842f, 17.6804562f, 14.7866173f, 14.8234911f, 19.4377403f, 15.7666721f, 11.1936378f };
    static const float jmax[NJ] = { 259.182587f, 153.709946f, 254.415833f, 377.374084f, 63.1564674f, 238.2733f, 183.108002f };
    static const float tgt[NJ] = { -2.91880322f, 1.05259836f, -2.57023644f, 2.06626081f, -1.94207144f, 0.61733216f, 1.32804322f };
    qo_motion_planner_f32 pl;
    qo_motion_joint_f32 jts[NJ];
    jcase c[NJ];
    size_t i;
    (void)state;
    memset(c, 0, sizeof c);
    for (i = 0; i < NJ; i++) {
        c[i].lim = qo_motion_limits_default;
        c[i].lim.vmax = vmax[i];
        c[i].lim.amax = amax[i];
        c[i].lim.jmax = jmax[i];
        c[i].p0 = 0.0f;
        c[i].v0 = 0.125f * tgt[i];
        c[i].a0 = 4.0f * tgt[i];
        c[i].target = tgt[i];
    }
    assert_int_equal(plan_cases(&pl, jts, c, NJ, QO_MOTION_SYNC_PHASE), QO_OK);
    for (i = 0; i < NJ; i++) {
        double e = limit_excess(&pl, i, 2000);
        if (e > RELLIM) {
            print_case("phase sync limit", 0, i, &c[i], e, 0.0);
            fail();
        }
    }
    /* Not feasible as a straight line: TIME, at the optimum 4.8065 s. */
    assert_int_equal(qo_motion_sync_used(&pl), QO_MOTION_SYNC_TIME);
    assert_true(fabs(pl.duration - 4.8065) < 1e-3);
}

/* Issue 11, defect 2: the profile "acceleration ramps down, then up to amax, holds, ramps to
 * zero" was missing (0.3363 s instead of 0.2627 s); also in a TIME plan (1.3925 s for 1.3231 s).
 * Third: the other orientation (a0 ramps briefly further away from zero, then up to amax),
 * found by make check-motion (0.5281 s instead of 0.5184 s). */
static void test_issue_missing_shape(void **state)
{
    jcase c[3];
    qo_motion_planner_f32 pl;
    qo_motion_joint_f32 jts[NJ];
    int k;
    (void)state;
    memset(c, 0, sizeof c);
    c[0].lim = c[1].lim = qo_motion_limits_default;
    c[0].lim.vmax = 4.41488028f;
    c[0].lim.amax = 19.952261f;
    c[0].lim.jmax = 108.015678f;
    c[0].p0 = -0.088470608f;
    c[0].v0 = -2.58858132f;
    c[0].a0 = 11.5556173f;
    c[0].target = -0.371979445f;
    c[1].lim.vmax = 3.34469533f;
    c[1].lim.amax = 2.34070969f;
    c[1].lim.jmax = 29.4899502f;
    c[1].p0 = 1.28110254f;
    c[1].v0 = -2.97041011f;
    c[1].a0 = 1.55960763f;
    c[1].target = -0.646739721f;
    c[2].lim = qo_motion_limits_default;
    c[2].lim.vmax = 4.1246357f;
    c[2].lim.amax = 3.74037433f;
    c[2].lim.jmax = 19.2452679f;
    c[2].p0 = 0.384773493f;
    c[2].v0 = -0.953012407f;
    c[2].a0 = -1.15454602f;
    c[2].target = 0.0998001546f;
    for (k = 0; k < 3; k++) {
        double tr = ref_time(&c[k]);
        assert_int_equal(plan_cases(&pl, jts, &c[k], 1, QO_MOTION_SYNC_TIME), QO_OK);
        if (!(pl.duration <= tr * (1.0 + RELTIME)) || limit_excess(&pl, 0, 2000) > RELLIM) {
            print_case("missing shape", k, 0, &c[k], pl.duration, tr);
            fail();
        }
    }
    assert_true(fabs(ref_time(&c[0]) - 0.2627) < 1e-3);
    assert_true(fabs(ref_time(&c[1]) - 1.3231) < 1e-3);
    assert_true(fabs(ref_time(&c[2]) - 0.5184) < 1e-3);
}

/* ---- asymmetric limits, target states, per-joint sync (unit checks) ---- */

static qo_motion_limits_f32 lim_of(float vmax, float amax, float jmax, float vmin, float amin)
{
    qo_motion_limits_f32 l = qo_motion_limits_default;
    l.vmax = vmax;
    l.amax = amax;
    l.jmax = jmax;
    l.vmin = vmin;
    l.amin = amin;
    return l;
}

/* Random limits as in issue 11, with a random vmin / amin where asked. */
static qo_motion_limits_f32 rand_lim(ref_rng *g, int asym_v, int asym_a)
{
    float vmax = (float)ref_rng_range(g, 0.5, 5.0), amax = (float)ref_rng_range(g, 1.0, 20.0);
    float jmax = (float)ref_rng_range(g, 10.0, 500.0);
    float vmin = asym_v ? (float)-ref_rng_range(g, 0.5, 5.0) : 0.0f, amin = asym_a ? (float)-ref_rng_range(g, 1.0, 20.0) : 0.0f;
    return lim_of(vmax, amax, jmax, vmin, amin);
}

static void init_n(qo_motion_planner_f32 *pl, qo_motion_joint_f32 *jts, size_t n, const qo_motion_limits_f32 *l,
                   qo_motion_sync sync)
{
    qo_motion_settings_f32 st = { QO_MOTION_SCURVE, QO_MOTION_SYNC_TIME };
    float p0[NJ];
    memset(p0, 0, sizeof p0);
    st.sync = sync;
    assert_int_equal(qo_motion_init_f32(pl, jts, n, l, p0, 0.0f, &st), QO_OK);
}

static void test_asym_limits_validated(void **state)
{
    qo_motion_planner_f32 pl;
    qo_motion_joint_f32 jts[1];
    float p0 = 0.0f, tg = 1.0f, pos, vel;
    const float bad[] = { 1.0f, -1e-7f, -2e12f, NAN, INFINITY, -INFINITY, 1e-30f };
    size_t k;
    (void)state;
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        qo_motion_limits_f32 l = qo_motion_limits_default;
        l.vmin = bad[k];
        assert_int_equal(qo_motion_init_f32(&pl, jts, 1, &l, &p0, 0.0f, NULL), QO_E_LIMIT);
        l.vmin = 0.0f;
        l.amin = bad[k];
        assert_int_equal(qo_motion_init_f32(&pl, jts, 1, &l, &p0, 0.0f, NULL), QO_E_LIMIT);
    }
    {
        /* a bad vmin in set_limits: old limits stay, the joint brakes */
        qo_motion_limits_f32 l = lim_of(2.0f, 5.0f, 50.0f, -1.0f, -2.0f);
        assert_int_equal(qo_motion_init_f32(&pl, jts, 1, &l, &p0, 0.0f, NULL), QO_OK);
        assert_int_equal(qo_motion_set_target_f32(&pl, 0.0f, &tg, NULL), QO_OK);
        l.vmin = 3.0f;
        assert_int_equal(qo_motion_set_limits_f32(&pl, 0.2f, 0, &l), QO_E_LIMIT);
        assert_int_equal(pl.braking, 1);
        assert_true(jts[0].lim.vmin == -1.0f);
        /* the velocity interface refuses a velocity below vmin, accepts down to it */
        vel = -1.5f;
        assert_int_equal(qo_motion_set_velocity_f32(&pl, 0.3f, &vel), QO_E_RANGE);
        vel = -1.0f;
        assert_int_equal(qo_motion_set_velocity_f32(&pl, 0.3f, &vel), QO_OK);
        assert_int_equal(qo_motion_sample_f32(&pl, qo_motion_end_time_f32(&pl) + 1.0f, &pos, &vel, NULL), QO_OK);
        assert_true(vel == -1.0f);
    }
}

/* Samples the planner at t for all n joints. */
static void snap(const qo_motion_planner_f32 *pl, float t, float *p, float *v, float *a)
{
    qo_motion_sample_f32(pl, t, p, v, a);
}

static void test_target_state_refused(void **state)
{
    /* joint limits vmax 2, vmin -1, amax 4, amin -8, jmax 16: a|a|/(2 jmax) = 0.5 at a = 4 */
    qo_motion_limits_f32 l[2];
    qo_motion_planner_f32 pl, before;
    qo_motion_joint_f32 jts[2], jb[2];
    struct {
        float v, a;
        qo_status st;
    } cases[] = {
        { 2.5f, 0.0f, QO_E_LIMIT },   /* above vmax */
        { -1.5f, 0.0f, QO_E_LIMIT },  /* below vmin (but within -vmax) */
        { 0.0f, 5.0f, QO_E_LIMIT },   /* above amax */
        { 0.0f, -9.0f, QO_E_LIMIT },  /* below amin */
        { 1.8f, 4.0f, QO_E_LIMIT },   /* 1.8 + 0.5 overshoots vmax while a ramps to 0 */
        { -0.8f, 4.0f, QO_E_LIMIT },  /* -0.8 - 0.5: not reachable from a = 0 within vmin */
        { 1.8f, -4.0f, QO_E_LIMIT },  /* reached from 1.8 + 0.5 > vmax */
        { 1.4f, 4.0f, QO_OK },        /* 1.9 and 0.9: fine */
        { -0.4f, -4.0f, QO_OK },      /* -0.9 and 0.1 */
    };
    float tg[2] = { 1.0f, -0.5f }, v[2], a[2], p1[2], v1[2], a1[2], p2[2], v2[2], a2[2];
    uint32_t cl = 77u;
    size_t k;
    (void)state;
    l[0] = lim_of(2.0f, 4.0f, 16.0f, -1.0f, -8.0f);
    l[1] = lim_of(2.0f, 4.0f, 16.0f, -1.0f, -8.0f);
    for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        init_n(&pl, jts, 2, l, QO_MOTION_SYNC_TIME);
        assert_int_equal(qo_motion_set_target_f32(&pl, 0.0f, tg, NULL), QO_OK);
        snap(&pl, 0.3f, p1, v1, a1);
        memcpy(&before, &pl, sizeof pl);
        memcpy(jb, jts, sizeof jb);
        v[0] = 0.0f;
        a[0] = 0.0f;
        v[1] = cases[k].v;
        a[1] = cases[k].a;
        cl = 77u;
        assert_int_equal(qo_motion_set_target_state_f32(&pl, 0.2f, tg, v, a, &cl), cases[k].st);
        assert_int_equal(cl, 0u);
        if (cases[k].st != QO_OK) {
            /* refused: nothing moves differently */
            assert_memory_equal(&pl, &before, sizeof pl);
            assert_memory_equal(jts, jb, sizeof jb);
            snap(&pl, 0.3f, p2, v2, a2);
            assert_memory_equal(p1, p2, sizeof p1);
            assert_memory_equal(v1, v2, sizeof v1);
        }
    }
    /* TRAPEZOID has no jerk limit: a target acceleration is refused (QO_E_ARG), a velocity not */
    {
        qo_motion_settings_f32 st = { QO_MOTION_TRAPEZOID, QO_MOTION_SYNC_TIME };
        float p0[2] = { 0.0f, 0.0f };
        assert_int_equal(qo_motion_init_f32(&pl, jts, 2, l, p0, 0.0f, &st), QO_OK);
        v[0] = 0.5f;
        v[1] = 0.0f;
        a[0] = 1.0f;
        a[1] = 0.0f;
        memcpy(&before, &pl, sizeof pl);
        assert_int_equal(qo_motion_set_target_state_f32(&pl, 0.0f, tg, v, a, NULL), QO_E_ARG);
        assert_memory_equal(&pl, &before, sizeof pl);
        assert_int_equal(qo_motion_set_target_state_f32(&pl, 0.0f, tg, v, NULL, NULL), QO_OK);
        snap(&pl, qo_motion_end_time_f32(&pl), p1, v1, a1);
        assert_true(fabs(v1[0] - 0.5) < 1e-6 && fabs(p1[0] - 1.0) < 1e-6);
    }
    /* NaN velocity or acceleration: brake, as for a NaN target */
    init_n(&pl, jts, 2, l, QO_MOTION_SYNC_TIME);
    assert_int_equal(qo_motion_set_target_f32(&pl, 0.0f, tg, NULL), QO_OK);
    v[0] = NAN;
    assert_int_equal(qo_motion_set_target_state_f32(&pl, 0.1f, tg, v, NULL, NULL), QO_E_NONFINITE);
    assert_int_equal(pl.braking, 1);
    v[0] = 0.0f;
    a[0] = INFINITY;
    assert_int_equal(qo_motion_set_target_state_f32(&pl, 0.2f, tg, v, a, NULL), QO_E_NONFINITE);
    assert_int_equal(qo_motion_set_target_state_f32(NULL, 0.2f, tg, v, a, NULL), QO_E_NULL);
    assert_int_equal(qo_motion_set_target_state_f32(&pl, 0.2f, NULL, v, a, NULL), QO_E_NULL);
    assert_int_equal(qo_motion_set_target_state_f32(&pl, 0.1f, tg, NULL, NULL, NULL), QO_E_ORDER);
}

/* The motion after the end of a plan to (p, v, a), in double: a ramps to 0 at jmax, then the
 * velocity stays. */
static void after_end_ref(double p, double v, double a, double J, double x, double *po, double *vo, double *ao)
{
    double ta = fabs(a) / J, jr = a > 0.0 ? -J : J, y = x < ta ? x : ta;
    *po = p + y * v + y * y * a / 2.0 + y * y * y * jr / 6.0;
    *vo = v + y * a + y * y * jr / 2.0;
    *ao = x < ta ? a + y * jr : 0.0;
    if (x > ta) *po += *vo * (x - ta);
}

static void test_after_end(void **state)
{
    ref_rng g;
    int cs;
    (void)state;
    g.s = 2201;
    for (cs = 0; cs < ORACLE_GROUPS(300); cs++) {
        qo_motion_planner_f32 pl;
        qo_motion_joint_f32 jts[NJ];
        qo_motion_limits_f32 l[NJ];
        qo_motion_table_q16 tab;
        qo_motion_seg_q16 segs[NJ * QO_MOTION_Q16_SEGS];
        float tg[NJ], v[NJ], a[NJ], pos[NJ], vel[NJ], acc[NJ];
        qo_q16 qp[NJ], qv[NJ], qa[NJ];
        size_t i;
        int k;
        for (i = 0; i < NJ; i++) {
            mref_lim r;
            l[i] = rand_lim(&g, cs % 2, cs % 3);
            r = ref_lim_of(&l[i]);
            tg[i] = (float)ref_rng_range(&g, -3.0, 3.0);
            rand_state(&g, &r, 1, &v[i], &a[i]);
            if (cs % 5 == 0) a[i] = 0.0f;
        }
        init_n(&pl, jts, NJ, l, (qo_motion_sync)(cs % 4));
        assert_int_equal(qo_motion_set_target_state_f32(&pl, 0.0f, tg, v, a, NULL), QO_OK);
        assert_int_equal(qo_motion_export_q16(&pl, &tab, segs, NJ * QO_MOTION_Q16_SEGS), QO_OK);
        for (k = 0; k <= 40; k++) {
            float t = pl.duration + 0.02f * (float)k;
            snap(&pl, t, pos, vel, acc);
            qo_motion_sample_q16(&tab, (qo_q16)lrint(t * 65536.0), qp, qv, qa);
            for (i = 0; i < NJ; i++) {
                double pr, vr, ar, x = (double)t - jts[i].duration;
                mref_lim r = ref_lim_of(&l[i]);
                after_end_ref(tg[i], v[i], a[i], l[i].jmax, x, &pr, &vr, &ar);
                if (fabs(pos[i] - pr) > 1e-5 * (1.0 + fabs(pr)) || fabs(vel[i] - vr) > 1e-5 * r.vmax ||
                    fabs(acc[i] - ar) > 1e-5 * r.amax || vel[i] > r.vmax * (1.0 + 1e-6) ||
                    vel[i] < r.vmin * (1.0 + 1e-6) || !qo_motion_done_f32(&pl, t)) {
                    print_error("case %d joint %zu x %g: p %g v %g a %g, ref %g %g %g\n", cs, i, x, (double)pos[i],
                                (double)vel[i], (double)acc[i], pr, vr, ar);
                    fail();
                }
                /* the Q16.16 table follows the same motion at its own (rounded) time */
                x = lrint(t * 65536.0) / 65536.0 - jts[i].duration;
                if (x < 0.0) continue; /* the rounded time falls in the plan's last phase */
                after_end_ref(tg[i], v[i], a[i], l[i].jmax, x, &pr, &vr, &ar);
                if (fabs(qp[i] / 65536.0 - pr) > 2e-4 * (1.0 + fabs(pr)) || fabs(qv[i] / 65536.0 - vr) > 2e-4 * (1.0 + r.vmax) ||
                    fabs(qa[i] / 65536.0 - ar) > 2e-4 * (1.0 + r.amax)) {
                    print_error("q16 case %d joint %zu x %g: p %g v %g a %g, ref %g %g %g\n", cs, i, x, qp[i] / 65536.0,
                                qv[i] / 65536.0, qa[i] / 65536.0, pr, vr, ar);
                    fail();
                }
            }
        }
    }
}

/* Duration of a joint's own minimum-time plan, from the reference. */
static double ref_min(const qo_motion_limits_f32 *l, float p0, float v0, float a0, float tg, float vf, float af)
{
    mref_lim r = ref_lim_of(l);
    return mref_min_time(&r, p0, v0, a0, tg, vf, af);
}

static void test_joint_sync(void **state)
{
    ref_rng g;
    int cs, nline = 0, nunsynced = 0;
    (void)state;
    g.s = 2202;
    for (cs = 0; cs < ORACLE_GROUPS(400); cs++) {
        qo_motion_planner_f32 pl;
        qo_motion_joint_f32 jts[NJ];
        qo_motion_limits_f32 l[NJ];
        float tg[NJ], v0[NJ], a0[NJ], vf[NJ], af[NJ];
        qo_motion_sync js[NJ];
        double tr[NJ], tsync = 0.0, T;
        size_t i;
        int nphase = 0, k;
        qo_motion_sync dflt = (qo_motion_sync)(cs % 4);
        for (i = 0; i < NJ; i++) {
            l[i] = rand_lim(&g, 0, 0);
            tg[i] = (float)ref_rng_range(&g, -3.0, 3.0);
            v0[i] = a0[i] = vf[i] = af[i] = 0.0f;
            if (ref_rng_unit(&g) < 0.5) v0[i] = (float)ref_rng_range(&g, -0.5, 0.5) * l[i].vmax;
            /* moving targets on some joints (TIME_IF_NECESSARY), at rest on the others */
            if (ref_rng_unit(&g) < 0.5) vf[i] = (float)ref_rng_range(&g, -0.5, 0.5) * l[i].vmax;
            js[i] = (qo_motion_sync)(ref_rng_next(&g) % 5); /* 4 = keep the settings' sync */
        }
        init_n(&pl, jts, NJ, l, dflt);
        for (i = 0; i < NJ; i++) {
            put_state(&pl, i, 0.0f, v0[i], a0[i]);
            if (js[i] != 4) assert_int_equal(qo_motion_set_joint_sync_f32(&pl, i, js[i]), QO_OK);
            else js[i] = dflt;
            if (js[i] == QO_MOTION_SYNC_TIME_IF_NECESSARY)
                js[i] = vf[i] != 0.0f ? QO_MOTION_SYNC_TIME : QO_MOTION_SYNC_NONE;
            tr[i] = ref_min(&l[i], 0.0f, v0[i], a0[i], tg[i], vf[i], af[i]);
            if (js[i] != QO_MOTION_SYNC_NONE) tsync = fmax(tsync, tr[i]);
            if (js[i] == QO_MOTION_SYNC_PHASE) nphase++;
        }
        assert_int_equal(qo_motion_set_target_state_f32(&pl, 0.0f, tg, vf, af, NULL), QO_OK);
        T = pl.duration;
        for (i = 0; i < NJ; i++) {
            double d = jts[i].duration;
            if (js[i] == QO_MOTION_SYNC_NONE) {
                if (fabs(d - tr[i]) > 1e-3 * tr[i] + 1e-6) {
                    print_error("case %d joint %zu (own time): %g ref %g\n", cs, i, d, tr[i]);
                    fail();
                }
            } else if (!(pl.unsynced >> i & 1u)) {
                /* every synchronised joint ends at the common duration; it is the slowest
                 * synchronised joint's minimum unless the straight line is slower */
                double Ts = 0.0;
                size_t m;
                for (m = 0; m < NJ; m++)
                    if (js[m] != QO_MOTION_SYNC_NONE) Ts = fmax(Ts, jts[m].duration);
                if (fabs(d - Ts) > 1e-6 * Ts || Ts < tsync * (1.0 - 1e-3) - 1e-6 ||
                    (pl.sync_used != QO_MOTION_SYNC_PHASE && Ts > tsync * (1.0 + 1e-3) + 1e-6)) {
                    print_error("case %d joint %zu (sync %d): %g common %g ref %g used %d\n", cs, i, (int)js[i], d, Ts,
                                tsync, (int)pl.sync_used);
                    fail();
                }
            }
        }
        /* PHASE joints that got the line move on it: (p_i - p0_i) / d_i is the same for all */
        nunsynced += pl.unsynced != 0;
        if (pl.sync_used == QO_MOTION_SYNC_PHASE) {
            nline++;
            assert_true(nphase > 0);
            for (k = 1; k < 16; k++) {
                float pos[NJ];
                double s = NAN;
                snap(&pl, (float)(T * k / 16.0), pos, NULL, NULL);
                for (i = 0; i < NJ; i++) {
                    if (js[i] != QO_MOTION_SYNC_PHASE || tg[i] == 0.0f) continue;
                    if (s != s) s = pos[i] / tg[i];
                    else if (fabs(pos[i] / tg[i] - s) > 1e-5) {
                        print_error("case %d joint %zu: off the line, s %g vs %g\n", cs, i, pos[i] / tg[i], s);
                        fail();
                    }
                }
            }
        }
        assert_true(T >= 0.0);
    }
    /* the straight line was used in a share of the plans, and the sync gap stayed rare */
    print_message("joint sync: %d of %d plans on a straight line, %d with an unsynced joint\n", nline,
                  (int)ORACLE_GROUPS(400), nunsynced);
    /* shares of the full run; the emulated Cortex-M sample (a few plans) checks the plans only */
    if (ORACLE_GROUPS(400) == 400) {
        assert_true(nline >= 20);
        assert_true(nunsynced <= 4);
    }
}

static void test_joint_sync_args(void **state)
{
    qo_motion_planner_f32 pl;
    qo_motion_joint_f32 jts[2];
    qo_motion_limits_f32 l[2];
    float p0[2] = { 0.0f, 0.0f };
    qo_motion_settings_f32 st = { QO_MOTION_SCURVE, QO_MOTION_SYNC_TIME_IF_NECESSARY };
    (void)state;
    l[0] = l[1] = qo_motion_limits_default;
    assert_int_equal(qo_motion_set_joint_sync_f32(NULL, 0, QO_MOTION_SYNC_TIME), QO_E_NULL);
    assert_int_equal(qo_motion_init_f32(&pl, jts, 2, l, p0, 0.0f, &st), QO_OK);
    assert_int_equal(qo_motion_set_joint_sync_f32(&pl, 2, QO_MOTION_SYNC_TIME), QO_E_RANGE);
    assert_int_equal(qo_motion_set_joint_sync_f32(&pl, 0, (qo_motion_sync)4), QO_E_ARG);
    assert_int_equal(qo_motion_set_joint_sync_f32(&pl, 0, (qo_motion_sync)-1), QO_E_ARG);
    assert_int_equal(jts[0].sync, -1);
    assert_int_equal(qo_motion_set_joint_sync_f32(&pl, 1, QO_MOTION_SYNC_PHASE), QO_OK);
    assert_int_equal(jts[1].sync, (int)QO_MOTION_SYNC_PHASE);
    st.sync = (qo_motion_sync)4;
    assert_int_equal(qo_motion_init_f32(&pl, jts, 2, l, p0, 0.0f, &st), QO_E_ARG);
    assert_int_equal(qo_motion_set_joint_sync_f32(&pl, 0, QO_MOTION_SYNC_TIME), QO_E_STATE);
}

/* A stream of moving setpoints (teleoperation): each re-plan passes through its target state
 * without stopping, continuous in p, v, a, within asymmetric limits. */
static void test_stream_through_states(void **state)
{
    qo_motion_planner_f32 pl;
    qo_motion_joint_f32 jts[2];
    qo_motion_limits_f32 l[2];
    float t = 0.0f, p[2], v[2], a[2], pb[2], vb[2], ab[2], tg[2], vf[2];
    int k;
    size_t i;
    (void)state;
    l[0] = lim_of(2.0f, 8.0f, 80.0f, -1.0f, -4.0f);
    l[1] = lim_of(1.0f, 5.0f, 50.0f, 0.0f, 0.0f);
    init_n(&pl, jts, 2, l, QO_MOTION_SYNC_TIME);
    for (k = 0; k < 200; k++) {
        double s = 0.02 * k;
        tg[0] = (float)(0.5 * sin(s));
        tg[1] = (float)(0.3 * cos(1.3 * s));
        vf[0] = (float)(0.5 * 0.5 * cos(s)); /* d/dt of the setpoint at 0.5 s per unit of s */
        vf[1] = (float)(-0.5 * 0.39 * sin(1.3 * s));
        snap(&pl, t, pb, vb, ab);
        assert_int_equal(qo_motion_set_target_state_f32(&pl, t, tg, vf, NULL, NULL), QO_OK);
        snap(&pl, t, p, v, a);
        for (i = 0; i < 2; i++) {
            mref_lim r = ref_lim_of(&l[i]);
            assert_true(fabs(p[i] - pb[i]) <= 1e-6 * (1.0 + fabs(pb[i])));
            assert_true(fabs(v[i] - vb[i]) <= 1e-6 * r.vmax);
            assert_true(fabs(a[i] - ab[i]) <= 1e-6 * r.amax);
            assert_true(v[i] <= r.vmax * (1.0 + 1e-6) && v[i] >= r.vmin * (1.0 + 1e-6));
            assert_true(a[i] <= r.amax * (1.0 + 1e-6) && a[i] >= r.amin * (1.0 + 1e-6));
        }
        t += 0.01f;
    }
}

/* Joints with target accelerations from `make check-motion`: the first two were 1.37x and
 * 1.79x slower than the reference before the dips with am of either sign; each planned alone
 * (NONE) must be within 0.1 % of the reference. */
static void test_target_state_shapes(void **state)
{
    /* vmax amax jmax vmin amin p0 v0 a0 target vf af */
    static const float k[][11] = {
        { 3.08677292f, 10.4465113f, 60.5358429f, -3.12709069f, -8.9171772f, 1.26687586f, -0.786278486f, 9.55788231f,
          1.51485348f, 1.13608086f, -4.76285744f },
        { 2.54340959f, 14.7162514f, 26.5771179f, -3.59248972f, 0.0f, 1.14524162f, 1.91491199f, -10.9061069f,
          0.010820671f, -1.14858377f, 8.28869438f },
        /* the other way round: the planner's 0.0762 s profile (a0 -> 6.9 -> 0 -> amin, held, ->
         * af) was right and the reference's vm grid missed it (1.70 s): the reference now also
         * scans the junction velocities where a transfer changes shape */
        { 2.90597129f, 16.5567951f, 433.930695f, -4.26396561f, -2.45528555f, 0.000869405747f, 1.79845357f,
          6.56440592f, 0.140540272f, 1.93420422f, 11.1921558f },
        /* check-motion TIME_IF_NECESSARY case 5781 joint 5: 2.018 s where the reference finds
         * 0.809 s (a0 eased from -11.3 to -7.48, then down and up to af): the dip's residual
         * over am in [a0, 0] has two roots between two of its four scan points */
        { 3.4372437f, 2.062994f, 20.7182293f, 0.0f, -15.6111498f, -1.47362924f, 2.52445889f, -11.3011713f,
          -2.19661188f, -3.04818821f, -0.323818952f },
    };
    size_t m;
    (void)state;
    for (m = 0; m < sizeof k / sizeof k[0]; m++) {
        qo_motion_planner_f32 pl;
        qo_motion_joint_f32 jts[1];
        jcase c;
        double tr;
        memset(&c, 0, sizeof c);
        c.lim = lim_of(k[m][0], k[m][1], k[m][2], k[m][3], k[m][4]);
        c.p0 = k[m][5];
        c.v0 = k[m][6];
        c.a0 = k[m][7];
        c.target = k[m][8];
        c.vf = k[m][9];
        c.af = k[m][10];
        tr = ref_time(&c);
        assert_int_equal(plan_cases(&pl, jts, &c, 1, QO_MOTION_SYNC_NONE), QO_OK);
        if (fabs(jts[0].duration - tr) > RELTIME * tr || limit_excess(&pl, 0, 256) > RELLIM) {
            print_case("target state shape", (int)m, 0, &c, jts[0].duration, tr);
            fail();
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reference_closed_form),
        cmocka_unit_test(test_line_checks_fail),
        cmocka_unit_test(test_issue_phase_sync_moving),
        cmocka_unit_test(test_issue_missing_shape),
        cmocka_unit_test(test_issue_large_vmax_jump),
        cmocka_unit_test(test_oracle_none),
        cmocka_unit_test(test_oracle_time),
        cmocka_unit_test(test_oracle_phase),
        cmocka_unit_test(test_oracle_time_if_necessary),
        cmocka_unit_test(test_oracle_wide),
        cmocka_unit_test(test_oracle_stress),
        cmocka_unit_test(test_timing),
        cmocka_unit_test(test_timing_args),
        cmocka_unit_test(test_velocity),
        cmocka_unit_test(test_velocity_args),
        cmocka_unit_test(test_asym_limits_validated),
        cmocka_unit_test(test_target_state_refused),
        cmocka_unit_test(test_after_end),
        cmocka_unit_test(test_joint_sync),
        cmocka_unit_test(test_joint_sync_args),
        cmocka_unit_test(test_stream_through_states),
        cmocka_unit_test(test_target_state_shapes),
    };
    /* e.g. QO_MOTION_ORACLE_FILTER=test_oracle_time: one part of a long check-motion run */
    if (getenv("QO_MOTION_ORACLE_FILTER")) cmocka_set_test_filter(getenv("QO_MOTION_ORACLE_FILTER"));
    return cmocka_run_group_tests(tests, NULL, NULL);
}
