/* Online point-to-point motion, float32. See qorient/motion.h for the contract and the design. */
#include "qorient/motion.h"

#include <float.h>
#include <math.h>

const qo_motion_settings_f32 qo_motion_settings_default = { QO_MOTION_SCURVE, QO_MOTION_SYNC_TIME };
const qo_motion_limits_f32 qo_motion_limits_default = { 1.0f, 1.0f, 1.0f, -INFINITY, INFINITY, 0.0f, 0.0f, 0.0f };

/* One piece of a profile under construction: duration d, jerk j; with seta the acceleration
 * is set to a at its start (TRAPEZOID: acceleration jumps), else it carries on continuously. */
typedef struct mseg {
    float d, j, a, v;
    int seta, setv;
} mseg;

typedef struct mstate {
    float p, v, a;
} mstate;

/* Segments of one plan: velocity change (<= 3) + cruise (1) + stop (<= 3). */
#define MSEGS 7

static void integ(mstate *s, const mseg *g)
{
    float d = g->d;
    if (g->seta) s->a = g->a;
    if (g->setv) s->v = g->v;
    s->p += d * (s->v + d * (0.5f * s->a + d * g->j * (1.0f / 6.0f)));
    s->v += d * (s->a + 0.5f * d * g->j);
    s->a += d * g->j;
}

/* Fastest change from (v0, a0) to (v1, 0) within |a| <= amax (after bringing an a0 beyond it
 * back at jmax) and |j| <= jmax (SCURVE), or at +-amax (TRAPEZOID). Writes <= 3 segments. */
static unsigned vchange(int scurve, float v0, float a0, float v1, float amax, float jmax, mseg *out)
{
    float vnat, s, a0s, dv, ap, t1, t2, t3, dv1, dv3;
    int capped = 0;
    if (!scurve) {
        float d = v1 - v0;
        out[0].d = fabsf(d) / amax;
        out[0].j = 0.0f;
        out[0].a = d >= 0.0f ? amax : -amax;
        out[0].seta = 1;
        out[0].setv = 0;
        return 1;
    }
    /* Velocity reached by ramping a0 straight to zero: v1 above it needs a positive pulse. */
    vnat = v0 + a0 * fabsf(a0) / (2.0f * jmax);
    s = (v1 >= vnat) ? 1.0f : -1.0f;
    a0s = s * a0;
    dv = s * (v1 - v0);
    if (a0s >= amax) {
        ap = amax;
        capped = 1;
    } else {
        /* Peak of a ramp-up / ramp-down pulse: dv = (2 ap^2 - a0s^2) / (2 jmax). */
        float ap2 = jmax * dv + 0.5f * a0s * a0s;
        ap = ap2 > 0.0f ? sqrtf(ap2) : 0.0f;
        if (ap >= amax) {
            ap = amax;
            capped = 1;
        }
        if (ap < a0s) ap = a0s; /* rounding only: dv >= a0s^2/(2 jmax) when a0s > 0 */
    }
    t1 = fabsf(ap - a0s) / jmax;
    dv1 = 0.5f * (a0s + ap) * t1;
    t3 = ap / jmax;
    dv3 = 0.5f * ap * t3;
    t2 = (capped && ap > 0.0f) ? (dv - dv1 - dv3) / ap : 0.0f;
    if (!(t2 > 0.0f)) t2 = 0.0f;
    out[0].d = t1;
    out[0].j = ap >= a0s ? s * jmax : -s * jmax;
    out[0].seta = out[0].setv = 0;
    out[1].d = t2;
    out[1].j = 0.0f;
    out[1].seta = out[1].setv = 0;
    out[2].d = t3;
    out[2].j = -s * jmax;
    out[2].seta = out[2].setv = 0;
    return 3;
}

/* Profile through extremum velocity vc with cruise tc, from (v0, a0). */
static unsigned build(int scurve, float v0, float a0, float vc, float tc, const qo_motion_limits_f32 *l,
                      mseg *out)
{
    unsigned n = vchange(scurve, v0, a0, vc, l->amax, l->jmax, out);
    /* The cruise (and the stop after it) starts from exactly (vc, 0): rounding gathered
     * while the velocity change passed through large values must not be carried over a long
     * cruise into the end position. */
    out[n].d = tc;
    out[n].j = 0.0f;
    out[n].a = 0.0f;
    out[n].v = vc;
    out[n].seta = out[n].setv = 1;
    n++;
    n += vchange(scurve, vc, 0.0f, 0.0f, l->amax, l->jmax, out + n);
    return n;
}

/* The "dip" shape, the profiles without an acceleration zero before the stop: the acceleration
 * ramps from a0 straight to am (between 0 and a0), then the fastest pulse from (v1, am) to rest
 * (it ramps back away from zero, may hold at +-amax, and ramps to zero). E.g. a joint moving
 * toward a near target while braking eases the braking first to travel further, then brakes
 * harder: "ramp down, up to amax, hold, ramp to zero" of issue 11. With am = 0 it is the
 * extremum-velocity profile through vn; with am = a0 the direct stop. The velocity never leaves
 * [-|vn|, |vn|] on the way to rest, so it stays within vmax when the start does. SCURVE only. */
static unsigned build_dip(float v0, float a0, float am, const qo_motion_limits_f32 *l, mseg *out)
{
    float j = am >= a0 ? l->jmax : -l->jmax, d = fabsf(am - a0) / l->jmax;
    float v1 = v0 + d * (a0 + 0.5f * d * j);
    out[0].d = d;
    out[0].j = j;
    out[0].seta = out[0].setv = 0;
    return 1 + vchange(1, v1, am, 0.0f, l->amax, l->jmax, out + 1);
}

/* A joint's solved profile: family 0 = extremum velocity x with cruise tc (build), family 1 =
 * dip to acceleration x (build_dip). */
static unsigned build_fam(int scurve, int fam, float v0, float a0, float x, float tc,
                          const qo_motion_limits_f32 *l, mseg *out)
{
    if (fam == 1) return build_dip(v0, a0, x, l, out);
    return build(scurve, v0, a0, x, tc, l, out);
}

/* Displacement and duration of segments g[0..n) from velocity v0, acceleration a0. */
static void eval_segs(float v0, float a0, const mseg *g, unsigned n, float *disp, float *dur)
{
    mstate s;
    unsigned i;
    float t = 0.0f;
    s.p = 0.0f;
    s.v = v0;
    s.a = a0;
    for (i = 0; i < n; i++) {
        integ(&s, &g[i]);
        t += g[i].d;
    }
    *disp = s.p;
    *dur = t;
}

/* Displacement and duration of the zero-cruise profile through vc. */
static void eval_vc(int scurve, float v0, float a0, float vc, const qo_motion_limits_f32 *l, float *disp,
                    float *dur)
{
    mseg g[MSEGS];
    unsigned n = build(scurve, v0, a0, vc, 0.0f, l, g);
    eval_segs(v0, a0, g, n, disp, dur);
}

/* What a root search evaluates at extremum velocity vc. mode 0 (minimum time): displacement of
 * the zero-cruise profile minus dp, aux = its duration. mode 1 (time sync): position reached in
 * exactly T with the cruise filling the rest, minus dp, aux = that cruise time. mode 2: the dip
 * profile to acceleration vc (build_dip), displacement minus dp, aux = its duration. */
typedef struct rctx {
    int scurve, mode;
    float v0, a0, dp, T;
    const qo_motion_limits_f32 *l;
} rctx;

static rctx rctx_make(int scurve, int mode, float v0, float a0, float dp, float T, const qo_motion_limits_f32 *l)
{
    rctx c = { scurve, mode, v0, a0, dp, T, l };
    return c;
}

static float resid(const rctx *c, float vc, float *aux)
{
    float d, t;
    if (c->mode == 2) {
        mseg g[4];
        unsigned n = build_dip(c->v0, c->a0, vc, c->l, g);
        eval_segs(c->v0, c->a0, g, n, &d, aux);
        return d - c->dp;
    }
    eval_vc(c->scurve, c->v0, c->a0, vc, c->l, &d, &t);
    if (c->mode == 0) {
        *aux = t;
        return d - c->dp;
    }
    *aux = c->T - t;
    return d + vc * (c->T - t) - c->dp;
}

/* Root of resid between a and b, whose residuals fa, fb have opposite signs. Illinois method:
 * regula falsi that halves the stale end's residual, so it keeps the bracket (like bisection,
 * never diverges) but converges superlinearly; at most QO_MOTION_BISECT_ITERS steps, stops when
 * the bracket is 2 float32 ulps wide. Returns the end with the smaller true |residual|. */
static float root(const rctx *c, float a, float b, float fa, float fb, float xa, float xb, float *aux,
                  float *fres)
{
    float ga = fa, gb = fb; /* Illinois-weighted copies */
    int side = 0;
    unsigned it;
    for (it = 0; it < QO_MOTION_BISECT_ITERS; it++) {
        float m = a - ga * (b - a) / (gb - ga), fm, xm;
        if (!(m > fminf(a, b) && m < fmaxf(a, b))) m = 0.5f * (a + b);
        if (m == a || m == b) break;
        fm = resid(c, m, &xm);
        /* Done once the position misses by float32 rounding of the move (what the 2-ulp bracket
         * below would give at best), on the side a cruise can absorb in mode 0. */
        if (fm == 0.0f || (fabsf(fm) <= 1.2e-7f * (fabsf(c->dp) + fabsf(m) * (c->mode == 1 ? c->T : xm)) &&
                           (c->mode != 0 || fm * m <= 0.0f))) {
            *aux = xm;
            *fres = fm;
            return m;
        }
        if ((fm < 0.0f) == (fb < 0.0f)) {
            b = m;
            fb = gb = fm;
            xb = xm;
            if (side == -1) ga *= 0.5f;
            side = -1;
        } else {
            a = m;
            fa = ga = fm;
            xa = xm;
            if (side == 1) gb *= 0.5f;
            side = 1;
        }
        /* 2 ulps of the larger end, and no finer than 2.4e-10 vmax near vc = 0 (the residual's
         * slope there is bounded, so that is far below float32 resolution of the result) */
        if (fabsf(b - a) <= 2.4e-7f * fmaxf(fmaxf(fabsf(a), fabsf(b)), 1e-3f * (c->mode == 2 ? c->l->amax : c->l->vmax)))
            break;
    }
    /* Mode 0: prefer the end a short cruise can correct (residual opposite in sign to the
     * velocity: the profile falls short); near vn the displacement has a square-root kink, so
     * 2 ulps of vc can still miss the target by more than float resolution of p. */
    if (c->mode == 0 && fabsf(a) > 1e-3f * c->l->vmax && fabsf(b) > 1e-3f * c->l->vmax) {
        if (fa * a <= 0.0f) {
            *aux = xa;
            *fres = fa;
            return a;
        }
        if (fb * b <= 0.0f) {
            *aux = xb;
            *fres = fb;
            return b;
        }
    }
    if (fabsf(fa) <= fabsf(fb)) {
        *aux = xa;
        *fres = fa;
        return a;
    }
    *aux = xb;
    *fres = fb;
    return b;
}

/* Keeps the candidate profile of smallest duration. */
static void consider(float vc, float tc, float dur, float *bv, float *bt, float *bd)
{
    if (dur < *bd) {
        *bv = vc;
        *bt = tc;
        *bd = dur;
    }
}

/* Cube root of a >= 0 (0 for a <= 0 or NaN): a first guess from the exponent bits (Kahan's
 * division of the biased exponent by 3), then Newton steps y <- (2y + a/y^2)/3, quadratic from
 * within a few percent. Not libm's cbrtf, so every target gives the same bits (the caller
 * checks the closed form's residual and falls back to the root search on any doubt). */
static float cbrt_pos(float a)
{
    union { float f; uint32_t u; } b;
    float y;
    int k;
    if (!(a > 0.0f) || a > FLT_MAX) return a > FLT_MAX ? a : 0.0f;
    b.f = a;
    b.u = b.u / 3u + 709921077u;
    y = b.f;
    for (k = 0; k < 4; k++) y = (2.0f * y + a / (y * y)) / 3.0f;
    return y;
}

/* Rest-to-rest SCURVE in closed form (the common case: a joint that has arrived). Peak velocity
 * x >= 0 of the symmetric profile covering distance D: with the acceleration limit reached
 * (x >= A^2/J) D = x (x/A + A/J), else D = 2 x sqrt(x/J). Used as a fast path: the profile's
 * integrated displacement is then checked (rest_fix), and any doubt goes to the root search. */
static float rest_peak(float D, const qo_motion_limits_f32 *l, float *slope)
{
    float V = l->vmax, A = l->amax, J = l->jmax, aj = A / J, x, t;
    if (D >= 2.0f * A * aj * aj) {
        x = 0.5f * A * (sqrtf(aj * aj + 4.0f * D / A) - aj);
        *slope = 2.0f * x / A + aj;
    } else {
        t = cbrt_pos(0.5f * D * sqrtf(J));
        x = t * t;
        *slope = 3.0f * sqrtf(x / J);
    }
    if (x > V) x = V;
    return x;
}

/* Settles a closed-form peak x (sign of the move) by its integrated residual f: a profile that
 * falls short gets the cruise -f/x; one that overshoots is lowered by 2 f / slope (twice the
 * linear step, so that it falls short) and checked again. Returns 0 (use the root search) if
 * the residual is not at float32 rounding level. */
static int rest_fix(const rctx *c, float x, float slope, float tol, float *vc, float *tc, float *dur)
{
    int k;
    for (k = 0; k < 2; k++) {
        float t, f = resid(c, x, &t);
        if (!(fabsf(f) <= tol)) return 0;
        if (f * x <= 0.0f) {
            *vc = x;
            *tc = x != 0.0f ? (c->mode == 0 ? -f / x : t) : 0.0f;
            *dur = c->mode == 0 ? t + *tc : c->T;
            return *tc >= 0.0f;
        }
        x -= 2.0f * f / slope;
    }
    return 0;
}

static int rest_min(float dp, const qo_motion_limits_f32 *l, float *vc, float *tc, float *dur)
{
    rctx c = rctx_make(1, 0, 0.0f, 0.0f, dp, 0.0f, l);
    float slope, x = rest_peak(fabsf(dp), l, &slope);
    if (dp < 0.0f) x = -x;
    return rest_fix(&c, x, slope, 4e-6f * fabsf(dp), vc, tc, dur);
}

/* Rest-to-rest SCURVE profile of exactly duration T: D = x (T - tacc(x)), the smaller root,
 * tacc = x/A + A/J (hold) or 2 sqrt(x/J); the second by safeguarded Newton on u = sqrt(x). */
static int rest_time(float dp, float T, const qo_motion_limits_f32 *l, float *vc, float *tc)
{
    rctx c = rctx_make(1, 1, 0.0f, 0.0f, dp, T, l);
    float D = fabsf(dp), A = l->amax, J = l->jmax, aj = A / J, Tp = T - aj, disc = Tp * Tp - 4.0f * D / A, x;
    float slope;
    if (Tp > 0.0f && disc >= 0.0f && (x = 2.0f * D / (Tp + sqrtf(disc))) >= A * aj) {
        slope = Tp - 2.0f * x / A;
    } else {
        float sj = sqrtf(J), lo = sqrtf(D / T), hi = fminf(T * sj / 3.0f, sqrtf(l->vmax)), u = lo;
        unsigned it;
        if (!(lo <= hi)) return 0;
        for (it = 0; it < 12; it++) {
            float g = u * u * (T - 2.0f * u / sj) - D, dg = u * (2.0f * T - 6.0f * u / sj), un;
            if (g < 0.0f) lo = u;
            else hi = u;
            un = dg > 0.0f ? u - g / dg : 0.5f * (lo + hi);
            if (!(un > lo && un < hi)) un = 0.5f * (lo + hi);
            if (un == u) break;
            u = un;
        }
        x = u * u;
        slope = T - 3.0f * u / sj;
    }
    if (!(slope > 0.0f)) return 0;
    if (dp < 0.0f) x = -x;
    return rest_fix(&c, x, slope, 4e-6f * (D + fabsf(x) * T), vc, tc, &D);
}

/* Fastest dip profile (build_dip) with displacement dp: the residual is scanned at
 * QO_MOTION_DIP_SCAN + 1 points of am in [0, a0] (its ends are the extremum-velocity profile
 * through vn and the direct stop) and every sign change is solved. Returns 0 if none. */
#define QO_MOTION_DIP_SCAN 1
static int solve_dip(float v0, float a0, float dp, float e0, float e1, const qo_motion_limits_f32 *l, float *am,
                     float *dur)
{
    rctx c;
    float x[QO_MOTION_DIP_SCAN + 1], f[QO_MOTION_DIP_SCAN + 1], t[QO_MOTION_DIP_SCAN + 1];
    float vb = fmaxf(l->vmax, fabsf(v0 + a0 * fabsf(a0) / (2.0f * l->jmax))) * (1.0f + 1e-6f);
    unsigned k;
    c = rctx_make(1, 2, v0, a0, dp, 0.0f, l);
    *am = 0.0f;
    *dur = INFINITY;
    for (k = 0; k <= QO_MOTION_DIP_SCAN; k++) {
        x[k] = e0 + (e1 - e0) * (float)k / (float)QO_MOTION_DIP_SCAN;
        f[k] = resid(&c, x[k], &t[k]);
    }
    for (k = 0; k <= QO_MOTION_DIP_SCAN; k++) {
        float r = x[k], tr = t[k], fr = f[k];
        if (fr != 0.0f) {
            if (k == QO_MOTION_DIP_SCAN || f[k + 1] == 0.0f || (fr < 0.0f) == (f[k + 1] < 0.0f)) continue;
            r = root(&c, x[k], x[k + 1], f[k], f[k + 1], t[k], t[k + 1], &tr, &fr);
            /* no cruise absorbs a residual here: keep only a root to float precision */
            if (fabsf(fr) > 1e-6f * (fabsf(dp) + (fabsf(v0) + l->vmax) * tr)) continue;
        }
        {
            /* ramping a0 away from zero first drives the velocity further: its extremum, where
             * the pulse to rest crosses a = 0, must stay within vmax (or the start's own reach) */
            float d = fabsf(r - a0) / l->jmax, j = r >= a0 ? l->jmax : -l->jmax;
            float v1 = v0 + d * (a0 + 0.5f * d * j);
            if (fabsf(v1 + r * fabsf(r) / (2.0f * l->jmax)) > vb) continue;
        }
        if (tr < *dur) {
            *dur = tr;
            *am = r;
        }
    }
    return *dur < INFINITY;
}

/* Minimum-time extremum velocity vc and cruise tc for displacement dp (see motion.h).
 * The displacement D(vc) of the zero-cruise profile is monotone on [-vmax, min(0, vn)] and on
 * [max(0, vn), vmax], vn being the velocity the start reaches by ramping a0 to zero; between
 * 0 and vn the profile stops in two stages (velocity change to vc, then stop) and D has one
 * interior extremum (located by golden section). Every monotone piece whose ends bracket dp
 * gives a root; the root (or the cruise at +-vmax) of smallest duration wins. */
static void solve_min(int scurve, float v0, float a0, float dp, const qo_motion_limits_f32 *l, float *vc,
                      float *tc, int *fam, float *dur)
{
    rctx c;
    float pt[5], fp[5], xp[5], vn, bv = 0.0f, bt = 0.0f, bd = INFINITY, x, fz = NAN, fn0 = NAN, xn0 = 0.0f, dipd = NAN;
    unsigned np = 0, i;
    *fam = 0;
    if (scurve && v0 == 0.0f && a0 == 0.0f && rest_min(dp, l, vc, tc, dur)) return;
    c = rctx_make(scurve, 0, v0, a0, dp, 0.0f, l);
    vn = scurve ? v0 + a0 * fabsf(a0) / (2.0f * l->jmax) : v0;
    vn = fminf(fmaxf(vn, -l->vmax), l->vmax);
    pt[np++] = -l->vmax;
    if (fminf(0.0f, vn) > pt[np - 1]) pt[np++] = fminf(0.0f, vn);
    if (fmaxf(0.0f, vn) > pt[np - 1]) pt[np++] = fmaxf(0.0f, vn);
    if (l->vmax > pt[np - 1]) pt[np++] = l->vmax;
    for (i = 0; i < np; i++) {
        fp[i] = resid(&c, pt[i], &xp[i]);
        if (pt[i] == 0.0f) fz = fp[i];
        if (pt[i] == vn) {
            fn0 = fp[i];
            xn0 = xp[i];
        }
    }
    /* Cruising at +-vmax when even the fastest peak falls short. */
    if (fp[np - 1] <= 0.0f) consider(l->vmax, -fp[np - 1] / l->vmax, xp[np - 1] - fp[np - 1] / l->vmax, &bv, &bt, &bd);
    if (fp[0] >= 0.0f) consider(-l->vmax, fp[0] / l->vmax, xp[0] + fp[0] / l->vmax, &bv, &bt, &bd);
    /* Outer pieces first: a single velocity extremum beyond vn (or a reversal) reaches dp
     * faster than stopping in two stages, so the middle piece is searched only when neither
     * outer piece brackets dp (e.g. a0 already braking, dp between the two stops' reach). */
    for (i = 0; i + 1 < np; i++) {
        int outer = pt[i + 1] <= fminf(0.0f, vn) || pt[i] >= fmaxf(0.0f, vn);
        if (!outer) continue;
        if (fp[i] == 0.0f) consider(pt[i], 0.0f, xp[i], &bv, &bt, &bd);
        if (fp[i + 1] == 0.0f) consider(pt[i + 1], 0.0f, xp[i + 1], &bv, &bt, &bd);
        if (fp[i] != 0.0f && fp[i + 1] != 0.0f && (fp[i] < 0.0f) != (fp[i + 1] < 0.0f)) {
            float fr, r = root(&c, pt[i], pt[i + 1], fp[i], fp[i + 1], xp[i], xp[i + 1], &x, &fr);
            float tcr = (r != 0.0f && fr * r < 0.0f) ? -fr / r : 0.0f;
            consider(r, tcr, x + tcr, &bv, &bt, &bd);
        }
    }
    /* The dip family runs from the extremum-velocity profile through vn (am = 0) to the direct
     * stop (vc = 0, am = a0): searched when those two bracket dp, i.e. when the two-stage
     * middle piece below would be; its profiles are then never shorter (checked against the
     * reference in tests/test_motion_oracle.c), so that piece is searched only without a dip. */
    if (scurve && a0 != 0.0f && vn != 0.0f && (fz < 0.0f) != (fn0 < 0.0f) && fz == fz && fn0 == fn0) {
        float am, dd;
        if (solve_dip(v0, a0, dp, 0.0f, a0, l, &am, &dd) && dd < bd) {
            bv = am;
            bt = 0.0f;
            bd = dipd = dd;
            *fam = 1;
        }
    }
    /* The other orientation: a0 ramped further away from zero first (to am between a0 and
     * +-amax), then the pulse to rest; from the direct stop (am = a0) to am = +-amax. Its far
     * end is evaluated only here; solved when it brackets dp with the direct stop. */
    if (scurve && a0 != 0.0f && fabsf(a0) < l->amax && fz == fz) {
        float aw = a0 > 0.0f ? l->amax : -l->amax, am, dd, fw, tw;
        rctx cw = rctx_make(1, 2, v0, a0, dp, 0.0f, l);
        fw = resid(&cw, aw, &tw);
        if (fw != fw || (fw < 0.0f) != (fz < 0.0f) || fw == 0.0f) {
            if (solve_dip(v0, a0, dp, a0, aw, l, &am, &dd) && dd < bd) {
                bv = am;
                bt = 0.0f;
                bd = dipd = dd;
                *fam = 1;
            }
        }
    }
    /* The two-stage middle piece: split it at its extremum when it has one. */
    if (!(bd < INFINITY) && vn != 0.0f && fabsf(vn) > 1e-6f * l->vmax) {
        unsigned k = 1; /* pt[k-1], pt[k] = the middle piece [min(0, vn), max(0, vn)] */
        float lo, hi, fm, xm;
        while (k + 1 < np && pt[k] != fmaxf(0.0f, vn)) k++;
        lo = pt[k - 1];
        hi = pt[k];
        float dlo = fp[k - 1], dhi = fp[k];
        fm = resid(&c, 0.5f * (lo + hi), &xm);
        if (fm > fmaxf(dlo, dhi) || fm < fminf(dlo, dhi)) {
            const float g = 0.381966f;
            float sgn = fm > fmaxf(dlo, dhi) ? 1.0f : -1.0f, a = lo, b = hi;
            float x1 = a + g * (b - a), x2 = b - g * (b - a), f1, f2, dum;
            unsigned it;
            f1 = sgn * resid(&c, x1, &dum);
            f2 = sgn * resid(&c, x2, &dum);
            for (it = 0; it < 24; it++) {
                if (f1 > f2) {
                    b = x2;
                    x2 = x1;
                    f2 = f1;
                    x1 = a + g * (b - a);
                    f1 = sgn * resid(&c, x1, &dum);
                } else {
                    a = x1;
                    x1 = x2;
                    f1 = f2;
                    x2 = b - g * (b - a);
                    f2 = sgn * resid(&c, x2, &dum);
                }
            }
            for (i = np; i > k; i--) {
                pt[i] = pt[i - 1];
                fp[i] = fp[i - 1];
                xp[i] = xp[i - 1];
            }
            pt[k] = f1 > f2 ? x1 : x2;
            fp[k] = resid(&c, pt[k], &xp[k]);
            np++;
        }
    }
    if (!(bd < INFINITY)) {
        for (i = 0; i < np; i++) {
            if (fp[i] == 0.0f) consider(pt[i], 0.0f, xp[i], &bv, &bt, &bd);
            if (i + 1 < np && fp[i] != 0.0f && fp[i + 1] != 0.0f && (fp[i] < 0.0f) != (fp[i + 1] < 0.0f)) {
                float fr, r = root(&c, pt[i], pt[i + 1], fp[i], fp[i + 1], xp[i], xp[i + 1], &x, &fr);
                float tcr = (r != 0.0f && fr * r < 0.0f) ? -fr / r : 0.0f;
                consider(r, tcr, x + tcr, &bv, &bt, &bd);
            }
        }
    }
    {
        /* A root a float ulp away from the velocity the start state reaches anyway (vn)
         * would add a pulse of 2 sqrt(eps / jmax) seconds: take vn itself when it is a root to
         * float precision, and let a short cruise absorb the residual when its sign allows. */
        float fn = fn0, xn = xn0, tn = 0.0f;
        if (fn != fn) fn = resid(&c, vn, &xn); /* vn was not among the points */
        if (fabsf(fn) <= 2e-7f * (fabsf(dp) + (fabsf(v0) + l->vmax) * xn)) {
            if (vn != 0.0f && -fn / vn >= 0.0f) tn = -fn / vn;
            /* preferred over a candidate up to 1e-6 relative shorter */
            if (xn + tn - 1e-6f * xn < bd) {
                bv = vn;
                bt = tn;
                bd = xn + tn;
            }
        }
    }
    if (bd != dipd) *fam = 0; /* a later candidate (vn) was shorter */
    if (!(bd < INFINITY)) {
        /* Not reachable for finite inputs (the pieces cover [-vmax, vmax] and the cruises
         * the rest); stop as a defined answer. */
        bv = 0.0f;
        bt = 0.0f;
    }
    *vc = bv;
    *tc = bt;
    *dur = bd < INFINITY ? bd : 0.0f;
}

/* A profile of exactly duration T >= the minimum. First bracket: lower |vc| from vc* toward 0
 * (the residual changes sign on [0, vc*] when the displacement is monotone there). When it
 * does not (the two-stage piece between 0 and vn is not monotone), scan [-vmax, vmax] at
 * QO_MOTION_SYNC_SCAN points plus 0, vn and vc* and take the sign change, with a non-negative
 * cruise, nearest vc*. Returns 0 if no such profile was found. */
#define QO_MOTION_SYNC_SCAN 9
static int solve_time(int scurve, float v0, float a0, float dp, float vcs, float T, const qo_motion_limits_f32 *l,
                      float *vc, float *tc)
{
    rctx c;
    float fa, fb, tca, tcb, fr;
    float xs[QO_MOTION_SYNC_SCAN + 3], gs[QO_MOTION_SYNC_SCAN + 3], ts[QO_MOTION_SYNC_SCAN + 3];
    float bestd = INFINITY;
    unsigned n = 0, i, k;
    if (scurve && v0 == 0.0f && a0 == 0.0f && rest_time(dp, T, l, vc, tc)) return 1;
    c = rctx_make(scurve, 1, v0, a0, dp, T, l);
    fa = resid(&c, 0.0f, &tca);
    fb = resid(&c, vcs, &tcb);
    if (fa != 0.0f && (fa < 0.0f) != (fb < 0.0f)) {
        *vc = root(&c, 0.0f, vcs, fa, fb, tca, tcb, tc, &fr);
        if (*tc >= -1e-5f * T) {
            if (*tc < 0.0f) *tc = 0.0f; /* rounding */
            return 1;
        }
    }
    /* Scan: sorted points, the sign changes whose root has a non-negative cruise. */
    {
        float vn = scurve ? v0 + a0 * fabsf(a0) / (2.0f * l->jmax) : v0;
        xs[n++] = 0.0f;
        xs[n++] = vcs;
        xs[n++] = fminf(fmaxf(vn, -l->vmax), l->vmax);
        for (k = 0; k < QO_MOTION_SYNC_SCAN; k++)
            xs[n++] = -l->vmax + 2.0f * l->vmax * (float)k / (float)(QO_MOTION_SYNC_SCAN - 1);
        for (i = 1; i < n; i++) {
            float x = xs[i];
            k = i;
            while (k > 0 && xs[k - 1] > x) {
                xs[k] = xs[k - 1];
                k--;
            }
            xs[k] = x;
        }
        for (i = 0; i < n; i++) gs[i] = resid(&c, xs[i], &ts[i]);
        for (i = 0; i + 1 < n; i++) {
            float r, tr;
            if (xs[i] == xs[i + 1]) continue;
            if (gs[i] == 0.0f && ts[i] >= 0.0f) {
                r = xs[i];
                tr = ts[i];
            } else if (gs[i] != 0.0f && gs[i + 1] != 0.0f && (gs[i] < 0.0f) != (gs[i + 1] < 0.0f)) {
                r = root(&c, xs[i], xs[i + 1], gs[i], gs[i + 1], ts[i], ts[i + 1], &tr, &fr);
                if (tr < -1e-5f * T) continue;
                if (tr < 0.0f) tr = 0.0f;
            } else {
                continue;
            }
            if (fabsf(r - vcs) < bestd) {
                bestd = fabsf(r - vcs);
                *vc = r;
                *tc = tr;
            }
        }
    }
    if (bestd < INFINITY) return 1;
    /* Stop, then wait at rest, if the minimum solve itself was a stop (vc* ~ 0). */
    *vc = 0.0f;
    *tc = tca;
    return tca >= 0.0f && fabsf(fa) <= 1e-4f * (fabsf(dp) + l->vmax * T);
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
        integ(&s, &g[i]);
        t += g[i].d;
    }
    jt->final = final;
    jt->duration = t;
}

static mstate joint_state(const qo_motion_joint_f32 *jt, float tau)
{
    mstate s;
    unsigned k;
    const qo_motion_phase_f32 *ph;
    if (jt->nph == 0 || tau >= jt->duration) {
        s.p = jt->final;
        s.v = 0.0f;
        s.a = 0.0f;
        if (jt->vend != 0.0f && tau > jt->duration) {
            /* velocity interface: the joint keeps its target velocity after the last phase */
            s.p = jt->final + jt->vend * (tau - jt->duration);
            s.v = jt->vend;
        }
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

static int limits_ok(const qo_motion_limits_f32 *l)
{
    if (!limit_in_range(l->vmax) || !limit_in_range(l->amax) || !limit_in_range(l->jmax)) return 0;
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
        if (!pos_in_range(jt->final) || !isfinite(jt->duration) || !isfinite(jt->vend)) return 0;
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
        jt->final = jt->goal = jt->w_p;
        jt->duration = 0.0f;
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

/* Samples every joint at t_now into its scratch state and moves t0 there. */
static void capture(qo_motion_planner_f32 *pl, float t_now)
{
    size_t i;
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        mstate s = joint_state(jt, t_now - pl->t0);
        if (!(pos_in_range(s.p) && isfinite(s.v) && isfinite(s.a))) {
            s.p = jt->final; /* not expected for a checked plan: its end, at rest */
            s.v = s.a = 0.0f;
        }
        jt->w_p = s.p;
        jt->w_v = s.v;
        jt->w_a = pl->settings.profile == QO_MOTION_SCURVE ? s.a : 0.0f;
        jt->vend = 0.0f; /* every plan made from here ends at rest unless it says otherwise */
    }
    pl->t0 = t_now;
}

/* Velocity interface and safety stop: every joint from its captured state to (w_vg, 0) as fast
 * as its limits allow, then on at w_vg (a brake: w_vg = 0, at rest there). No sync. The end
 * positions become the goals. */
static void plan_velocity(qo_motion_planner_f32 *pl)
{
    size_t i;
    int sc = pl->settings.profile == QO_MOTION_SCURVE;
    float dur = 0.0f;
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        mseg g[3];
        mstate s;
        unsigned k, n;
        s.p = jt->w_p;
        s.v = jt->w_v;
        s.a = jt->w_a;
        n = (jt->w_v == jt->w_vg && jt->w_a == 0.0f) ? 0 : vchange(sc, jt->w_v, jt->w_a, jt->w_vg, jt->lim.amax, jt->lim.jmax, g);
        for (k = 0; k < n; k++) integ(&s, &g[k]);
        load(jt, jt->w_p, jt->w_v, jt->w_a, g, n, s.p);
        jt->vend = jt->w_vg;
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
    for (i = 0; i < pl->n; i++) pl->joints[i].w_vg = 0.0f;
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

/* Largest |v|, |a|, |j| of a loaded plan: at phase ends, and |v| also where the acceleration
 * crosses zero inside a phase (its only interior extremum). */
static void peaks(const qo_motion_joint_f32 *jt, float *pv, float *pa, float *pj)
{
    unsigned k;
    *pv = *pa = *pj = 0.0f;
    for (k = 0; k < jt->nph; k++) {
        const qo_motion_phase_f32 *ph = &jt->ph[k];
        float d = ph->d, a1 = ph->a + d * ph->j, v1 = ph->v + d * (ph->a + 0.5f * d * ph->j);
        *pj = fmaxf(*pj, fabsf(ph->j));
        *pa = fmaxf(*pa, fmaxf(fabsf(ph->a), fabsf(a1)));
        *pv = fmaxf(*pv, fmaxf(fabsf(ph->v), fabsf(v1)));
        if ((ph->a < 0.0f) != (a1 < 0.0f) && ph->j != 0.0f) {
            float tz = -ph->a / ph->j;
            if (tz > 0.0f && tz < d) *pv = fmaxf(*pv, fabsf(ph->v + tz * (ph->a + 0.5f * tz * ph->j)));
        }
    }
}

/* Straight-line plan if every (v, a) is proportional to the displacement; 0 if not possible. */
static int plan_phase(qo_motion_planner_f32 *pl)
{
    size_t i, r = 0;
    int sc = pl->settings.profile == QO_MOTION_SCURVE;
    float dr = 0.0f, kv, ka, vc, tc;
    qo_motion_limits_f32 ls;
    qo_motion_joint_f32 unit;
    mseg g[MSEGS];
    unsigned n;
    int fam;
    float pv, pa, pj;
    for (i = 0; i < pl->n; i++) {
        if (fabsf(pl->joints[i].w_d) > dr) {
            dr = fabsf(pl->joints[i].w_d);
            r = i;
        }
    }
    if (dr == 0.0f) return 0;
    kv = pl->joints[r].w_v / pl->joints[r].w_d;
    ka = pl->joints[r].w_a / pl->joints[r].w_d;
    ls = qo_motion_limits_default;
    ls.vmax = ls.amax = ls.jmax = INFINITY;
    for (i = 0; i < pl->n; i++) {
        const qo_motion_joint_f32 *jt = &pl->joints[i];
        float d = jt->w_d, ad = fabsf(d);
        if (fabsf(jt->w_v - kv * d) > 1e-6f * fmaxf(jt->lim.vmax, fabsf(jt->w_v))) return 0;
        if (fabsf(jt->w_a - ka * d) > 1e-6f * fmaxf(jt->lim.amax, fabsf(jt->w_a))) return 0;
        if (ad == 0.0f) continue;
        ls.vmax = fminf(ls.vmax, jt->lim.vmax / ad);
        ls.amax = fminf(ls.amax, jt->lim.amax / ad);
        ls.jmax = fminf(ls.jmax, jt->lim.jmax / ad);
    }
    /* The scalar profile's limits are ratios limit / |d|: a tiny d makes them so large that
     * the unit solve's products (amax^2 / jmax...) overflow; such a plan goes per joint. */
    if (!(limit_in_range(ls.vmax) && limit_in_range(ls.amax) && limit_in_range(ls.jmax))) return 0;
    solve_min(sc, kv, ka, 1.0f, &ls, &vc, &tc, &fam, &pv);
    n = build_fam(sc, fam, kv, ka, vc, tc, &ls, g);
    load(&unit, 0.0f, kv, ka, g, n, 1.0f);
    /* a straight line has one duration: with duration rules that would change it, use TIME */
    if (timed(pl, unit.duration) != unit.duration) return 0;
    /* The scalar limits keep each joint's own limits only where the unit profile stays within
     * its scalar limits; from a moving start it may not (the shared jerk min(jmax_i / |d_i|)
     * can be too weak to brake a joint's initial acceleration in time): check the straight line
     * against every joint's limits (or its start values beyond them) before using it. */
    peaks(&unit, &pv, &pa, &pj);
    for (i = 0; i < pl->n; i++) {
        const qo_motion_joint_f32 *jt = &pl->joints[i];
        float ad = fabsf(jt->w_d), tol = 1.0f + 1e-6f;
        float vb = fmaxf(jt->lim.vmax, fabsf(jt->w_v) + jt->w_a * jt->w_a / (2.0f * jt->lim.jmax));
        float ab = fmaxf(jt->lim.amax, fabsf(jt->w_a));
        if (ad * pv > vb * tol || ad * pa > ab * tol || (sc && ad * pj > jt->lim.jmax * tol)) return 0;
    }
    pl->duration = unit.duration;
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        float d = jt->w_d;
        unsigned k;
        if (d == 0.0f) {
            jt->nph = 0;
            jt->final = jt->w_p;
            jt->duration = 0.0f;
            continue;
        }
        jt->nph = unit.nph;
        for (k = 0; k < unit.nph; k++) {
            jt->ph[k].t = unit.ph[k].t;
            jt->ph[k].d = unit.ph[k].d;
            jt->ph[k].p = jt->w_p + d * unit.ph[k].p;
            jt->ph[k].v = d * unit.ph[k].v;
            jt->ph[k].a = d * unit.ph[k].a;
            jt->ph[k].j = d * unit.ph[k].j;
        }
        jt->final = jt->w_p + d;
        jt->duration = unit.duration;
    }
    pl->sync_used = QO_MOTION_SYNC_PHASE;
    return 1;
}

/* Plans every joint from its captured state toward its goal with the planner's settings. */
static void plan_goals(qo_motion_planner_f32 *pl)
{
    size_t i;
    int sc = pl->settings.profile == QO_MOTION_SCURVE;
    float T = 0.0f, Tj;
    pl->braking = 0;
    pl->vel_mode = 0;
    pl->unsynced = 0;
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        float d = jt->goal - jt->w_p;
        if (jt->lim.wrap > 0.0f) d = wrap_delta(d, jt->lim.wrap);
        jt->w_d = d;
    }
    if (pl->settings.sync == QO_MOTION_SYNC_PHASE && plan_phase(pl)) return;
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        jt->w_fam = 0;
        if (jt->w_d == 0.0f && jt->w_v == 0.0f && jt->w_a == 0.0f) {
            jt->w_vc = jt->w_tc = jt->w_t = 0.0f;
            continue;
        }
        solve_min(sc, jt->w_v, jt->w_a, jt->w_d, &jt->lim, &jt->w_vc, &jt->w_tc, &jt->w_fam, &jt->w_t);
        if (jt->w_t > T) T = jt->w_t;
    }
    T = timed(pl, T);
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        mseg g[MSEGS];
        unsigned n;
        float vc = jt->w_vc, tc = jt->w_tc;
        int fam = jt->w_fam;
        if (jt->w_t == 0.0f && jt->w_d == 0.0f && jt->w_v == 0.0f && jt->w_a == 0.0f) {
            jt->nph = 0;
            jt->final = jt->w_p;
            jt->duration = 0.0f;
            continue;
        }
        Tj = pl->settings.sync != QO_MOTION_SYNC_NONE ? T : timed(pl, jt->w_t);
        if (jt->w_t < Tj) {
            float v2, t2, vcs = vc;
            if (fam == 1) {
                /* a dip profile meets the extremum-velocity family at vn */
                vcs = jt->w_v + jt->w_a * fabsf(jt->w_a) / (2.0f * jt->lim.jmax);
                vcs = fminf(fmaxf(vcs, -jt->lim.vmax), jt->lim.vmax);
            }
            if (solve_time(sc, jt->w_v, jt->w_a, jt->w_d, vcs, Tj, &jt->lim, &v2, &t2)) {
                vc = v2;
                tc = t2;
                fam = 0;
            } else {
                pl->unsynced |= (uint32_t)1 << i;
            }
        }
        n = build_fam(sc, fam, jt->w_v, jt->w_a, vc, tc, &jt->lim, g);
        load(jt, jt->w_p, jt->w_v, jt->w_a, g, n, jt->w_p + jt->w_d);
    }
    pl->duration = 0.0f;
    for (i = 0; i < pl->n; i++)
        if (pl->joints[i].duration > pl->duration) pl->duration = pl->joints[i].duration;
    pl->sync_used = pl->settings.sync == QO_MOTION_SYNC_NONE ? QO_MOTION_SYNC_NONE : QO_MOTION_SYNC_TIME;
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
    if ((st.profile != QO_MOTION_TRAPEZOID && st.profile != QO_MOTION_SCURVE) ||
        (st.sync != QO_MOTION_SYNC_NONE && st.sync != QO_MOTION_SYNC_TIME && st.sync != QO_MOTION_SYNC_PHASE))
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
        jt->goal = jt->final = start[i];
        jt->duration = 0.0f;
        jt->nph = 0;
        jt->w_p = start[i];
        jt->w_v = jt->w_a = jt->w_d = jt->w_vc = jt->w_tc = jt->w_t = 0.0f;
        jt->w_fam = 0;
        jt->w_vg = jt->vend = jt->aend = 0.0f;
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

qo_status qo_motion_set_target_f32(qo_motion_planner_f32 *pl, float t_now, const float *targets,
                                   uint32_t *clamped)
{
    size_t i;
    uint32_t mask = 0;
    qo_status st;
    if (clamped) *clamped = 0;
    if (pl == NULL || targets == NULL) return QO_E_NULL;
    st = check_time(pl, t_now);
    if (st != QO_OK) return st;
    for (i = 0; i < pl->n; i++) {
        if (!isfinite(targets[i])) {
            capture(pl, t_now);
            plan_brake_safe(pl);
            return QO_E_NONFINITE;
        }
    }
    capture(pl, t_now);
    for (i = 0; i < pl->n; i++) {
        qo_motion_joint_f32 *jt = &pl->joints[i];
        float g = targets[i];
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
    }
    st = plan_goals_checked(pl);
    if (clamped && st == QO_OK) *clamped = mask;
    return st;
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
    for (i = 0; i < pl->n; i++)
        if (fabsf(vel[i]) > pl->joints[i].lim.vmax) return QO_E_RANGE; /* refused: nothing changes */
    capture(pl, t_now);
    for (i = 0; i < pl->n; i++) pl->joints[i].w_vg = vel[i];
    return plan_velocity_checked(pl);
}

qo_status qo_motion_set_limits_f32(qo_motion_planner_f32 *pl, float t_now, size_t i,
                                   const qo_motion_limits_f32 *limits)
{
    size_t k;
    qo_status st;
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
    if (pl->vel_mode) {
        /* velocity interface: on toward the same velocities, within the new vmax */
        for (k = 0; k < pl->n; k++) {
            qo_motion_joint_f32 *jt = &pl->joints[k];
            jt->w_vg = fminf(fmaxf(jt->w_vg, -jt->lim.vmax), jt->lim.vmax);
        }
        return plan_velocity_checked(pl);
    }
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
        mstate s = joint_state(&pl->joints[i], tau);
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

/* float -> Q31.32 with saturation at +-2^31. */
static int64_t to_q32(float x, int *ovf)
{
    const float lim = 2147483648.0f;
    if (!(x < lim)) {
        *ovf = 1;
        return INT64_MAX;
    }
    if (!(x > -lim)) {
        *ovf = 1;
        return -INT64_MAX;
    }
    return (int64_t)llrintf(x * 4294967296.0f);
}

/* float seconds -> Q16.16 with saturation. */
static qo_q16 to_q16(float x, int *ovf)
{
    const float lim = 32767.0f;
    if (!(x <= lim)) {
        *ovf = 1;
        return INT32_MAX;
    }
    if (!(x >= -lim)) {
        *ovf = 1;
        return -INT32_MAX;
    }
    return (qo_q16)lrintf(x * 65536.0f);
}

qo_status qo_motion_export_q16(const qo_motion_planner_f32 *pl, qo_motion_table_q16 *table,
                               qo_motion_seg_q16 *segs, size_t cap)
{
    size_t i;
    int ovf = 0;
    if (table == NULL) return QO_E_NULL;
    table->segs = segs;
    table->n = 0;
    if (pl == NULL || segs == NULL) return QO_E_NULL;
    if (pl->n == 0 || pl->joints == NULL) return QO_E_STATE;
    if (cap < pl->n * QO_MOTION_Q16_SEGS) return QO_E_CAPACITY;
    for (i = 0; i < pl->n; i++) {
        const qo_motion_joint_f32 *jt = &pl->joints[i];
        qo_motion_seg_q16 *sg = &segs[i * QO_MOTION_Q16_SEGS];
        unsigned k;
        for (k = 0; k < jt->nph; k++) {
            const qo_motion_phase_f32 *ph = &jt->ph[k];
            qo_q16 tq = to_q16(ph->t, &ovf);
            /* Coefficients at the rounded boundary: the same polynomial, re-centred. */
            float tau = (float)tq * (1.0f / 65536.0f) - ph->t;
            float p = ph->p + tau * (ph->v + tau * (0.5f * ph->a + tau * ph->j * (1.0f / 6.0f)));
            float v = ph->v + tau * (ph->a + 0.5f * tau * ph->j);
            float a = ph->a + tau * ph->j;
            if (k == 0) tq = 0;
            sg[k].t = tq;
            sg[k].c0 = to_q32(p, &ovf);
            sg[k].c1 = to_q32(v, &ovf);
            sg[k].c2 = to_q32(0.5f * a, &ovf);
            sg[k].c3 = to_q32(ph->j * (1.0f / 6.0f), &ovf);
            if (fabsf(p) >= 32767.0f) ovf = 1;
        }
        for (; k < QO_MOTION_Q16_SEGS; k++) {
            sg[k].t = jt->nph ? to_q16(jt->duration, &ovf) : 0;
            sg[k].c0 = to_q32(jt->final, &ovf);
            sg[k].c1 = to_q32(jt->vend, &ovf); /* 0 at rest; the velocity interface's cruise */
            sg[k].c2 = sg[k].c3 = 0;
            if (fabsf(jt->final) >= 32767.0f) ovf = 1;
        }
    }
    table->n = pl->n;
    return ovf ? QO_E_OVERFLOW : QO_OK;
}

/* API stubs: filled in by the following commits. */
qo_status qo_motion_set_target_state_f32(qo_motion_planner_f32 *pl, float t_now, const float *pos,
                                         const float *vel, const float *acc, uint32_t *clamped)
{
    (void)pl; (void)t_now; (void)pos; (void)vel; (void)acc;
    if (clamped) *clamped = 0;
    return QO_E_ARG;
}

qo_status qo_motion_set_joint_sync_f32(qo_motion_planner_f32 *pl, size_t i, qo_motion_sync sync)
{
    (void)pl; (void)i; (void)sync;
    return QO_E_ARG;
}
