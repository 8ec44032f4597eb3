/* Interpolation on the unit-quaternion sphere, fixed point (Q1.30). See qorient/interp_fx.h
 * for the contract of each function; the constructions mirror lib/src/interp.c. Integer
 * arithmetic only: int32 values, int64 intermediates, no floating point, no libm. */
#include "qorient/interp_fx.h"

#include "qorient/fxmath.h"
#include "qorient/quat_fx.h"

#include "fx_internal.h"

#define ONE64 ((int64_t)QO_Q30_ONE)
/* 1/3 and 2/3 in Q1.30, rounded to nearest. */
#define THIRD_Q30 ((int64_t)357913941)
#define TWO_THIRDS_Q30 ((int64_t)715827883)

/* Taylor coefficients of sinc(x) = sin(x)/x in the variable v = x^2/16, Q1.31 (rounded):
 * C_k = (-16)^k / (2k+1)!. Scaling by 16 keeps v <= 0.62 for |x| <= pi, so every coefficient's
 * rounding (2^-32) costs at most 2^-32 * v^k in the sum, and the Horner partial sums stay
 * below 2.7 (|v * h| < 2^63). Truncation after k = 10: < pi^22/23! = 3.4e-12. */
static const int64_t sinc_c[11] = {
    2147483648LL, -5726623061LL, 4581298449LL, -1745256552LL, 387834789LL, -56412333LL,
    5785880LL, -440829LL, 25931LL, -1213LL, 46LL
};

static qo_quat_q30 identity_q(void)
{
    qo_quat_q30 r = { QO_Q30_ONE, 0, 0, 0 };
    return r;
}

/* -q for a unit q (|components| <= 2^30: no overflow). */
static qo_quat_q30 neg_q(qo_quat_q30 q)
{
    qo_quat_q30 r;
    r.w = -q.w; r.x = -q.x; r.y = -q.y; r.z = -q.z;
    return r;
}

static int is_zero_q(qo_quat_q30 q)
{
    return q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0;
}

/* Unit quaternion v/|v| of an int64 4-vector of any scale (the format cancels), rounded to
 * nearest per component. Returns 0 (and identity) for the zero vector.
 * The vector is scaled by a power of two so that its largest component is in [2^30, 2^31]:
 * exact for every int32 input (a quaternion input is never rounded here), one rounding of
 * <= 2^-31 relative for the wide internal sums. The squares are then exact (<= 2^62) and
 * summed as quarters (n4 = |w|^2/4 <= 2^62, truncation 2^-60 relative); the square root is
 * taken with 2^(k/2) extra bits (N >= 2^31: 2^-32 relative), and each component is one
 * rounded 64-bit division: <= 0.75 LSB from the exact unit vector for an int32 input. */
static int unit_from_i64(const int64_t v[4], qo_quat_q30 *out)
{
    uint64_t m = 0, n4 = 0, N, num, q;
    int64_t w[4];
    unsigned sh = 0, k;
    int i;
    for (i = 0; i < 4; i++) {
        uint64_t av = qo_fx_abs_u64(v[i]);
        if (av > m) m = av;
    }
    if (m == 0) {
        *out = identity_q();
        return 0;
    }
    if (m > ((uint64_t)1 << 31)) {
        while ((m >> sh) > ((uint64_t)1 << 31)) sh++;
        /* m >> sh in (2^30, 2^31]; after rounding the largest is at most 2^31. */
        for (i = 0; i < 4; i++) w[i] = qo_fx_rshift_round_up(v[i], sh);
    } else {
        while ((m << sh) < ((uint64_t)1 << 30)) sh++;
        for (i = 0; i < 4; i++) w[i] = v[i] * ((int64_t)1 << sh);   /* exact, no shift of < 0 */
    }
    for (i = 0; i < 4; i++) n4 += (uint64_t)(w[i] * w[i]) >> 2;
    /* n4 in [2^58, 2^62]: the largest even k with n4 * 2^k < 2^64 (at most 4). */
    k = (n4 < ((uint64_t)1 << 60)) ? 4u : (n4 < ((uint64_t)1 << 62)) ? 2u : 0u;
    N = qo_fx_sqrt_u64(n4 << k);   /* |w|/2 * 2^(k/2), >= 2^31 */
    for (i = 0; i < 4; i++) {
        qo_q30 c;
        /* w_i 2^30 / |w| = w_i 2^(29 + k/2) / N; |w_i| 2^(29 + k/2) <= 2^31 * 2^31. */
        num = qo_fx_abs_u64(w[i]) << (29u + k / 2u);
        q = (num + N / 2u) / N;
        c = (qo_q30)q;   /* <= 2^30 */
        if (w[i] < 0) c = -c;
        if (i == 0) out->w = c;
        else if (i == 1) out->x = c;
        else if (i == 2) out->y = c;
        else out->z = c;
    }
    return 1;
}

/* Checks and normalises one orientation input: QO_E_DEGENERATE (and identity) for zero.
 * qo_quat_normalize_q30 itself, so "unit a" in the header is exactly its result. */
static qo_status unit_in(qo_quat_q30 q, qo_quat_q30 *u)
{
    return qo_quat_normalize_q30(q, u);
}

/* Checks two orientation inputs; the first failure wins (both are written). */
static qo_status unit_in2(qo_quat_q30 a, qo_quat_q30 b, qo_quat_q30 *ua, qo_quat_q30 *ub)
{
    qo_status sa = unit_in(a, ua), sb = unit_in(b, ub);
    return (sa != QO_OK) ? sa : sb;
}

/* dot(a, b) in Q2.60, exact, for unit a, b (each product <= 2^60). */
static int64_t dot60(qo_quat_q30 a, qo_quat_q30 b)
{
    return (int64_t)a.w * b.w + (int64_t)a.x * b.x + (int64_t)a.y * b.y + (int64_t)a.z * b.z;
}

/* b, negated when it lies in the other hemisphere than ref. dot == 0 keeps b. */
static qo_quat_q30 align_to(qo_quat_q30 b, qo_quat_q30 ref)
{
    return (dot60(ref, b) < 0) ? neg_q(b) : b;
}

/* 4-D angle between unit a and unit b in [0, pi], Q3.28: 2*atan2(|a-b|, |a+b|). The sums and
 * differences are exact, their squares summed exactly in 64 bits (<= 2^62.1 for unit inputs),
 * so the small one of the two lengths keeps its absolute accuracy (0.5 LSB of Q1.30). */
static qo_q28 angle4(qo_quat_q30 a, qo_quat_q30 b)
{
    int64_t dw = (int64_t)a.w - b.w, dx = (int64_t)a.x - b.x;
    int64_t dy = (int64_t)a.y - b.y, dz = (int64_t)a.z - b.z;
    int64_t sw = (int64_t)a.w + b.w, sx = (int64_t)a.x + b.x;
    int64_t sy = (int64_t)a.y + b.y, sz = (int64_t)a.z + b.z;
    uint64_t d2 = (uint64_t)(dw * dw) + (uint64_t)(dx * dx) + (uint64_t)(dy * dy) +
                  (uint64_t)(dz * dz);
    uint64_t s2 = (uint64_t)(sw * sw) + (uint64_t)(sx * sx) + (uint64_t)(sy * sy) +
                  (uint64_t)(sz * sz);
    uint64_t d = qo_fx_sqrt_u64(d2), s = qo_fx_sqrt_u64(s2);
    /* Lengths up to 2 (+rounding) in Q1.30 can reach 2^31: halve both (only the ratio counts). */
    if (d > (uint64_t)INT32_MAX || s > (uint64_t)INT32_MAX) {
        d = (d + 1u) >> 1;
        s = (s + 1u) >> 1;
    }
    return (qo_q28)(2 * qo_fx_atan2_q28((int32_t)d, (int32_t)s));
}

/* sin(x)/x in Q1.31 for x in Q3.28 (int64), |x| <= pi (+ a few LSB). */
static int64_t sinc_q31(int64_t x)
{
    int64_t v = qo_fx_rshift_round_up(x * x, 29);   /* x^2 (Q56) / 16 -> Q31, <= 0.62 * 2^31 */
    int64_t h = sinc_c[10];
    int k;
    for (k = 9; k >= 0; k--) h = sinc_c[k] + qo_fx_rshift_round_up(v * h, 31);
    return h;
}

/* w(u) = sin(u th)/th = u * sinc(u th) in Q1.31 (int64), u in Q1.30 (int64), th in Q3.28,
 * |u th| <= pi. Relative accuracy ~1e-9 for every th, including th == 0 (w = u exactly). */
static int64_t weight_q31(int64_t u, qo_q28 th)
{
    int64_t ut = qo_fx_rshift_round_up(u * th, 30);   /* Q3.28 */
    return qo_fx_rshift_round_up(u * sinc_q31(ut), 30);
}

/* Great-circle interpolation of unit a and b with th = angle4(a, b), u in Q1.30 within
 * [-1, 2] (extrapolation allowed), no sign flip, result normalised. th < pi - near-pi angle. */
static qo_quat_q30 slerp_weights(qo_quat_q30 a, qo_quat_q30 b, qo_q28 th, int64_t u)
{
    int64_t r[4];
    qo_quat_q30 n;
    if (th <= QO_Q28_HALF_PI + 8) {
        /* |u th| <= pi and |(1-u) th| <= pi for u in [-1, 2]. Weights <= 2 and |wa| + |wb|
         * <= 3 (Q1.31, 2^32.6), components <= 2^30: the sums stay below 2^63. */
        int64_t wa = weight_q31(ONE64 - u, th), wb = weight_q31(u, th);
        r[0] = wa * a.w + wb * b.w;
        r[1] = wa * a.x + wb * b.x;
        r[2] = wa * a.y + wb * b.y;
        r[3] = wa * a.z + wb * b.z;
    } else {
        /* Beyond 90 deg (extrapolated control points, pyramid levels) the weights grow like
         * 1/sin(th) and amplify the error of th. As in interp.c: rotate a towards the unit
         * direction e of the a-b plane orthogonal to a, out = cos(u th) a + sin(u th) e, with e
         * built from s = a + b (exact; small but with small RELATIVE error near th = pi) as
         * s - (s.a) a. s.a is exact in Q2.60 and split in a Q1.30 high part and a low part,
         * so e keeps the accuracy of s. */
        int64_t s[4], av[4], sa, hi, lo;
        qo_quat_q30 e;
        qo_q30 sn, cs;
        int i;
        av[0] = a.w; av[1] = a.x; av[2] = a.y; av[3] = a.z;
        s[0] = av[0] + b.w; s[1] = av[1] + b.x; s[2] = av[2] + b.y; s[3] = av[3] + b.z;
        sa = s[0] * av[0] + s[1] * av[1] + s[2] * av[2] + s[3] * av[3];
        hi = sa >> 30;
        lo = sa - hi * ((int64_t)1 << 30);   /* 0 <= lo < 2^30 */
        for (i = 0; i < 4; i++)
            r[i] = s[i] * ((int64_t)1 << 30) - hi * av[i] - qo_fx_rshift_round_up(lo * av[i], 30);
        (void)unit_from_i64(r, &e);
        /* u th in Q3.60: u (Q30) * th (Q28) is Q58, |u th| <= 2 pi < 8. */
        (void)qo_fx_sincos_q60(u * th * 4, &sn, &cs);
        r[0] = (int64_t)cs * a.w + (int64_t)sn * e.w;
        r[1] = (int64_t)cs * a.x + (int64_t)sn * e.x;
        r[2] = (int64_t)cs * a.y + (int64_t)sn * e.y;
        r[3] = (int64_t)cs * a.z + (int64_t)sn * e.z;
    }
    /* |r| is far from 0 in the allowed range of th, so this cannot fail. */
    (void)unit_from_i64(r, &n);
    return n;
}

/* Unchecked great-circle slerp for internal use (control points need u = 2, 1/2, +-1/3).
 * Returns 0 and *out = a when a and b are (nearly) antipodal, where the circle is undefined. */
static int slerp_raw(qo_quat_q30 a, qo_quat_q30 b, int64_t u, qo_quat_q30 *out)
{
    qo_q28 th = angle4(a, b);
    if (QO_Q28_PI - th < QO_INTERP_SLERP_NEAR_PI_Q28) {
        *out = a;
        return 0;
    }
    *out = slerp_weights(a, b, th, u);
    return 1;
}

static qo_status check_t(qo_q30 t)
{
    return (t < 0 || t > QO_Q30_ONE) ? QO_E_RANGE : QO_OK;
}

qo_status qo_interp_lerp_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q30 t, qo_quat_q30 *out)
{
    if (out == NULL) return QO_E_NULL;
    *out = a;
    if (check_t(t) != QO_OK) return QO_E_RANGE;
    /* a + round(t (b - a)): |t (b - a)| <= 2^30 * 2^32; the result lies between a and b,
     * so it fits (t == 1: b - a exactly). */
    out->w = (qo_q30)(a.w + qo_fx_rshift_round_up((int64_t)t * ((int64_t)b.w - a.w), 30));
    out->x = (qo_q30)(a.x + qo_fx_rshift_round_up((int64_t)t * ((int64_t)b.x - a.x), 30));
    out->y = (qo_q30)(a.y + qo_fx_rshift_round_up((int64_t)t * ((int64_t)b.y - a.y), 30));
    out->z = (qo_q30)(a.z + qo_fx_rshift_round_up((int64_t)t * ((int64_t)b.z - a.z), 30));
    return QO_OK;
}

qo_status qo_interp_nlerp_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q30 t, qo_quat_q30 *out)
{
    qo_quat_q30 ua, ub;
    qo_status st;
    int64_t r[4], ta, tb;
    if (out == NULL) return QO_E_NULL;
    st = unit_in2(a, b, &ua, &ub);
    if (st != QO_OK) {
        *out = identity_q();
        return st;
    }
    *out = ua;
    if (check_t(t) != QO_OK) return QO_E_RANGE;
    if (t == 0) return QO_OK;
    ub = align_to(ub, ua);
    if (t == QO_Q30_ONE) {
        *out = ub;
        return QO_OK;
    }
    ta = ONE64 - t;
    tb = t;
    r[0] = ta * ua.w + tb * ub.w;
    r[1] = ta * ua.x + tb * ub.x;
    r[2] = ta * ua.y + tb * ub.y;
    r[3] = ta * ua.z + tb * ub.z;
    /* After the flip dot >= 0, so |r| >= 1/sqrt(2): normalising cannot fail. */
    (void)unit_from_i64(r, out);
    return QO_OK;
}

/* Short (longway == 0) or long (longway != 0) slerp, as slerp_common in interp.c. */
static qo_status slerp_common(qo_quat_q30 a, qo_quat_q30 b, qo_q30 t, int longway,
                              qo_quat_q30 *out)
{
    qo_quat_q30 ua, ub;
    qo_status st;
    qo_q28 th;
    if (out == NULL) return QO_E_NULL;
    st = unit_in2(a, b, &ua, &ub);
    if (st != QO_OK) {
        *out = identity_q();
        return st;
    }
    *out = ua;
    if (check_t(t) != QO_OK) return QO_E_RANGE;
    /* The flipped copy is what every step below uses, so a and -a interpolate to a unit
     * quaternion, never through the origin. The long way puts b' on the far side of a
     * (dot == 0, exact in 64 bits, keeps b: both ways are 180 deg). */
    if (longway ? dot60(ua, ub) > 0 : dot60(ua, ub) < 0) ub = neg_q(ub);
    th = angle4(ua, ub);
    /* Long way between the same rotation (phi below 2e-3 rad): a full turn about an axis the
     * inputs no longer define (the rule and limit of qo_interp_slerp_long_f32). */
    if (longway && QO_Q28_PI - th < QO_INTERP_SLERP_NEAR_PI_Q28) return QO_E_DEGENERATE;
    if (t == 0) return QO_OK;
    if (t == QO_Q30_ONE) {
        *out = ub;
        return QO_OK;
    }
    /* th <= pi/2 (short) or in [pi/2, pi - 1e-3] (long, slerp_weights' rotation branch). */
    *out = slerp_weights(ua, ub, th, t);
    return QO_OK;
}

qo_status qo_interp_slerp_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q30 t, qo_quat_q30 *out)
{
    return slerp_common(a, b, t, 0, out);
}

/* round(p / 2^30) of an exact product sum (ties up). */
static int32_t rnd30_i32(int64_t p) { return (int32_t)qo_fx_rshift_round_up(p, 30); }

qo_status qo_interp_slerp_fast_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q30 t, qo_quat_q30 *out)
{
    qo_quat_q30 ua, ub, v, e;
    qo_status sa, sb;
    int64_t d;
    int32_t c, vn;
    qo_q30 sn, cs;
    qo_q28 th;
    if (out == NULL) return QO_E_NULL;
    sa = qo_quat_normalize_fast_q30(a, &ua);
    sb = qo_quat_normalize_fast_q30(b, &ub);
    if (sa != QO_OK || sb != QO_OK) {
        *out = identity_q();
        return sa != QO_OK ? sa : sb;
    }
    *out = ua;
    if (check_t(t) != QO_OK) return QO_E_RANGE;
    /* Products through qo_fx_mul32_i64: no libgcc 64-bit multiply on Cortex-M0. |ua|, |ub|
     * <= 1 (normalize_fast never exceeds 1), so every sum below stays far inside int64. */
    d = qo_fx_mul32_i64(ua.w, ub.w) + qo_fx_mul32_i64(ua.x, ub.x) + qo_fx_mul32_i64(ua.y, ub.y) +
        qo_fx_mul32_i64(ua.z, ub.z);
    if (d < 0) {
        ub = neg_q(ub);
        d = -d;
    }
    if (t == 0) return QO_OK;
    if (t == QO_Q30_ONE) {
        *out = ub;
        return QO_OK;
    }
    if (ua.w == ub.w && ua.x == ub.x && ua.y == ub.y && ua.z == ub.z) return QO_OK;   /* one point */
    c = rnd30_i32(d);
    if (c > QO_Q30_ONE) c = QO_Q30_ONE;
    /* The unit direction e of b' orthogonal to a, from v = b' - cos(th) a: short for a small
     * th, but its rounding error (<= 1 LSB) becomes an error of e of ~1 LSB / sin(th), which
     * the result carries times sin(t th): at most ~t LSB. */
    v.w = ub.w - rnd30_i32(qo_fx_mul32_i64(c, ua.w));
    v.x = ub.x - rnd30_i32(qo_fx_mul32_i64(c, ua.x));
    v.y = ub.y - rnd30_i32(qo_fx_mul32_i64(c, ua.y));
    v.z = ub.z - rnd30_i32(qo_fx_mul32_i64(c, ua.z));
    if (qo_quat_normalize_fast_q30(v, &e) != QO_OK) return QO_OK;   /* b' == a: a itself */
    /* th = atan2(|v|, cos th) in [0, pi/2], |v| = v . e */
    vn = rnd30_i32(qo_fx_mul32_i64(v.w, e.w) + qo_fx_mul32_i64(v.x, e.x) +
                   qo_fx_mul32_i64(v.y, e.y) + qo_fx_mul32_i64(v.z, e.z));
    th = qo_fx_atan2_q28(vn, c);
    /* y = t th / 2 in Q1.31 = (t th, Q4.58) / 2^28, in [0, pi/4] */
    qo_fx_sincos_2y_q30((uint32_t)qo_fx_rshift_round_up(qo_fx_mul32_i64(t, th), 28), &sn, &cs);
    /* cos(t th) a + sin(t th) e: unit to the accuracy of a and e; clamped to +-1. */
    {
        int32_t o[4];
        const int32_t av[4] = { ua.w, ua.x, ua.y, ua.z }, ev[4] = { e.w, e.x, e.y, e.z };
        int i;
        for (i = 0; i < 4; i++) {
            int32_t r = rnd30_i32(qo_fx_mul32_i64(cs, av[i]) + qo_fx_mul32_i64(sn, ev[i]));
            o[i] = r > QO_Q30_ONE ? QO_Q30_ONE : r < -QO_Q30_ONE ? -QO_Q30_ONE : r;
        }
        out->w = o[0]; out->x = o[1]; out->y = o[2]; out->z = o[3];
    }
    return QO_OK;
}

/* Checks that every key is non-zero. */
static qo_status check_keys(const qo_quat_q30 *keys, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (is_zero_q(keys[i])) return QO_E_DEGENERATE;
    return QO_OK;
}

static void fill_identity(qo_quat_q30 *q, size_t n)
{
    size_t i;
    if (q == NULL) return;
    for (i = 0; i < n; i++) q[i] = identity_q();
}

/* Unit key (validated beforehand) aligned to prev. */
static qo_quat_q30 next_key(qo_quat_q30 k, qo_quat_q30 prev)
{
    qo_quat_q30 u;
    (void)unit_in(k, &u);
    return align_to(u, prev);
}

qo_status qo_interp_align_keys_q30(const qo_quat_q30 *keys, size_t n, qo_quat_q30 *out)
{
    size_t i;
    qo_status st;
    qo_quat_q30 prev;
    if (keys == NULL || out == NULL) {
        fill_identity(out, n);
        return QO_E_NULL;
    }
    if (n == 0) return QO_E_TOO_FEW;
    st = check_keys(keys, n);
    if (st != QO_OK) {
        fill_identity(out, n);
        return st;
    }
    (void)unit_in(keys[0], &prev);
    out[0] = prev;
    for (i = 1; i < n; i++) {
        prev = next_key(keys[i], prev);
        out[i] = prev;
    }
    return QO_OK;
}

/* de Casteljau on p[0..n-1] (unit, sign-aligned), in place. Exact endpoints. */
static qo_quat_q30 casteljau(qo_quat_q30 *p, size_t n, qo_q30 t)
{
    size_t lev, i;
    if (t == 0) return p[0];
    if (t == QO_Q30_ONE) return p[n - 1];
    for (lev = n - 1; lev > 0; lev--) {
        for (i = 0; i < lev; i++) {
            qo_quat_q30 r;
            /* An antipodal pair inside the pyramid has no circle: keep its first point. */
            (void)slerp_raw(p[i], p[i + 1], t, &r);
            p[i] = r;
        }
    }
    return p[0];
}

qo_status qo_interp_bezier_q30(const qo_quat_q30 *ctrl, size_t n, qo_q30 t, qo_quat_q30 *out)
{
    qo_quat_q30 p[QO_INTERP_BEZIER_MAX_POINTS];
    size_t i;
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    *out = identity_q();
    if (ctrl == NULL) return QO_E_NULL;
    if (n < 2) return QO_E_TOO_FEW;
    if (n > QO_INTERP_BEZIER_MAX_POINTS) return QO_E_CAPACITY;
    st = check_keys(ctrl, n);
    if (st != QO_OK) return st;
    (void)unit_in(ctrl[0], &p[0]);
    *out = p[0];
    if (check_t(t) != QO_OK) return QO_E_RANGE;
    for (i = 1; i < n; i++) p[i] = next_key(ctrl[i], p[i - 1]);
    *out = casteljau(p, n, t);
    return QO_OK;
}

qo_status qo_interp_bezier3_q30(qo_quat_q30 q0, qo_quat_q30 q1, qo_quat_q30 q2, qo_quat_q30 q3,
                              qo_q30 t, qo_quat_q30 *out)
{
    qo_quat_q30 c[4];
    c[0] = q0; c[1] = q1; c[2] = q2; c[3] = q3;
    return qo_interp_bezier_q30(c, 4, t, out);
}

/* Slerp(q_i, Bisect(Double(q_{i-1}, q_i), q_{i+1}), u) for u = +-1/3: returns a_i and b_i. */
static void inner_controls(qo_quat_q30 qm, qo_quat_q30 qc, qo_quat_q30 qn,
                           qo_quat_q30 *ai, qo_quat_q30 *bi)
{
    qo_quat_q30 dbl, abar;
    (void)slerp_raw(qm, qc, 2 * ONE64, &dbl);
    if (!slerp_raw(dbl, qn, ONE64 / 2, &abar)) {
        /* Double(q_{i-1}, q_i) antipodal to q_{i+1}: no bisector. The Euclidean formula's
         * limit (q_{i+1} == q_{i-1}) is a zero tangent, so abar = q_i (documented). */
        abar = qc;
    }
    (void)slerp_raw(qc, abar, THIRD_Q30, ai);
    (void)slerp_raw(qc, abar, -THIRD_Q30, bi);
}

/* End control point Slerp(q_end, Slerp(q_far, q_near, 2), 1/3) of the notes. */
static qo_quat_q30 end_control(qo_quat_q30 q_end, qo_quat_q30 q_near, qo_quat_q30 q_far)
{
    qo_quat_q30 dbl, r;
    (void)slerp_raw(q_far, q_near, 2 * ONE64, &dbl);
    if (!slerp_raw(q_end, dbl, THIRD_Q30, &r)) r = q_end;
    return r;
}

qo_status qo_interp_spline_controls_q30(const qo_quat_q30 *keys, size_t n,
                                      qo_quat_q30 *a, qo_quat_q30 *b)
{
    qo_quat_q30 qm, qc, qn;
    qo_status st;
    size_t i;
    fill_identity(a, n);
    fill_identity(b, n);
    if (keys == NULL || a == NULL || b == NULL) return QO_E_NULL;
    if (n < 2) return QO_E_TOO_FEW;
    st = check_keys(keys, n);
    if (st != QO_OK) return st;
    (void)unit_in(keys[0], &qm);
    qc = next_key(keys[1], qm);
    if (n == 2) {
        /* Evenly spaced on the arc: the cubic Bezier is then the constant-rate slerp. */
        (void)slerp_raw(qm, qc, THIRD_Q30, &a[0]);
        (void)slerp_raw(qm, qc, TWO_THIRDS_Q30, &b[1]);
        b[0] = qm;
        a[1] = qc;
        return QO_OK;
    }
    qn = next_key(keys[2], qc);
    a[0] = end_control(qm, qc, qn);
    b[0] = qm;
    /* Rolling window (q_{i-1}, q_i, q_{i+1}) over the aligned keys: no scratch array. */
    for (i = 1; i + 1 < n; i++) {
        if (i > 1) {
            qm = qc;
            qc = qn;
            qn = next_key(keys[i + 1], qc);
        }
        inner_controls(qm, qc, qn, &a[i], &b[i]);
    }
    /* Window is now (q_{n-3}, q_{n-2}, q_{n-1}). */
    b[n - 1] = end_control(qn, qc, qm);
    a[n - 1] = qn;
    return QO_OK;
}

qo_status qo_interp_spline_eval_q30(const qo_quat_q30 *keys, const qo_quat_q30 *a,
                                  const qo_quat_q30 *b, size_t n, qo_q16 s, qo_quat_q30 *out)
{
    qo_quat_q30 p[4];
    qo_status st;
    size_t i, k;
    qo_q30 t;
    if (out == NULL) return QO_E_NULL;
    *out = identity_q();
    if (keys == NULL || a == NULL || b == NULL) return QO_E_NULL;
    if (n < 2) return QO_E_TOO_FEW;
    if (s < 0 || (uint64_t)s > (uint64_t)(n - 1) * (uint64_t)QO_Q16_ONE) {
        /* below 0 -> first key, above n-1 -> last key */
        (void)unit_in(s < 0 ? keys[0] : keys[n - 1], out);
        return QO_E_RANGE;
    }
    i = (size_t)((uint32_t)s >> 16);
    if (i > n - 2) i = n - 2;
    /* local parameter: the remaining Q16.16 value (<= 1.0) shifted to Q1.30, exact */
    t = (qo_q30)(((uint32_t)s - (uint32_t)i * (uint32_t)QO_Q16_ONE) << 14);
    p[0] = keys[i];
    p[1] = a[i];
    p[2] = b[i + 1];
    p[3] = keys[i + 1];
    st = check_keys(p, 4);
    if (st != QO_OK) return st;
    for (k = 0; k < 4; k++) (void)unit_in(p[k], &p[k]);
    /* a_i and b_{i+1} carry the aligned signs and lie within 60 deg (4-D) of their keys, so
     * aligning the keys to them is unambiguous even for unaligned caller keys. */
    p[0] = align_to(p[0], p[1]);
    p[3] = align_to(p[3], p[2]);
    *out = casteljau(p, 4, t);
    return QO_OK;
}

qo_status qo_interp_squad_q30(qo_quat_q30 q0, qo_quat_q30 s0, qo_quat_q30 s1, qo_quat_q30 q1,
                            qo_q30 t, qo_quat_q30 *out)
{
    qo_quat_q30 p[4], x, y;
    qo_status st;
    size_t k;
    int64_t h;
    if (out == NULL) return QO_E_NULL;
    *out = identity_q();
    p[0] = q0; p[1] = s0; p[2] = s1; p[3] = q1;
    st = check_keys(p, 4);
    if (st != QO_OK) return st;
    for (k = 0; k < 4; k++) (void)unit_in(p[k], &p[k]);
    *out = p[0];
    if (check_t(t) != QO_OK) return QO_E_RANGE;
    if (t == 0) return QO_OK;
    p[3] = align_to(p[3], p[0]);
    p[1] = align_to(p[1], p[0]);
    p[2] = align_to(p[2], p[3]);
    if (t == QO_Q30_ONE) {
        *out = p[3];
        return QO_OK;
    }
    (void)slerp_raw(p[0], p[3], t, &x);
    (void)slerp_raw(p[1], p[2], t, &y);
    /* 2 t (1 - t) in Q1.30, exact product rounded once; in [0, 1/2]. */
    h = qo_fx_rshift_round_up(2 * (int64_t)t * (ONE64 - t), 30);
    (void)slerp_raw(x, y, h, out);
    return QO_OK;
}

/* log of a unit relative rotation as its Q3.28 vector part (theta/2 * axis). */
static qo_vec3_q28 log_unit(qo_quat_q30 q)
{
    qo_vec3_q28 l;
    (void)qo_quat_log_q30(q, &l);
    return l;
}

/* -(l1 + l2)/4, each component rounded once (|l| <= pi/2 + rounding: no overflow). */
static qo_q28 quarter_neg_sum(qo_q28 a, qo_q28 b)
{
    return (qo_q28)qo_fx_rshift_round_up(-((int64_t)a + b), 2);
}

qo_status qo_interp_squad_controls_q30(const qo_quat_q30 *keys, size_t n, qo_quat_q30 *s)
{
    qo_quat_q30 qm, qc, qn, qci, e;
    qo_vec3_q28 l1, l2, arg;
    qo_status st;
    size_t i;
    fill_identity(s, n);
    if (keys == NULL || s == NULL) return QO_E_NULL;
    if (n < 2) return QO_E_TOO_FEW;
    st = check_keys(keys, n);
    if (st != QO_OK) return st;
    (void)unit_in(keys[0], &qc);
    s[0] = qc;
    qn = next_key(keys[1], qc);
    for (i = 1; i + 1 < n; i++) {
        qm = qc;
        qc = qn;
        qn = next_key(keys[i + 1], qc);
        qci = qo_quat_conj_q30(qc);
        /* Aligned keys: both relative rotations have w >= 0 (up to the product's rounding),
         * so the logs are the short ones, |l| <= pi/2. */
        l1 = log_unit(qo_quat_mul_q30(qci, qn));
        l2 = log_unit(qo_quat_mul_q30(qci, qm));
        arg.x = quarter_neg_sum(l1.x, l2.x);
        arg.y = quarter_neg_sum(l1.y, l2.y);
        arg.z = quarter_neg_sum(l1.z, l2.z);
        (void)qo_quat_exp_q30(arg, &e);
        (void)unit_in(qo_quat_mul_q30(qc, e), &s[i]);
    }
    s[n - 1] = qn;
    return QO_OK;
}

/* ---- the remaining twins of interp.h (issue 16) ---- */

qo_status qo_interp_slerp_long_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q30 t, qo_quat_q30 *out)
{
    return slerp_common(a, b, t, 1, out);
}

qo_status qo_interp_slerp_rate_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q16 duration,
                                 qo_vec3_q16 *omega)
{
    qo_quat_q30 ua, ub;
    qo_vec3_q28 lg;
    qo_status st;
    int64_t r[3];
    int i;
    if (omega == NULL) return QO_E_NULL;
    omega->x = omega->y = omega->z = 0;
    st = unit_in2(a, b, &ua, &ub);
    if (st != QO_OK) return st;
    if (duration <= 0) return QO_E_RANGE;
    ub = align_to(ub, ua);
    /* conj(a)*b' has w = dot >= 0, so its log is the short rotation's phi/2 * axis (Q3.28,
     * |lg| <= pi/2). omega = 2 lg / duration: Q3.28 * 2 / Q16.16 -> Q16.16 is
     * lg_raw * 2^(1 + 16 + 16 - 28) / duration_raw = lg_raw * 32 / duration_raw, one rounded
     * division (|lg_raw * 32| < 2^34). */
    (void)qo_quat_log_q30(qo_quat_mul_q30(qo_quat_conj_q30(ua), ub), &lg);
    r[0] = qo_fx_div_round_away((int64_t)lg.x * 32, (uint64_t)duration);
    r[1] = qo_fx_div_round_away((int64_t)lg.y * 32, (uint64_t)duration);
    r[2] = qo_fx_div_round_away((int64_t)lg.z * 32, (uint64_t)duration);
    for (i = 0; i < 3; i++)
        if (r[i] > INT32_MAX || r[i] < -INT32_MAX) return QO_E_RANGE;   /* a tiny duration */
    omega->x = (qo_q16)r[0];
    omega->y = (qo_q16)r[1];
    omega->z = (qo_q16)r[2];
    return QO_OK;
}
