/* One-joint time-optimal solver (float32): the profile family, its root searches, minimum time
 * and exact-duration solves. See qorient/motion.h for the design; motion.c plans N joints. */
#include "motion_internal.h"

#include <float.h>
#include <math.h>

/* Fastest change from (v0, a0) to (v1, 0) within a in [-an, ap] (after bringing an a0 beyond
 * them back at jmax) and |j| <= jmax (SCURVE), or at ap / -an (TRAPEZOID). A rising velocity
 * uses the positive bound ap, a falling one an. Writes <= 3 segments. */
static unsigned vchange(int scurve, float v0, float a0, float v1, const mlim *l, mseg *out)
{
    float vnat, s, a0s, dv, ap, t1, t2, t3, dv1, dv3, amax, jmax = l->j;
    int capped = 0;
    if (!scurve) {
        float d = v1 - v0;
        amax = d >= 0.0f ? l->ap : l->an;
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
    amax = s > 0.0f ? l->ap : l->an;
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
        /* v1 = vnat is the ramp of a0 to zero: v1 - v0 rounded to the ulp of v0 would add a
         * pulse of 2 sqrt(ulp(v0) / jmax) (check-motion timing case 645: 4.5e-5 s, whose
         * residual hid the minimum next to vs, 3.6 % slower) */
        if (v1 == vnat) ap = fmaxf(a0s, 0.0f);
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

static unsigned reverse_segs(const mseg *g, unsigned n, mseg *out);

/* Fastest change from (vc, 0) to the end state (vf, af): with af != 0 it is the time reversal
 * of the fastest change from (-vf, af) to (-vc, 0) (x~(s) = x(T - s) negates v and jerk, keeps
 * a and the acceleration bounds), its segments taken backwards with the jerk negated. */
static unsigned vchange_end(int scurve, float vc, float vf, float af, const mlim *l, mseg *out)
{
    mseg g[3];
    if (af == 0.0f || !scurve) return vchange(scurve, vc, 0.0f, vf, l, out);
    return reverse_segs(g, vchange(1, -vf, af, -vc, l, g), out);
}

/* Profile through extremum velocity vc with cruise tc, from (v0, a0) to (vf, af). */
static unsigned build(const mprob *p, float vc, float tc, mseg *out)
{
    unsigned n = vchange(p->scurve, p->v0, p->a0, vc, &p->l, out);
    /* The cruise (and the stop after it) starts from exactly (vc, 0): rounding gathered
     * while the velocity change passed through large values must not be carried over a long
     * cruise into the end position. */
    out[n].d = tc;
    out[n].j = 0.0f;
    out[n].a = 0.0f;
    out[n].v = vc;
    out[n].seta = out[n].setv = 1;
    n++;
    n += vchange_end(p->scurve, vc, p->vf, p->af, &p->l, out + n);
    return n;
}

/* The "dip" shape, the profiles without an acceleration zero before the stop: the acceleration
 * ramps from a0 straight to am (between 0 and a0), then the fastest pulse from (v1, am) to rest
 * (it ramps back away from zero, may hold at +-amax, and ramps to zero). E.g. a joint moving
 * toward a near target while braking eases the braking first to travel further, then brakes
 * harder: "ramp down, up to amax, hold, ramp to zero" of issue 11. With am = 0 it is the
 * extremum-velocity profile through vn; with am = a0 the direct stop. The velocity never leaves
 * [-|vn|, |vn|] on the way to rest, so it stays within vmax when the start does. SCURVE only. */
/* Fastest change from (v0, a0) to (v1, a1), both accelerations within [-an, ap]: one pulse,
 * up-down (peak >= max(a0, a1)) or down-up, its peak from the velocity balance
 * (2 pk^2 - a0^2 - a1^2) / (2 jmax) = v1 - v0, clipped to the bound with a hold; the shorter
 * of the two that exist. Writes 3 segments; 0 if neither exists (then out[0].d is NaN). */
static unsigned vchange2(float v0, float a0, float v1, float a1, const mlim *l, mseg *out)
{
    float best = INFINITY, J = l->j;
    int k;
    out[0].d = NAN;
    for (k = 0; k < 2; k++) {
        float s = k == 0 ? 1.0f : -1.0f, bound = k == 0 ? l->ap : l->an;
        float b0 = s * a0, b1 = s * a1, dv = s * (v1 - v0), m = fmaxf(b0, b1);
        float X = J * dv + 0.5f * (b0 * b0 + b1 * b1), pk, h = 0.0f, t;
        if (m > bound * (1.0f + 1e-6f)) continue;
        if (X < 0.0f) {
            if (X < -1e-6f * (J * fabsf(dv) + b0 * b0 + b1 * b1)) continue;
            X = 0.0f;
        }
        /* the lower peak is the faster pulse when both reach max(a0, a1) */
        pk = -sqrtf(X);
        if (pk < m) pk = sqrtf(X);
        if (pk < m - 1e-5f * (fabsf(m) + pk)) continue;
        if (pk < m) pk = m;
        if (pk > bound) {
            pk = bound;
            h = (dv - (pk * pk - b0 * b0) / (2.0f * J) - (pk * pk - b1 * b1) / (2.0f * J)) / pk;
            if (h < 0.0f) h = 0.0f;
        }
        t = (pk - b0) / J + h + (pk - b1) / J;
        if (t < best) {
            best = t;
            out[0].d = (pk - b0) / J;
            out[0].j = s * J;
            out[1].d = h;
            out[1].j = 0.0f;
            out[2].d = (pk - b1) / J;
            out[2].j = -s * J;
        }
    }
    out[0].seta = out[0].setv = out[1].seta = out[1].setv = out[2].seta = out[2].setv = 0;
    return best < INFINITY ? 3 : 0;
}

static unsigned build_dip(const mprob *p, float am, mseg *out)
{
    float j = am >= p->a0 ? p->l.j : -p->l.j, d = fabsf(am - p->a0) / p->l.j;
    float v1 = p->v0 + d * (p->a0 + 0.5f * d * j);
    out[0].d = d;
    out[0].j = j;
    out[0].seta = out[0].setv = 0;
    /* the pulse to (vf, 0), or to a target acceleration (NaN duration if there is none) */
    if (p->af == 0.0f) return 1 + vchange(1, v1, am, p->vf, &p->l, out + 1);
    vchange2(v1, am, p->vf, p->af, &p->l, out + 1);
    return 4;
}

/* The time reversal of a problem: x~(s) = x(T - s) starts at the end state with v negated
 * and a kept, over -dp, with the velocity bounds swapped; its profiles taken backwards with the
 * jerk negated are the original's. The "end dip" (family 2: a pulse, then a single ramp to the
 * target acceleration) is the reversed problem's dip. */
static mprob reversed(const mprob *p)
{
    mprob r = *p;
    r.l.vp = p->l.vn;
    r.l.vn = p->l.vp;
    r.v0 = -p->vf;
    r.a0 = p->af;
    r.vf = -p->v0;
    r.af = p->a0;
    r.dp = -p->dp;
    return r;
}

static unsigned reverse_segs(const mseg *g, unsigned n, mseg *out)
{
    unsigned k;
    for (k = 0; k < n; k++) {
        out[k] = g[n - 1 - k];
        out[k].j = -g[n - 1 - k].j;
    }
    return n;
}

/* Velocity gained by a jerk ramp of the acceleration from x to y at |jerk| = J. */
static float ramp_dv(float x, float y, float J)
{
    return 0.5f * (x + y) * fabsf(y - x) / J;
}

static void ramp_seg(float x, float y, float J, mseg *g)
{
    g->d = fabsf(y - x) / J;
    g->j = y >= x ? J : -J;
    g->seta = g->setv = 0;
}

/* The "two holds" shape (families 3 and 4): a0 ramps to one acceleration bound B1 and holds it
 * h1, ramps to the other bound B2 and holds it h2, then ramps to af (family 3: B1 = ap, family
 * 4: B1 = -an). E.g. braking hard from a positive acceleration toward a target state that
 * accelerates the other way. */
static unsigned build_holds(const mprob *p, int fam, float h1, float h2, mseg *out)
{
    float B1 = fam == 3 ? p->l.ap : -p->l.an, B2 = fam == 3 ? -p->l.an : p->l.ap, J = p->l.j;
    ramp_seg(p->a0, B1, J, &out[0]);
    out[1].d = h1;
    out[1].j = 0.0f;
    out[1].seta = out[1].setv = 0;
    ramp_seg(B1, B2, J, &out[2]);
    out[3].d = h2;
    out[3].j = 0.0f;
    out[3].seta = out[3].setv = 0;
    ramp_seg(B2, p->af, J, &out[4]);
    return 5;
}

/* A joint's solved profile: family 0 = extremum velocity x with cruise tc (build), family 1 =
 * dip to acceleration x (build_dip), family 2 = end dip from acceleration x, families 3 and 4 =
 * two holds of x and tc seconds (build_holds). */
unsigned qo_motion_build(const mprob *p, const msol *s, mseg *out)
{
    if (s->fam >= 3) return build_holds(p, s->fam, s->x, s->tc, out);
    if (s->fam == 1) return build_dip(p, s->x, out);
    if (s->fam == 2) {
        mprob r = reversed(p);
        mseg g[4];
        return reverse_segs(g, build_dip(&r, s->x, g), out);
    }
    return build(p, s->x, s->tc, out);
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
        /* a segment of zero duration only sets (the root searches' profiles have no cruise,
         * often no hold): integrating it would add exact zeros */
        if (g[i].d == 0.0f) {
            if (g[i].seta) s.a = g[i].a;
            if (g[i].setv) s.v = g[i].v;
            continue;
        }
        mseg_integ(&s, &g[i]);
        t += g[i].d;
    }
    *disp = s.p;
    *dur = t;
}

/* Displacement and duration of the zero-cruise profile through vc. */
static void eval_vc(const mprob *p, float vc, float *disp, float *dur)
{
    mseg g[MSEGS];
    unsigned n = build(p, vc, 0.0f, g);
    eval_segs(p->v0, p->a0, g, n, disp, dur);
}

static float cbrt_pos(float a);

/* What a root search evaluates at extremum velocity vc. mode 0 (minimum time): displacement of
 * the zero-cruise profile minus dp, aux = its duration. mode 1 (time sync): position reached in
 * exactly T with the cruise filling the rest, minus dp, aux = that cruise time. mode 2: the dip
 * profile to acceleration vc (build_dip), displacement minus dp, aux = its duration. */
typedef struct rctx {
    const mprob *p;
    int mode;
    float dp, T;
    float vs, as; /* scale of the velocities (mode 0, 1) and accelerations (mode 2) searched */
    float vd;     /* mode 2: the velocities a dip surely flies (start, end, their ramps to a = 0) */
} rctx;

/* 1 if a and b are the same float, zero's sign included (NaN never is). */
static int same_bits(float a, float b)
{
    return a == b && !signbit(a) == !signbit(b);
}

/* x clamped to the velocity limits [-vn, vp]: fminf(fmaxf(x, -vn), vp) without the libm calls
 * (the same value: the bounds are finite and nonzero, and a NaN x gives -vn as fmaxf does). */
static float clamp_v(float x, const mlim *l)
{
    x = x > -l->vn ? x : -l->vn;
    return x < l->vp ? x : l->vp;
}

/* max of two numbers that are not NaN (fmaxf is a libm call where NaN rules must hold) */
static float maxf(float a, float b)
{
    return a > b ? a : b;
}

/* Velocity scale of a problem: a bound (with a margin of 4) on the velocities of the profiles
 * that can reach dp in about the minimum time, or the velocity limit if that is smaller. The
 * solver's tolerances are float32 rounding of positions, i.e. relative to the velocities
 * actually flown: with the limit itself as the scale, a vmax of 1e8 made a 0.4 miss look like
 * rounding and the plan lost its target (a position jump at the end). Bound: the speed of the
 * start and end states with their acceleration ramps (v), the stop from v (at most v t with
 * t = v/A + 2 sqrt(v/J) + |a0|/J), then the distance L = |dp| + 2 v t covered from rest, whose
 * peak is at most min(sqrt(A L), (L sqrt(J))^(2/3)). */
static float vscale_bound(const mprob *p, float lim);

static float vscale(const mprob *p)
{
    const mlim *l = &p->l;
    float J = l->j, A = maxf(l->ap, l->an), lim = maxf(l->vp, l->vn), D = fabsf(p->dp), q = 0.25f * lim;
    /* Both bounds at or above the limit already for L = |dp| (L is larger): the limit, without
     * a division or root (most joints with ordinary limits). Not only where the limit is far
     * above (8x was tried: a joint with vmax 33 moving at 0.07 then jumped at its end). */
    if (A * D >= q * q && D * D * J >= q * q * q) return lim;
    return vscale_bound(p, lim);
}

static float vscale_bound(const mprob *p, float lim)
{
    const mlim *l = &p->l;
    float J = l->j, A = maxf(l->ap, l->an), q = 0.25f * lim;
    float v = fabsf(p->v0) + fabsf(p->vf) + (p->a0 * p->a0 + p->af * p->af) / (2.0f * J);
    float t = v / A + 2.0f * sqrtf(v / J) + (fabsf(p->a0) + fabsf(p->af)) / J;
    float L = fabsf(p->dp) + 2.0f * v * t, r = 4.0f * (v + sqrtf(A * L)), w = q - v;
    /* the jerk bound 4 (v + u^2), u^2 = (L sqrt(J))^(2/3), is below the limit only where
     * L^2 J < w^3: the cube root is needed there only (the solver's hot path skips it) */
    if (w > 0.0f && L * L * J < w * w * w) {
        float u = cbrt_pos(L * sqrtf(J)), rj = 4.0f * (v + u * u);
        if (!(r <= rj)) r = rj;
    }
    return r < lim ? r : lim; /* also the limit where r is NaN or infinite */
}

static rctx rctx_make(const mprob *p, int mode, float T)
{
    rctx c;
    c.p = p;
    c.mode = mode;
    c.dp = p->dp;
    c.T = T;
    c.vs = vscale(p);
    /* accelerations: those of the states, or the peak sqrt(J v) a velocity change needs */
    c.as = maxf(p->l.ap, p->l.an);
    if (p->l.j * c.vs < 0.0625f * c.as * c.as) { /* sqrt(J vs) < as / 4 */
        float as = 4.0f * (fabsf(p->a0) + fabsf(p->af) + sqrtf(p->l.j * c.vs));
        if (as < c.as) c.as = as;
    }
    c.vd = 0.0f;
    if (mode == 2) {
        float J2 = 2.0f * p->l.j;
        c.vd = maxf(maxf(fabsf(p->v0), fabsf(p->vf)),
                    maxf(fabsf(p->v0 + p->a0 * fabsf(p->a0) / J2), fabsf(p->vf - p->af * fabsf(p->af) / J2)));
    }
    return c;
}

static float resid(const rctx *c, float vc, float *aux)
{
    float d, t;
    if (c->mode == 2) {
        mseg g[4];
        unsigned n = build_dip(c->p, vc, g);
        eval_segs(c->p->v0, c->p->a0, g, n, &d, aux);
        return d - c->dp;
    }
    eval_vc(c->p, vc, &d, &t);
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
        if (!(a < b ? m > a && m < b : m > b && m < a)) m = 0.5f * (a + b);
        if (m == a || m == b) break;
        fm = resid(c, m, &xm);
        /* Done once the position misses by float32 rounding of the move (what the 2-ulp bracket
         * below would give at best), on the side a cruise can absorb in mode 0. In mode 2 m is
         * an acceleration: the positions scale with the velocities flown (vd), and |m| xm (a
         * velocity, not the one flown) stopped dips at wide limits outside solve_dip's own
         * tolerance, which then dropped them (make check-motion wide cases 1174 and 1900: up to
         * 1.26x slower). */
        if (fm == 0.0f || (fabsf(fm) <= 1.2e-7f * (fabsf(c->dp) + (c->mode == 2 ? c->vd : fabsf(m)) *
                                                                    (c->mode == 1 ? c->T : xm)) &&
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
        if (fabsf(b - a) <= 2.4e-7f * maxf(maxf(fabsf(a), fabsf(b)), 1e-3f * (c->mode == 2 ? c->as : c->vs)))
            break;
    }
    /* Mode 0: prefer the end a short cruise can correct (residual opposite in sign to the
     * velocity: the profile falls short); near vn the displacement has a square-root kink, so
     * 2 ulps of vc can still miss the target by more than float resolution of p. */
    if (c->mode == 0 && fabsf(a) > 1e-3f * c->vs && fabsf(b) > 1e-3f * c->vs) {
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

/* Records a winning candidate of family fam (see msol) with its family, so the flag always
 * belongs to the profile that won last: a dip replaced by a later candidate of the same
 * duration once kept family 1 with that candidate's extremum velocity read as the dip's
 * acceleration, a plan 20 % over vmax (fuzz/regress/motion/vs-tie-dip: v0 -6.98, a0 -4.50,
 * dp -8.60, vmax 9, amax 30, jmax 13). */
static void keep(int fam, float x, float tc, float dur, float *bv, float *bt, float *bd, int *bf)
{
    *bv = x;
    *bt = tc;
    *bd = dur;
    *bf = fam;
}

/* Keeps the candidate profile of smallest duration (keep). */
static void consider(int fam, float x, float tc, float dur, float *bv, float *bt, float *bd, int *bf)
{
    if (dur < *bd) keep(fam, x, tc, dur, bv, bt, bd, bf);
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
static float rest_peak(float D, float V, float A, float J, float *slope)
{
    float aj = A / J, x, t;
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

static int rest_min(const mprob *p, float *vc, float *tc, float *dur)
{
    rctx c = rctx_make(p, 0, 0.0f);
    float dp = p->dp, slope, x = rest_peak(fabsf(dp), dp >= 0.0f ? p->l.vp : p->l.vn, p->l.ap, p->l.j, &slope);
    if (dp < 0.0f) x = -x;
    return rest_fix(&c, x, slope, 4e-6f * fabsf(dp), vc, tc, dur);
}

/* Rest-to-rest SCURVE profile of exactly duration T: D = x (T - tacc(x)), the smaller root,
 * tacc = x/A + A/J (hold) or 2 sqrt(x/J); the second by safeguarded Newton on u = sqrt(x). */
static int rest_time(const mprob *p, float T, float *vc, float *tc)
{
    rctx c = rctx_make(p, 1, T);
    float dp = p->dp, V = dp >= 0.0f ? p->l.vp : p->l.vn;
    float D = fabsf(dp), A = p->l.ap, J = p->l.j, aj = A / J, Tp = T - aj, disc = Tp * Tp - 4.0f * D / A, x;
    float slope;
    if (Tp > 0.0f && disc >= 0.0f && (x = 2.0f * D / (Tp + sqrtf(disc))) >= A * aj) {
        slope = Tp - 2.0f * x / A;
    } else {
        float sj = sqrtf(J), lo = sqrtf(D / T), hi = fminf(T * sj / 3.0f, sqrtf(V)), u = lo;
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

/* 1 if the velocity of segments g[0..n) from (v0, a0) stays within [-vbn, vbp] (checked at the
 * segment ends and where the acceleration crosses zero); its largest |v| in *vpk (may be NULL). */
static int segs_within(float v0, float a0, const mseg *g, unsigned n, float vbp, float vbn, float *vpk)
{
    mstate st;
    unsigned k;
    float pk = fabsf(v0);
    st.p = 0.0f;
    st.v = v0;
    st.a = a0;
    for (k = 0; k < n; k++) {
        float a1 = st.a + g[k].d * g[k].j;
        if (g[k].j != 0.0f && (st.a < 0.0f) != (a1 < 0.0f)) {
            float tz = -st.a / g[k].j, vz = st.v + tz * (st.a + 0.5f * tz * g[k].j);
            if (vz > vbp || vz < -vbn) return 0;
            pk = maxf(pk, fabsf(vz));
        }
        mseg_integ(&st, &g[k]);
        if (st.v > vbp || st.v < -vbn) return 0;
        pk = maxf(pk, fabsf(st.v));
    }
    if (vpk) *vpk = pk;
    return 1;
}

/* Where the residual at scan points k-1, k, k+1 (those that exist) keeps one sign but comes
 * closest to zero at k, a pair of roots may lie between them, hidden from the scan (issue 11,
 * check-motion TIME_IF_NECESSARY case 5781: a dip to -7.5 found only between am = -8.5 and
 * -5.7, 0.809 s where the scan gave 2.018 s). Golden section for the residual's extremum on
 * [x[k-1], x[k+1]] toward zero, stopped as soon as it changes sign. Returns 1 with the point
 * in *xe, *fe, *te if it does, else 0. */
static int dip_bump(const rctx *c, const float *x, const float *f, unsigned k, unsigned n, float *xe, float *fe,
                    float *te)
{
    const float g = 0.381966f;
    float sg = f[k] < 0.0f ? 1.0f : -1.0f, a = x[k > 0 ? k - 1 : k], b = x[k < n ? k + 1 : k];
    float x1 = a + g * (b - a), x2 = b - g * (b - a), f1, f2, t1, t2;
    unsigned it;
    if (k > 0 && !(sg * f[k] > sg * f[k - 1])) return 0;
    if (k < n && !(sg * f[k] > sg * f[k + 1])) return 0;
    f1 = resid(c, x1, &t1);
    f2 = resid(c, x2, &t2);
    for (it = 0; it < 20; it++) {
        /* a NaN (no pulse to the end state there) counts as farthest from zero */
        int left = !(sg * f2 >= sg * f1) || f2 != f2;
        if (left ? sg * f1 > 0.0f : sg * f2 > 0.0f) break;
        if (left) {
            b = x2;
            x2 = x1;
            f2 = f1;
            t2 = t1;
            x1 = a + g * (b - a);
            f1 = resid(c, x1, &t1);
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            t1 = t2;
            x2 = b - g * (b - a);
            f2 = resid(c, x2, &t2);
        }
    }
    if (sg * f1 > 0.0f && !(sg * f2 > sg * f1 && f2 == f2)) {
        *xe = x1;
        *fe = f1;
        *te = t1;
        return 1;
    }
    if (sg * f2 > 0.0f) {
        *xe = x2;
        *fe = f2;
        *te = t2;
        return 1;
    }
    return 0;
}

/* Fastest dip profile (build_dip) with displacement dp: the residual is scanned at nscan + 1
 * (<= QO_MOTION_DIP_SCAN + 1) points of am in [e0, e1] (e.g. the extremum-velocity profile
 * through vn and the direct transfer) and every sign change is solved; with nscan > 1 (the
 * residual not known to be monotone) also the pairs of roots between the points (dip_bump).
 * kn[0..nk): points whose residual and duration the caller has already, {am, f, t}, used
 * where a scan point has the same bits. Returns 0 if none. */
#define QO_MOTION_DIP_SCAN 4
typedef struct mpt {
    float x, f, t;
} mpt;

static int solve_dip(const mprob *p, float e0, float e1, unsigned nscan, const mpt *kn, unsigned nk, float *am,
                     float *dur)
{
    rctx c;
    float x[2 * QO_MOTION_DIP_SCAN + 2], f[2 * QO_MOTION_DIP_SCAN + 2], t[2 * QO_MOTION_DIP_SCAN + 2];
    float v0 = p->v0, a0 = p->a0, dp = p->dp, J = p->l.j, vnat = v0 + a0 * fabsf(a0) / (2.0f * J);
    /* velocity bounds of the profile: the limits, or the start's own reach beyond them */
    float vbp = fmaxf(p->l.vp, vnat) * (1.0f + 1e-6f), vbn = fmaxf(p->l.vn, -vnat) * (1.0f + 1e-6f);
    unsigned k, n;
    c = rctx_make(p, 2, 0.0f);
    *am = 0.0f;
    *dur = INFINITY;
    if (nscan > QO_MOTION_DIP_SCAN) nscan = QO_MOTION_DIP_SCAN;
    for (k = 0; k <= nscan; k++) {
        unsigned i;
        x[k] = e0 + (e1 - e0) * (float)k / (float)nscan;
        for (i = 0; i < nk && !same_bits(kn[i].x, x[k]); i++) continue;
        if (i < nk) {
            f[k] = kn[i].f;
            t[k] = kn[i].t;
        } else {
            f[k] = resid(&c, x[k], &t[k]);
        }
    }
    n = nscan;
    if (nscan > 1) {
        float xb[QO_MOTION_DIP_SCAN + 1], fb[QO_MOTION_DIP_SCAN + 1], tb[QO_MOTION_DIP_SCAN + 1];
        unsigned nb = 0, i;
        for (k = 0; k <= nscan; k++) {
            if (f[k] == 0.0f || f[k] != f[k]) continue;
            if (dip_bump(&c, x, f, k, nscan, &xb[nb], &fb[nb], &tb[nb])) nb++;
        }
        /* insert the sign-change points, keeping x sorted in the scan direction */
        for (i = 0; i < nb; i++) {
            k = ++n;
            while (k > 0 && (e1 > e0 ? x[k - 1] > xb[i] : x[k - 1] < xb[i])) {
                x[k] = x[k - 1];
                f[k] = f[k - 1];
                t[k] = t[k - 1];
                k--;
            }
            x[k] = xb[i];
            f[k] = fb[i];
            t[k] = tb[i];
        }
    }
    nscan = n;
    for (k = 0; k <= nscan; k++) {
        float r = x[k], tr = t[k], fr = f[k], vpk;
        if (fr != 0.0f) {
            if (k == nscan || f[k + 1] == 0.0f || (fr < 0.0f) == (f[k + 1] < 0.0f)) continue;
            if (fr != fr || f[k + 1] != f[k + 1]) continue; /* no pulse to the end state there */
            r = root(&c, x[k], x[k + 1], f[k], f[k + 1], t[k], t[k + 1], &tr, &fr);
        }
        if (p->af != 0.0f) {
            /* to a target acceleration am may lie on either side of zero: every velocity
             * extremum of the profile is checked */
            mseg g[4];
            if (!segs_within(v0, a0, g, build_dip(p, r, g), vbp, vbn, &vpk)) continue;
        } else {
            /* ramping a0 away from zero first drives the velocity further: its extremum, where
             * the pulse to the end crosses a = 0, must stay within the velocity bounds */
            float d = fabsf(r - a0) / J, j = r >= a0 ? J : -J;
            float v1 = v0 + d * (a0 + 0.5f * d * j), ve = v1 + r * fabsf(r) / (2.0f * J);
            if (ve > vbp || ve < -vbn) continue;
            vpk = maxf(maxf(fabsf(v0), fabsf(v1)), maxf(fabsf(ve), fabsf(p->vf)));
        }
        /* No cruise absorbs a residual here: keep only a root to float precision of the
         * positions, i.e. relative to the velocities this profile flies (not the velocity scale
         * vs, a bound with a margin: 16x the speed flown in make check-motion wide case 1503,
         * where a bracket end on the direct stop, 8.1e-6 short of a 1.8 move, passed as a root
         * and the plan was 0.3 % faster than possible by snapping to its target at the end). */
        if (fr != 0.0f && !(fabsf(fr) <= 1e-6f * (fabsf(dp) + maxf(vpk, c.vd) * tr))) continue;
        if (tr < *dur) {
            *dur = tr;
            *am = r;
        }
    }
    return *dur < INFINITY;
}

/* The two-holds shapes (build_holds): the velocity balance fixes h2 = (R - B1 h1) / B2, and the
 * displacement is then quadratic in h1: fitted through three evaluations, its smallest root
 * with h1, h2 >= 0 taken (the duration grows with h1), kept if its integrated residual is at
 * float32 rounding and the velocity stays within the bounds. */
static void solve_holds(const mprob *p, msol *sol)
{
    const mlim *l = &p->l;
    float J = l->j, vnat = p->v0 + p->a0 * fabsf(p->a0) / (2.0f * J);
    float vbp = maxf(l->vp, vnat) * (1.0f + 1e-6f), vbn = maxf(l->vn, -vnat) * (1.0f + 1e-6f);
    float vs = vscale(p);
    int fam;
    for (fam = 3; fam <= 4; fam++) {
        float B1 = fam == 3 ? l->ap : -l->an, B2 = fam == 3 ? -l->an : l->ap;
        float R = p->vf - p->v0 - ramp_dv(p->a0, B1, J) - ramp_dv(B1, B2, J) - ramp_dv(B2, p->af, J);
        float h0 = maxf(0.0f, R / B1), H, f[3], t, qa, qb, disc, u, h1, h2, d, dur;
        mseg g[5];
        int k;
        H = (fabsf(B1 - p->a0) + fabsf(B2 - B1) + fabsf(p->af - B2)) / J + h0 + 1e-3f;
        for (k = 0; k < 3; k++) {
            float hh = h0 + H * (float)k;
            eval_segs(p->v0, p->a0, g, build_holds(p, fam, hh, (R - B1 * hh) / B2, g), &f[k], &t);
            f[k] -= p->dp;
        }
        /* f(u) = f0 + qb u + qa u^2, u = h1 - h0 */
        qa = (f[2] - 2.0f * f[1] + f[0]) / (2.0f * H * H);
        qb = (f[1] - f[0]) / H - qa * H;
        if (qa == 0.0f) {
            u = qb != 0.0f ? -f[0] / qb : -1.0f;
        } else {
            float r1, r2, q;
            disc = qb * qb - 4.0f * qa * f[0];
            if (!(disc >= 0.0f)) continue;
            q = -0.5f * (qb + (qb >= 0.0f ? sqrtf(disc) : -sqrtf(disc)));
            r1 = q / qa;
            r2 = q != 0.0f ? f[0] / q : r1;
            if (r1 > r2) {
                float tmp = r1;
                r1 = r2;
                r2 = tmp;
            }
            u = r1 >= 0.0f ? r1 : r2;
        }
        if (!(u >= 0.0f)) continue;
        h1 = h0 + u;
        h2 = (R - B1 * h1) / B2;
        if (h2 < 0.0f) h2 = 0.0f; /* rounding at h0 */
        build_holds(p, fam, h1, h2, g);
        eval_segs(p->v0, p->a0, g, 5, &d, &dur);
        if (!(fabsf(d - p->dp) <= 1e-6f * (fabsf(p->dp) + (fabsf(p->v0) + vs) * dur))) continue;
        if (!(dur < sol->t) || !segs_within(p->v0, p->a0, g, 5, vbp, vbn, NULL)) continue;
        sol->x = h1;
        sol->tc = h2;
        sol->t = dur;
        sol->fam = fam;
    }
}

/* Target accelerations (af != 0): the dips at both ends (three jerk ramps a0 -> am -> peak ->
 * af, the peak from the velocity balance and clipped with a hold; the end dip the reversed
 * problem's), am over the whole acceleration range in its pieces between the bounds, 0 and a0,
 * each scanned at 4 points. Keeps the shortest in *sol if shorter than sol->t. */
static void solve_dips_moving(const mprob *p, msol *sol)
{
    int e;
    unsigned k;
    for (e = 0; e < 2; e++) {
        /* am over every acceleration: the pieces between the bounds, 0 and a0 */
        mprob r = e ? reversed(p) : *p;
        float pt[4], am, dd;
        pt[0] = -r.l.an;
        pt[1] = r.a0 < 0.0f ? r.a0 : 0.0f;
        pt[2] = r.a0 < 0.0f ? 0.0f : r.a0;
        pt[3] = r.l.ap;
        for (k = 0; k < 3; k++) {
            if (!(pt[k + 1] > pt[k])) continue;
            if (solve_dip(&r, pt[k], pt[k + 1], 3, NULL, 0, &am, &dd) && dd < sol->t) {
                sol->x = am;
                sol->tc = 0.0f;
                sol->t = dd;
                sol->fam = 1 + e;
            }
        }
    }
}

/* Minimum-time extremum velocity vc and cruise tc for displacement dp (see motion.h).
 * The displacement D(vc) of the zero-cruise profile is monotone on [-vn, min(vs, ve)] and on
 * [max(vs, ve), vp], vs being the velocity the start reaches by ramping a0 to zero and ve the
 * one the end state is reached from by a ramp from zero (0 for a target at rest); between
 * them the profile changes velocity in two stages and D has one interior extremum (located by
 * golden section). Every monotone piece whose ends bracket dp gives a root; the root (or the
 * cruise at vp / -vn) of smallest duration wins. */
void qo_motion_solve_min(const mprob *p, msol *sol)
{
    rctx c;
    const mlim *l = &p->l;
    float v0 = p->v0, a0 = p->a0, dp = p->dp;
    float pt[5], fp[5], xp[5], vn, ve, lo, hi, bv = 0.0f, bt = 0.0f, bd = INFINITY, x, fz = NAN, fn0 = NAN, xn0 = 0.0f,
          xz = 0.0f;
    unsigned np = 0, i, skip, kz = 0;
    int scurve = p->scurve, atrest = p->vf == 0.0f && p->af == 0.0f;
    sol->fam = 0;
    sol->f0 = sol->t0 = NAN;
    if (scurve && v0 == 0.0f && a0 == 0.0f && atrest && l->ap == l->an && rest_min(p, &sol->x, &sol->tc, &sol->t))
        return;
    c = rctx_make(p, 0, 0.0f);
    vn = scurve ? v0 + a0 * fabsf(a0) / (2.0f * l->j) : v0;
    vn = clamp_v(vn, l);
    ve = p->vf;
    if (scurve && p->af != 0.0f) ve = clamp_v(ve - p->af * fabsf(p->af) / (2.0f * l->j), l);
    lo = fminf(vn, ve);
    hi = fmaxf(vn, ve);
    pt[np++] = -l->vn;
    if (lo > pt[np - 1]) pt[np++] = lo;
    if (hi > pt[np - 1]) pt[np++] = hi;
    if (l->vp > pt[np - 1]) pt[np++] = l->vp;
    /* D is increasing on the outer pieces, so an end is decided by the inner point next to it
     * when that misses dp by far more than rounding: beyond it D misses further (no root, no
     * cruise). Such an end (-vn or vp, never vs or ve) is evaluated only if the pieces between
     * are searched below (skip: bit 1 the first point, bit 2 the last). */
    skip = 0;
    for (i = 1; i + 1 < np; i++) {
        fp[i] = resid(&c, pt[i], &xp[i]);
        if (i == 1 && pt[1] == lo && fp[1] < -1e-5f * (fabsf(dp) + c.vs * xp[1])) skip |= 1;
        if (i + 2 == np && pt[i] == hi && fp[i] > 1e-5f * (fabsf(dp) + c.vs * xp[i])) skip |= 2;
    }
    if (!(skip & 1)) fp[0] = resid(&c, pt[0], &xp[0]);
    if (np > 1 && !(skip & 2)) fp[np - 1] = resid(&c, pt[np - 1], &xp[np - 1]);
    for (i = 0; i < np; i++) {
        if ((i == 0 && (skip & 1)) || (i + 1 == np && (skip & 2))) continue;
        if (pt[i] == ve) {
            fz = fp[i];
            xz = xp[i];
            kz = same_bits(pt[i], p->vf) && !same_bits(v0, -0.0f);
        }
        if (same_bits(pt[i], 0.0f)) {
            sol->f0 = fp[i];
            sol->t0 = xp[i];
        }
        if (pt[i] == vn) {
            fn0 = fp[i];
            xn0 = xp[i];
        }
    }
    /* Cruising at vp / -vn when even the fastest peak falls short. */
    if (!(skip & 2) && fp[np - 1] <= 0.0f)
        consider(0, l->vp, -fp[np - 1] / l->vp, xp[np - 1] - fp[np - 1] / l->vp, &bv, &bt, &bd, &sol->fam);
    if (!(skip & 1) && fp[0] >= 0.0f) consider(0, -l->vn, fp[0] / l->vn, xp[0] + fp[0] / l->vn, &bv, &bt, &bd, &sol->fam);
    /* Outer pieces first: a single velocity extremum beyond vs and ve (or a reversal) reaches
     * dp faster than changing velocity in two stages, so the middle piece is searched only when
     * neither outer piece brackets dp (e.g. a0 already braking, dp between the two stops' reach). */
    for (i = 0; i + 1 < np; i++) {
        int outer = pt[i + 1] <= lo || pt[i] >= hi;
        if (!outer || (i == 0 && (skip & 1)) || (i + 2 == np && (skip & 2))) continue;
        if (fp[i] == 0.0f) consider(0, pt[i], 0.0f, xp[i], &bv, &bt, &bd, &sol->fam);
        if (fp[i + 1] == 0.0f) consider(0, pt[i + 1], 0.0f, xp[i + 1], &bv, &bt, &bd, &sol->fam);
        if (fp[i] != 0.0f && fp[i + 1] != 0.0f && (fp[i] < 0.0f) != (fp[i + 1] < 0.0f)) {
            float fr, r = root(&c, pt[i], pt[i + 1], fp[i], fp[i + 1], xp[i], xp[i + 1], &x, &fr);
            float tcr = (r != 0.0f && fr * r < 0.0f) ? -fr / r : 0.0f;
            consider(0, r, tcr, x + tcr, &bv, &bt, &bd, &sol->fam);
        }
    }
    /* The dip family runs from the extremum-velocity profile through vs (am = 0) to the direct
     * transfer (vc = ve, am = a0): searched when those two bracket dp, i.e. when the two-stage
     * middle piece below would be; its profiles are then never shorter (checked against the
     * reference in tests/core/test_motion_oracle.c), so that piece is searched only without a dip.
     * Only for end states with af = 0 (the dip's pulse ends at zero acceleration). */
    if (scurve && p->af == 0.0f && a0 != 0.0f && vn != ve && (fz < 0.0f) != (fn0 < 0.0f) && fz == fz && fn0 == fn0) {
        float am, dd;
        mpt kn[1];
        /* at am = a0 the dip is the direct transfer (a zero ramp, then the profile through ve =
         * vf): the same segments from the same start, so the same residual as fz (kz: ve has
         * vf's bits and v0 is not -0, which the ramp would turn into +0) */
        kn[0].x = a0;
        kn[0].f = fz;
        kn[0].t = xz;
        if (solve_dip(p, 0.0f, a0, 1, kn, kz, &am, &dd)) consider(1, am, 0.0f, dd, &bv, &bt, &bd, &sol->fam);
    }
    /* The other orientation: a0 ramped further away from zero first (to am between a0 and the
     * bound on its side), then the pulse to the end; from the direct transfer (am = a0) to the
     * bound. Its far end is evaluated only here; solved when it brackets dp with the direct one. */
    /* It starts at the direct transfer (fz) and drives the velocity further in a0's direction
     * as am grows, so where the direct transfer already overshoots dp in that direction (by far
     * more than rounding) the far end does too: no bracket, fw not evaluated. */
    if (scurve && p->af == 0.0f && a0 != 0.0f && (a0 > 0.0f ? a0 < l->ap : -a0 < l->an) && fz == fz &&
        !((a0 > 0.0f ? fz : -fz) > 1e-5f * (fabsf(dp) + c.vs * xz))) {
        float aw = a0 > 0.0f ? l->ap : -l->an, am, dd, fw, tw;
        rctx cw = rctx_make(p, 2, 0.0f);
        fw = resid(&cw, aw, &tw);
        if (fw != fw || (fw < 0.0f) != (fz < 0.0f) || fw == 0.0f) {
            mpt kn[2];
            kn[0].x = aw;
            kn[0].f = fw;
            kn[0].t = tw;
            kn[1].x = a0; /* the direct transfer, as above */
            kn[1].f = fz;
            kn[1].t = xz;
            if (solve_dip(p, a0, aw, 1, kn, 1 + kz, &am, &dd)) consider(1, am, 0.0f, dd, &bv, &bt, &bd, &sol->fam);
        }
    }
    if (!(bd < INFINITY)) {
        if (skip & 1) fp[0] = resid(&c, pt[0], &xp[0]);
        if (skip & 2) fp[np - 1] = resid(&c, pt[np - 1], &xp[np - 1]);
    }
    /* The two-stage middle piece: split it at its extremum when it has one. */
    if (!(bd < INFINITY) && vn != ve && hi - lo > 1e-6f * c.vs) {
        unsigned k = 1; /* pt[k-1], pt[k] = the middle piece [lo, hi] */
        float mlo, mhi, fm, xm;
        while (k + 1 < np && pt[k] != hi) k++;
        mlo = pt[k - 1];
        mhi = pt[k];
        float dlo = fp[k - 1], dhi = fp[k];
        fm = resid(&c, 0.5f * (mlo + mhi), &xm);
        if (fm > fmaxf(dlo, dhi) || fm < fminf(dlo, dhi)) {
            const float g = 0.381966f;
            float sgn = fm > fmaxf(dlo, dhi) ? 1.0f : -1.0f, a = mlo, b = mhi;
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
            if (fp[i] == 0.0f) consider(0, pt[i], 0.0f, xp[i], &bv, &bt, &bd, &sol->fam);
            if (i + 1 < np && fp[i] != 0.0f && fp[i + 1] != 0.0f && (fp[i] < 0.0f) != (fp[i + 1] < 0.0f)) {
                float fr, r = root(&c, pt[i], pt[i + 1], fp[i], fp[i + 1], xp[i], xp[i + 1], &x, &fr);
                float tcr = (r != 0.0f && fr * r < 0.0f) ? -fr / r : 0.0f;
                consider(0, r, tcr, x + tcr, &bv, &bt, &bd, &sol->fam);
            }
        }
    }
    {
        /* A root a float ulp away from the velocity the start state reaches anyway (vs)
         * would add a pulse of 2 sqrt(eps / jmax) seconds: take vs itself when it is a root to
         * float precision, and let a short cruise absorb the residual when its sign allows. */
        float fn = fn0, xn = xn0, tn = 0.0f;
        if (fn != fn) fn = resid(&c, vn, &xn); /* vs was not among the points */
        if (fabsf(fn) <= 2e-7f * (fabsf(dp) + (fabsf(v0) + c.vs) * xn)) {
            if (vn != 0.0f && -fn / vn >= 0.0f) tn = -fn / vn;
            /* preferred over a candidate up to 1e-6 relative shorter */
            if (xn + tn - 1e-6f * xn < bd) keep(0, vn, tn, xn + tn, &bv, &bt, &bd, &sol->fam);
        }
    }
    if (!(bd < INFINITY)) {
        /* Not reachable for finite inputs (the pieces cover [-vn, vp] and the cruises the
         * rest); a defined answer. */
        bv = 0.0f;
        bt = 0.0f;
        sol->fam = 0;
    }
    sol->x = bv;
    sol->tc = bt;
    sol->t = bd < INFINITY ? bd : 0.0f;
    if (scurve && p->af != 0.0f) {
        if (!(bd < INFINITY)) sol->t = INFINITY;
        solve_dips_moving(p, sol);
        solve_holds(p, sol);
        if (!(sol->t < INFINITY)) sol->t = 0.0f;
    }
}

/* A profile of exactly duration T >= the minimum. First bracket: lower |vc| from vc* toward 0
 * (the residual changes sign on [0, vc*] when the displacement is monotone there). When it
 * does not (the two-stage piece between vs and ve is not monotone), scan [-vn, vp] at
 * QO_MOTION_SYNC_SCAN points plus 0, vs, ve and vc* and take the sign change, with a
 * non-negative cruise, nearest vc*. Returns 0 if no such profile was found. */
#define QO_MOTION_SYNC_SCAN 9
int qo_motion_solve_time(const mprob *p, const msol *min, float vcs, float T, msol *sol)
{
    float f0 = min->f0, t0 = min->t0, mx = min->x; /* read first: min may be sol */
    int dip = min->fam == 1;
    rctx c;
    const mlim *l = &p->l;
    float fa, fb, tca, tcb, fr;
    float xs[QO_MOTION_SYNC_SCAN + 4], gs[QO_MOTION_SYNC_SCAN + 4], ts[QO_MOTION_SYNC_SCAN + 4];
    float bestd = INFINITY;
    unsigned n = 0, i, k;
    sol->fam = 0;
    sol->t = T;
    if (p->scurve && p->v0 == 0.0f && p->a0 == 0.0f && p->vf == 0.0f && p->af == 0.0f && l->ap == l->an &&
        rest_time(p, T, &sol->x, &sol->tc))
        return 1;
    c = rctx_make(p, 1, T);
    /* The profile through 0 has the displacement d and duration t0 the minimum solve found; here
     * its residual is d + 0 (T - t0) - dp, which is f0 = d - dp bit for bit when all are finite
     * (d is never -0: eval_segs sums from +0). */
    if (fabsf(f0) <= FLT_MAX && fabsf(t0) <= FLT_MAX && fabsf(T) <= FLT_MAX) {
        fa = f0;
        tca = T - t0;
    } else {
        fa = resid(&c, 0.0f, &tca);
    }
    /* After a dip (to acceleration mx) the profile of exactly T usually has its extremum between
     * 0 and the dip's own (where the dip's pulse brings the acceleration to zero), while vcs
     * (vs, where the dip family meets this one) can lie on the other side of 0 and leave only
     * the scan: that bracket is tried first. A root there is a profile of exactly T with a
     * non-negative cruise, as any the scan finds; without one the search goes on as before. */
    if (dip && p->scurve && p->af == 0.0f && fa != 0.0f && fa == fa) {
        float J = l->j, d = fabsf(mx - p->a0) / J, vx, fx, tcx, tx;
        vx = p->v0 + d * (p->a0 + 0.5f * d * (mx >= p->a0 ? J : -J));
        vx = clamp_v(vx + mx * fabsf(mx) / (2.0f * J), l);
        fx = resid(&c, vx, &tcx);
        if (fx == fx && (fa < 0.0f) != (fx < 0.0f)) {
            float x = root(&c, 0.0f, vx, fa, fx, tca, tcx, &tx, &fr);
            if (tx >= -1e-5f * T) {
                sol->x = x;
                sol->tc = tx < 0.0f ? 0.0f : tx; /* rounding */
                return 1;
            }
        }
    }
    fb = resid(&c, vcs, &tcb);
    if (fa != 0.0f && (fa < 0.0f) != (fb < 0.0f)) {
        sol->x = root(&c, 0.0f, vcs, fa, fb, tca, tcb, &sol->tc, &fr);
        if (sol->tc >= -1e-5f * T) {
            if (sol->tc < 0.0f) sol->tc = 0.0f; /* rounding */
            return 1;
        }
    }
    /* Scan: sorted points, the sign changes whose root has a non-negative cruise. */
    {
        float vn = p->scurve ? p->v0 + p->a0 * fabsf(p->a0) / (2.0f * l->j) : p->v0;
        float ve = p->scurve ? p->vf - p->af * fabsf(p->af) / (2.0f * l->j) : p->vf;
        xs[n++] = 0.0f;
        xs[n++] = vcs;
        xs[n++] = clamp_v(vn, l);
        xs[n++] = clamp_v(ve, l);
        /* the grid spans the velocities a profile can use (the limits, or the problem's
         * scale where that is smaller: a grid over +-1e8 misses a root near 1) */
        float gn = fminf(l->vn, c.vs), gp = fminf(l->vp, c.vs);
        for (k = 0; k < QO_MOTION_SYNC_SCAN; k++)
            xs[n++] = -gn + (gp + gn) * (float)k / (float)(QO_MOTION_SYNC_SCAN - 1);
        for (i = 1; i < n; i++) {
            float x = xs[i];
            k = i;
            while (k > 0 && xs[k - 1] > x) {
                xs[k] = xs[k - 1];
                k--;
            }
            xs[k] = x;
        }
        /* 0, vcs, vs and ve often coincide with each other or a grid point (0 is one): each
         * distinct value is evaluated once (the same bits give the same residual) */
        for (i = 0; i < n; i++) {
            if (i > 0 && same_bits(xs[i], xs[i - 1])) {
                gs[i] = gs[i - 1];
                ts[i] = ts[i - 1];
            } else if (same_bits(xs[i], 0.0f)) {
                gs[i] = fa;
                ts[i] = tca;
            } else if (same_bits(xs[i], vcs)) {
                gs[i] = fb;
                ts[i] = tcb;
            } else {
                gs[i] = resid(&c, xs[i], &ts[i]);
            }
        }
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
                sol->x = r;
                sol->tc = tr;
            }
        }
    }
    if (bestd < INFINITY) return 1;
    /* Stop, then wait at rest, if the minimum solve itself was a stop (vc* ~ 0). */
    sol->x = 0.0f;
    sol->tc = tca;
    return tca >= 0.0f && fabsf(fa) <= 1e-4f * (fabsf(p->dp) + c.vs * T);
}

unsigned qo_motion_vchange(int scurve, float v0, float a0, float v1, const mlim *l, mseg *out)
{
    return vchange(scurve, v0, a0, v1, l, out);
}
