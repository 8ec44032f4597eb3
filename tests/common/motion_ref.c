/* Independent minimum-time reference for one jerk-limited joint. See motion_ref.h. */
#include "common/motion_ref.h"

#include <math.h>
#include <stddef.h>

/* One transfer: at most 3 phases of (duration, jerk). */
typedef struct xph {
    double d[3], j[3];
    double t;
} xph;

/* Fastest (v0, a0) -> (v1, a1): a pulse up-then-down (peak ap >= max(a0, a1)) or
 * down-then-up, the peak from the velocity balance (2 ap^2 - a0^2 - a1^2) / (2 J) = v1 - v0,
 * clipped to the acceleration bound with a hold. Returns 0 if neither pulse exists. */
static int xfer_dir(double s, double v0, double a0, double v1, double a1, double abound, double J, xph *x)
{
    /* s = +1: up-down with bound amax; s = -1: the mirror image (down-up, bound |amin|). */
    double b0 = s * a0, b1 = s * a1, dv = s * (v1 - v0), m = fmax(b0, b1);
    double X = J * dv + 0.5 * (b0 * b0 + b1 * b1), ap, h = 0.0;
    if (X < 0.0) {
        if (X < -1e-12 * (J * fabs(dv) + b0 * b0 + b1 * b1)) return 0;
        X = 0.0;
    }
    if (-sqrt(X) >= m - 1e-12 * (fabs(m) + sqrt(X))) ap = -sqrt(X);
    else if (sqrt(X) >= m - 1e-12 * (fabs(m) + sqrt(X))) ap = sqrt(X);
    else return 0;
    if (ap < m) ap = m;
    if (m > abound * (1.0 + 1e-12)) return 0;
    if (ap > abound) {
        ap = abound;
        h = (dv - (ap * ap - b0 * b0) / (2 * J) - (ap * ap - b1 * b1) / (2 * J)) / ap;
        if (h < 0.0) h = 0.0;
    }
    x->d[0] = (ap - b0) / J;
    x->j[0] = s * J;
    x->d[1] = h;
    x->j[1] = 0.0;
    x->d[2] = (ap - b1) / J;
    x->j[2] = -s * J;
    x->t = x->d[0] + x->d[1] + x->d[2];
    return 1;
}

static int xfer(const mref_lim *l, double v0, double a0, double v1, double a1, xph *x)
{
    xph u, w;
    int ou = xfer_dir(1.0, v0, a0, v1, a1, l->amax, l->jmax, &u);
    int ow = xfer_dir(-1.0, v0, a0, v1, a1, -l->amin, l->jmax, &w);
    if (ou && (!ow || u.t <= w.t)) *x = u;
    else if (ow) *x = w;
    else return 0;
    return 1;
}

typedef struct rstate {
    double p, v, a;
    int ok; /* 0 once the velocity leaves [vmin, vmax] */
} rstate;

/* Integrates one phase exactly, checking the velocity at its end and at an interior
 * acceleration zero (the only place a velocity extremum can be). */
static void run(const mref_lim *l, rstate *s, double d, double j)
{
    double tol = 1e-9 * (l->vmax - l->vmin);
    if (d <= 0.0) return;
    if (j != 0.0) {
        double tz = -s->a / j;
        if (tz > 0.0 && tz < d) {
            double vz = s->v + s->a * tz + 0.5 * j * tz * tz;
            if (vz > l->vmax + tol || vz < l->vmin - tol) s->ok = 0;
        }
    }
    s->p += d * (s->v + d * (0.5 * s->a + d * j / 6.0));
    s->v += d * (s->a + 0.5 * d * j);
    s->a += d * j;
    if (s->v > l->vmax + tol || s->v < l->vmin - tol) s->ok = 0;
}

typedef struct rprob {
    const mref_lim *l;
    double p0, v0, a0, pf, vf, af;
    double tol; /* position residual accepted as a root */
    double vs, vfloor; /* velocity scale of the move and its smallest (mref_min_time) */
    double as, afloor; /* the same for accelerations */
} rprob;

/* Position residual of the profile through junction (vm, am) with a cruise of tc, its
 * duration in *T and its validity (velocity bounds) in *ok. NaN if a transfer is missing. */
static double eval(const rprob *q, double vm, double am, double tc, double *T, int *ok)
{
    xph x1, x2;
    rstate s;
    int k;
    if (!xfer(q->l, q->v0, q->a0, vm, am, &x1) || !xfer(q->l, vm, am, q->vf, q->af, &x2)) {
        *ok = 0;
        *T = INFINITY;
        return NAN;
    }
    s.p = q->p0;
    s.v = q->v0;
    s.a = q->a0;
    s.ok = 1;
    for (k = 0; k < 3; k++) run(q->l, &s, x1.d[k], x1.j[k]);
    s.p += vm * tc;
    for (k = 0; k < 3; k++) run(q->l, &s, x2.d[k], x2.j[k]);
    *ok = s.ok;
    *T = x1.t + tc + x2.t;
    return s.p - q->pf;
}

/* Every vm root of the position residual at junction acceleration am; keeps the fastest valid
 * profile in *best. */
#define MREF_NV 48
#define MREF_NEST 6 /* nested grids at most (wide limits) */
static double ramp_vm(const rprob *q, int side, double am);

static void scan_am(const rprob *q, double am, double *best)
{
    const mref_lim *l = q->l;
    double xs[(MREF_NEST + 1) * (MREF_NV + 1) + 4], fs[(MREF_NEST + 1) * (MREF_NV + 1) + 4], T, f, J = l->jmax, s;
    int i, k, n = 0, ok;
    for (i = 0; i <= MREF_NV; i++) xs[n++] = l->vmin + (l->vmax - l->vmin) * i / MREF_NV;
    /* Limits far above what the move uses (vmax 1e8 for a move at 2 units/s): the same grid
     * over +-vs, vs/8, vs/64, ... down to the move's own speed, else its spacing hides roots. */
    for (s = q->vs, k = 0; k < MREF_NEST && s >= q->vfloor; s *= 0.125, k++) {
        double lo = fmax(l->vmin, -s), hi = fmin(l->vmax, s);
        if (hi - lo >= 0.125 * (l->vmax - l->vmin)) continue;
        for (i = 0; i <= MREF_NV; i++) xs[n++] = lo + (hi - lo) * i / MREF_NV;
    }
    /* The junction velocities where a transfer changes from one pulse to the other (a single
     * ramp) and the start's and the end's zero-acceleration velocities: two roots of the
     * residual can lie between two grid points there (check-motion found a joint the grid
     * missed, 1.70 s for a 0.076 s profile). */
    xs[n++] = ramp_vm(q, 0, am);
    xs[n++] = ramp_vm(q, 1, am);
    xs[n++] = q->v0 + q->a0 * fabs(q->a0) / (2.0 * J);
    xs[n++] = q->vf - q->af * fabs(q->af) / (2.0 * J);
    for (i = 1; i < n; i++) {
        double x = xs[i];
        for (k = i; k > 0 && xs[k - 1] > x; k--) xs[k] = xs[k - 1];
        xs[k] = x;
    }
    for (i = 0; i < n; i++) {
        if (xs[i] < l->vmin) xs[i] = l->vmin;
        if (xs[i] > l->vmax) xs[i] = l->vmax;
        fs[i] = eval(q, xs[i], am, 0.0, &T, &ok);
        if (fs[i] == 0.0 && ok && T < *best) *best = T;
    }
    for (i = 0; i + 1 < n; i++) {
        double lo = xs[i], hi = xs[i + 1], flo = fs[i], fhi = fs[i + 1];
        int it;
        if (!(flo * fhi < 0.0)) continue;
        for (it = 0; it < 60; it++) {
            double mid = 0.5 * (lo + hi), fm = eval(q, mid, am, 0.0, &T, &ok);
            if (fm == 0.0 || mid == lo || mid == hi) {
                lo = hi = mid;
                break;
            }
            if ((fm < 0.0) == (flo < 0.0)) {
                lo = mid;
                flo = fm;
            } else {
                hi = mid;
            }
        }
        /* A sign change can also be a jump (a transfer switching to another pulse): only a
         * true root counts. */
        f = eval(q, 0.5 * (lo + hi), am, 0.0, &T, &ok);
        if (ok && fabs(f) <= q->tol && T < *best) *best = T;
    }
}

/* Junction velocity that makes a transfer a single ramp: from (v0, a0) to acceleration am
 * (side 0), or from am into (vf, af) (side 1). */
static double ramp_vm(const rprob *q, int side, double am)
{
    double J = q->l->jmax;
    if (side == 0) return q->v0 + (am * am - q->a0 * q->a0) / (2.0 * (am >= q->a0 ? J : -J));
    return q->vf - (q->af * q->af - am * am) / (2.0 * (q->af >= am ? J : -J));
}

/* The profiles where one transfer is a single ramp lie where the fastest transfer jumps from a
 * short pulse to a long one (e.g. raising v while a < 0 needs a pulse through a > 0), so the
 * vm scan cannot bracket them: scan am along each ramp curve instead. */
#define MREF_NR 400
static void scan_ramps_on(const rprob *q, double alo, double ahi, double *best)
{
    int side, i;
    for (side = 0; side < 2; side++) {
        double px = 0.0, pf = NAN, T, f;
        int ok;
        for (i = 0; i <= MREF_NR; i++) {
            double am = alo + (ahi - alo) * i / MREF_NR;
            f = eval(q, ramp_vm(q, side, am), am, 0.0, &T, &ok);
            if (ok && fabs(f) <= q->tol && T < *best) *best = T;
            if (i > 0 && f * pf < 0.0) {
                double lo = px, hi = am, flo = pf;
                int it;
                for (it = 0; it < 60; it++) {
                    double mid = 0.5 * (lo + hi), fm = eval(q, ramp_vm(q, side, mid), mid, 0.0, &T, &ok);
                    if ((fm < 0.0) == (flo < 0.0)) {
                        lo = mid;
                        flo = fm;
                    } else {
                        hi = mid;
                    }
                }
                f = eval(q, ramp_vm(q, side, 0.5 * (lo + hi)), 0.5 * (lo + hi), 0.0, &T, &ok);
                if (ok && fabs(f) <= q->tol && T < *best) *best = T;
                f = eval(q, ramp_vm(q, side, am), am, 0.0, &T, &ok);
            }
            px = am;
            pf = f;
        }
    }
}

/* Over the whole acceleration range, then (limits far above what the move uses) over the
 * nested ranges +-as, as/8, ... down to the move's own accelerations, as scan_am does: on a grid
 * over amax 7e5 (spacing 3500) a ramp into a target acceleration from am = -9.5 fell between two
 * points and the reference answered 1.023 s for a 0.187 s profile (make check-motion wide case
 * 4593). */
static void scan_ramps(const rprob *q, double *best)
{
    const mref_lim *l = q->l;
    double s;
    int k;
    scan_ramps_on(q, l->amin, l->amax, best);
    for (s = q->as, k = 0; k < MREF_NEST && s >= q->afloor; s *= 0.125, k++) {
        double lo = fmax(l->amin, -s), hi = fmin(l->amax, s);
        if (hi - lo >= 0.125 * (l->amax - l->amin)) continue;
        scan_ramps_on(q, lo, hi, best);
    }
}

double mref_min_time(const mref_lim *l, double p0, double v0, double a0, double pf, double vf, double af)
{
    rprob q = { l, p0, v0, a0, pf, vf, af, 1e-9 * (1.0 + fabs(p0) + fabs(pf)), 0.0, 0.0, 0.0, 0.0 };
    double best = INFINITY, bam = 0.0, T, f, h, as, ah, afloor;
    int i, ok, lev;
    double special[5];
    if (p0 == pf && v0 == vf && a0 == af) return 0.0;
    {
        /* Velocities and accelerations a near-optimal profile can use, with a wide margin:
         * the states' speeds (with their acceleration ramps), a stop from them, then the
         * distance back from rest at the acceleration or jerk limit. */
        double A = fmax(l->amax, -l->amin), J = l->jmax;
        double w = fabs(v0) + fabs(vf) + (a0 * a0 + af * af) / J;
        double ts = w / A + 3.0 * sqrt(w / J) + (fabs(a0) + fabs(af)) / J;
        double L = fabs(pf - p0) + 2.0 * w * ts;
        double D = fabs(pf - p0);
        q.vs = 8.0 * (w + fmin(sqrt(A * L), cbrt(L * L * J)));
        q.vfloor = 0.5 * (w + fmin(sqrt(A * D), cbrt(D * D * J)));
        as = 8.0 * (fabs(a0) + fabs(af) + sqrt(J * q.vs));
        afloor = 0.5 * (fabs(a0) + fabs(af) + sqrt(J * q.vfloor));
        q.as = as;
        q.afloor = afloor;
    }
    /* Cruise on a velocity bound (junction (vmax, 0) or (vmin, 0)). */
    f = eval(&q, l->vmax, 0.0, 0.0, &T, &ok);
    if (ok && f <= 0.0) best = fmin(best, T - f / l->vmax);
    f = eval(&q, l->vmin, 0.0, 0.0, &T, &ok);
    if (ok && f >= 0.0) best = fmin(best, T - f / l->vmin);
    scan_ramps(&q, &best);
    special[0] = l->amin;
    special[1] = l->amax;
    special[2] = 0.0;
    special[3] = a0;
    special[4] = af;
    for (i = 0; i < 5; i++) {
        double b = best;
        scan_am(&q, special[i], &best);
        if (best < b) bam = special[i];
    }
    for (i = 0; i <= MREF_NV; i++) {
        double am = l->amin + (l->amax - l->amin) * i / MREF_NV, b = best;
        scan_am(&q, am, &best);
        if (best < b) bam = am;
    }
    /* Limits far above what the move uses: the same scan over the accelerations it can use. */
    ah = (l->amax - l->amin) / MREF_NV;
    for (lev = 0; lev < MREF_NEST && as >= afloor; as *= 0.125, lev++) {
        double lo = fmax(l->amin, -as), hi = fmin(l->amax, as);
        if (hi - lo >= 0.125 * (l->amax - l->amin)) continue;
        for (i = 0; i <= MREF_NV; i++) {
            double am = lo + (hi - lo) * i / MREF_NV, b = best;
            scan_am(&q, am, &best);
            if (best < b) {
                bam = am;
                ah = (hi - lo) / MREF_NV;
            }
        }
    }
    /* Refine the junction acceleration around the best so far (on the grid it came from). */
    h = ah;
    for (lev = 0; lev < 3; lev++) {
        double c = bam;
        for (i = -10; i <= 10; i++) {
            double am = c + h * i / 10.0, b = best;
            if (am < l->amin || am > l->amax || i == 0) continue;
            scan_am(&q, am, &best);
            if (best < b) bam = am;
        }
        h /= 10.0;
    }
    return best < INFINITY ? best : -1.0;
}

double mref_vel_time(const mref_lim *l, double v0, double a0, double v1, double a1)
{
    xph x;
    return xfer(l, v0, a0, v1, a1, &x) ? x.t : -1.0;
}

double mref_rest_time(double D, double V, double A, double J)
{
    double d = fabs(D), ta, tj, tv;
    if (d == 0.0) return 0.0;
    /* Reaching A needs A/J of ramp; reaching V needs V/A + A/J (or 2 sqrt(V/J) without hold). */
    if (V * J >= A * A) {
        tj = A / J;
        ta = V / A - A / J;
    } else {
        tj = sqrt(V / J);
        ta = 0.0;
    }
    /* Distance of the full accelerate-decelerate to V with no cruise. */
    if (d >= V * (2 * tj + ta)) {
        tv = (d - V * (2 * tj + ta)) / V;
        return 4 * tj + 2 * ta + tv;
    }
    /* No cruise: is the acceleration limit still reached? */
    if (d >= 2 * A * A * A / (J * J)) {
        tj = A / J;
        ta = 0.5 * (-3 * tj + sqrt(tj * tj + 4 * d / A)); /* d = A (ta + tj)(ta + 2 tj) */
        return 4 * tj + 2 * ta;
    }
    tj = cbrt(d / (2 * J));
    return 4 * tj;
}

void mref_vchange(double v0, double a0, double v1, double A, double J, double *dp, double *dt)
{
    double vn = v0 + a0 * fabs(a0) / (2 * J), s = v1 >= vn ? 1 : -1, as = s * a0, dv = s * (v1 - v0), ap;
    double t[3], jj[3], p = 0, v = v0, a = a0;
    int k;
    if (as >= A) ap = A;
    else {
        ap = sqrt(fmax(J * dv + 0.5 * as * as, 0));
        if (ap > A) ap = A;
        if (ap < as) ap = as;
    }
    t[0] = fabs(ap - as) / J;
    t[2] = ap / J;
    t[1] = ap > 0 ? (dv - 0.5 * (as + ap) * t[0] - 0.5 * ap * t[2]) / ap : 0;
    if (t[1] < 0) t[1] = 0;
    jj[0] = (ap >= as ? 1 : -1) * s * J;
    jj[1] = 0;
    jj[2] = -s * J;
    for (k = 0; k < 3; k++) {
        double d = t[k];
        p += v * d + a * d * d / 2 + jj[k] * d * d * d / 6;
        v += a * d + jj[k] * d * d / 2;
        a += jj[k] * d;
    }
    *dp = p;
    *dt = t[0] + t[1] + t[2];
}

/* One transfer run from state s (velocity bounds checked): appends its phases to pr. */
static void run_xfer(const mref_lim *l, rstate *s, const xph *x, mref_prof *pr)
{
    int k;
    for (k = 0; k < 3; k++) {
        run(l, s, x->d[k], x->j[k]);
        if (pr && x->d[k] > 0.0) {
            pr->d[pr->n] = x->d[k];
            pr->j[pr->n++] = x->j[k];
        }
    }
}

/* The three transfers of the two-cruise family, (v0, a0) -> (v1, 0) -> (v2, 0) -> (vf, af), run
 * from p0 without the cruises: 0 if one does not exist, else the state after them in *st (st->ok
 * 0 if a velocity bound was crossed). */
static int chain(const mref_lim *l, const double *s0, double v1, double v2, double vf, double af, xph *x, rstate *st)
{
    if (!xfer(l, s0[1], s0[2], v1, 0.0, &x[0]) || !xfer(l, v1, 0.0, v2, 0.0, &x[1]) || !xfer(l, v2, 0.0, vf, af, &x[2]))
        return 0;
    st->p = s0[0];
    st->v = s0[1];
    st->a = s0[2];
    st->ok = 1;
    run_xfer(l, st, &x[0], NULL);
    run_xfer(l, st, &x[1], NULL);
    run_xfer(l, st, &x[2], NULL);
    return 1;
}

#define MREF_NX 160
int mref_exact_time(const mref_lim *l, double p0, double v0, double a0, double pf, double vf, double af, double T,
                    mref_prof *out)
{
    double xs[MREF_NX + 5], s0[3], best = -1.0, bv1 = 0.0, bv2 = 0.0, J = l->jmax, tol = 1e-12 * (1.0 + T);
    int n = 0, i, k;
    xph x[3];
    rstate st;
    s0[0] = p0;
    s0[1] = v0;
    s0[2] = a0;
    for (i = 0; i <= MREF_NX; i++) xs[n++] = l->vmin + (l->vmax - l->vmin) * i / MREF_NX;
    xs[n++] = 0.0;
    xs[n++] = fmin(fmax(v0 + a0 * fabs(a0) / (2.0 * J), l->vmin), l->vmax);
    xs[n++] = fmin(fmax(vf - af * fabs(af) / (2.0 * J), l->vmin), l->vmax);
    xs[n++] = fmin(fmax(vf, l->vmin), l->vmax);
    for (i = 0; i < n; i++) {
        for (k = 0; k < n; k++) {
            double v1 = xs[i], v2 = xs[k], R, S, m;
            if (v1 == v2 || !chain(l, s0, v1, v2, vf, af, x, &st) || !st.ok) continue;
            R = T - x[0].t - x[1].t - x[2].t;
            if (R < -tol) continue;
            /* t1 + t2 = R, v1 t1 + v2 t2 = S: S between v1 R and v2 R */
            S = pf - st.p;
            m = fmin(S - fmin(v1, v2) * R, fmax(v1, v2) * R - S);
            if (m >= 0.0 && m > best) {
                best = m;
                bv1 = v1;
                bv2 = v2;
            }
        }
    }
    if (!(best >= 0.0)) return 0;
    if (out) {
        double R, S, t1, t2;
        chain(l, s0, bv1, bv2, vf, af, x, &st);
        R = fmax(T - x[0].t - x[1].t - x[2].t, 0.0);
        S = pf - st.p;
        t1 = fmin(fmax((S - bv2 * R) / (bv1 - bv2), 0.0), R);
        t2 = R - t1;
        out->n = 0;
        run_xfer(l, &st, &x[0], out);
        if (t1 > 0.0) {
            out->d[out->n] = t1;
            out->j[out->n++] = 0.0;
        }
        run_xfer(l, &st, &x[1], out);
        if (t2 > 0.0) {
            out->d[out->n] = t2;
            out->j[out->n++] = 0.0;
        }
        run_xfer(l, &st, &x[2], out);
    }
    return 1;
}
