/* Euler angles, fixed point (Q1.30 quaternions, Q3.28 radians). See qorient/euler_fx.h for the
 * contract of each function. Integer arithmetic only: no floating point at all, no libm.
 *
 * The method is the float32 core's (lib/src/euler.c), step for step: every convention is
 * reduced to the intrinsic form q = q_i(t1) * q_j(t2) * q_k(t3), the angles come straight from
 * the quaternion (Bernardes & Viollet 2022) as one atan2 each, and at lock a3 is chosen and a1
 * fitted. What fixed point changes is the arithmetic, and it is better here: the quaternion is
 * scaled by a power of two so its largest component is in (2^29, 2^30], after which every
 * product of the decomposition is EXACT in int64 (the bounds are given next to each one). Its
 * only roundings are the square roots of two sums of squares (correctly rounded), the
 * reduction of each atan2 argument pair to 30 significant bits, and the atan2 itself (<= 1 LSB
 * of Q3.28). The fit at lock and from_euler multiply quaternions and round each product once,
 * keeping one or more guard bits in between (qmul below).
 * Not used here, on purpose: a Q1.30 x Q1.30 -> Q1.30 quaternion product would round after
 * every step and lose the guard bits.
 */
#include "qorient/euler_fx.h"
#include "qorient/fxmath.h"

#include "fx_internal.h"
#include "euler_seq_internal.h"

/* pi and 2pi in Q8.56 (int64, rounded): the angle arithmetic of the nearest-solution variant
 * is done at 2^-56 and rounded to Q3.28 once. */
#define PI_Q56     ((int64_t)226375608064910089LL)
#define TWO_PI_Q56 ((int64_t)452751216129820178LL)

/* A quaternion held in int64 components, w x y z = v[0..3]. */
typedef struct q64 { int64_t v[4]; } q64;

/* a * b exactly, for |a|, |b| < 2^32 (every product in this file): the magnitudes through
 * the 32x32 product of fxmath.h, not libgcc's 64x64 multiply (slow on Cortex-M0). */
static int64_t smul(int64_t a, int64_t b)
{
    uint64_t p = qo_fx_umul32_u64((uint32_t)qo_fx_abs_u64(a), (uint32_t)qo_fx_abs_u64(b));
    return (a < 0) != (b < 0) ? -(int64_t)p : (int64_t)p;
}

/* fx_internal.h: defined here, its one user (out of line on purpose: see there). */
unsigned qo_fx_bits_above_30_u64(uint64_t v)
{
    unsigned s = 0;
    uint32_t t;
    if ((v >> 32) != 0) { s = 2; t = (uint32_t)(v >> 32); }
    else t = (uint32_t)v >> 30;
    if (t >= 0x10000u) { t >>= 16; s += 16; }
    if (t >= 0x100u) { t >>= 8; s += 8; }
    if (t >= 0x10u) { t >>= 4; s += 4; }
    if (t >= 0x4u) { t >>= 2; s += 2; }
    if (t >= 0x2u) { t >>= 1; s += 1; }
    return s + t;
}

/* atan2(y, x) for int64 arguments of one scale, |y|, |x| < 2^63: both are reduced by the
 * same power of two to below 2^30 (30 significant bits of the larger: 1e-9 rad at worst),
 * rounded on the magnitude so the result stays odd in y, then qo_fx_atan2_q28. */
static qo_q28 atan2_i64(int64_t y, int64_t x)
{
    uint64_t ay = qo_fx_abs_u64(y), ax = qo_fx_abs_u64(x), m = ay > ax ? ay : ax;
    unsigned s = qo_fx_bits_above_30_u64(m);   /* (a 64-bit shift per step is slow on Cortex-M0) */
    int32_t yy, xx;
    yy = (int32_t)qo_fx_urshift_round_up_u32(ay, s);
    xx = (int32_t)qo_fx_urshift_round_up_u32(ax, s);
    if (y < 0) yy = -yy;
    if (x < 0) xx = -xx;
    return qo_fx_atan2_q28(yy, xx);
}

/* Hamilton product a * b, each component round(sum / 2^shift) with ties away from zero: odd,
 * so a product with -q is exactly the negated product with q (q and -q then give bit-identical
 * angles, as in the _f32 core). The caller guarantees the
 * bounds: every single product < 2^62 and the true sum < 2^62 (then the partial sums of up to
 * four such products stay below 2^63). */
static q64 qmul(q64 a, q64 b, unsigned shift)
{
    const int64_t *p = a.v, *q = b.v;
    q64 r;
    r.v[0] = qo_fx_rshift_round_away(
        smul(p[0], q[0]) - smul(p[1], q[1]) - smul(p[2], q[2]) - smul(p[3], q[3]), shift);
    r.v[1] = qo_fx_rshift_round_away(
        smul(p[0], q[1]) + smul(p[1], q[0]) + smul(p[2], q[3]) - smul(p[3], q[2]), shift);
    r.v[2] = qo_fx_rshift_round_away(
        smul(p[0], q[2]) - smul(p[1], q[3]) + smul(p[2], q[0]) + smul(p[3], q[1]), shift);
    r.v[3] = qo_fx_rshift_round_away(
        smul(p[0], q[3]) + smul(p[1], q[2]) - smul(p[2], q[1]) + smul(p[3], q[0]), shift);
    return r;
}

/* Rotation by angle t (Q3.28 rad, any value) about coordinate axis `axis`, Q1.30 in int64.
 * sign -1 gives the conjugate (the inverse rotation). */
static q64 elem_quat(int axis, qo_q28 t, int sign)
{
    q64 q;
    qo_q30 s, c;
    (void)qo_fx_sincos_half_q28(t, &s, &c);
    q.v[0] = c;
    q.v[1] = q.v[2] = q.v[3] = 0;
    q.v[1 + axis] = sign < 0 ? -(int64_t)s : (int64_t)s;
    return q;
}

static qo_quat_q30 identity_q30(void)
{
    qo_quat_q30 q;
    q.w = QO_Q30_ONE;
    q.x = q.y = q.z = 0;
    return q;
}

qo_status qo_euler_to_quat_q30(qo_euler_seq seq, qo_euler_q28 e, qo_quat_q30 *out)
{
    const unsigned char *ax;
    q64 q1, q2, q3, p;
    if (out == NULL) return QO_E_NULL;
    *out = identity_q30();
    if (!qo_euler_seq_valid(seq)) return QO_E_ARG;
    ax = qo_euler_seq_row(seq);
    q1 = elem_quat(ax[0], e.a1, 1);
    q2 = elem_quat(ax[1], e.a2, 1);
    q3 = elem_quat(ax[2], e.a3, 1);
    /* First product exact in Q2.60 (each component a single product <= 2^60), kept as Q.31
     * (0.25 LSB of Q1.30); the second is then < 2^62 per product and in total, rounded once
     * to Q1.30. All components stay within [-1 - 1e-9, 1 + 1e-9]: no saturation possible. */
    if ((int)seq >= 12) p = qmul(qmul(q1, q2, 29), q3, 31);  /* body axes: q1 q2 q3 */
    else p = qmul(q3, qmul(q2, q1, 29), 31);                 /* world axes: q3 q2 q1 */
    out->w = (qo_q30)p.v[0];
    out->x = (qo_q30)p.v[1];
    out->y = (qo_q30)p.v[2];
    out->z = (qo_q30)p.v[3];
    return QO_OK;
}

/* q scaled by a power of two so the largest |component| is in (2^29, 2^30] (the rotation is
 * unchanged; only a component >= 1.0, possible in a non-unit input, loses its last bit).
 * Requires q non-zero. */
static q64 scale_pow2(qo_quat_q30 q)
{
    q64 r;
    uint64_t m;
    int i;
    r.v[0] = q.w; r.v[1] = q.x; r.v[2] = q.y; r.v[3] = q.z;
    m = 0;
    for (i = 0; i < 4; i++) if (qo_fx_abs_u64(r.v[i]) > m) m = qo_fx_abs_u64(r.v[i]);
    if (m > ((uint64_t)1 << 30)) {
        /* halved, rounded on the magnitude (so q and -q stay exact negatives): <= 2^30 */
        for (i = 0; i < 4; i++) {
            int64_t h = (int64_t)((qo_fx_abs_u64(r.v[i]) + 1u) >> 1);
            r.v[i] = r.v[i] < 0 ? -h : h;
        }
    } else {
        unsigned s = 0;
        while ((m << (s + 1)) <= ((uint64_t)1 << 30)) s++;
        for (i = 0; i < 4; i++) r.v[i] *= (int64_t)1 << s;          /* exact */
    }
    return r;
}

/* The full (unlocked) decomposition of a scaled q, plus the lock margin. */
typedef struct decomp {
    qo_euler_q28 e;  /* principal solution, scipy ranges */
    qo_q28 margin;   /* rad, [0, pi/2] */
} decomp;

/* (n1^2 - n2^2) / 2 from the exact sums of squares, as a signed value (each sum < 2^64). */
static int64_t half_diff(uint64_t s1, uint64_t s2)
{
    return s1 >= s2 ? (int64_t)((s1 - s2) >> 1) : -(int64_t)((s2 - s1) >> 1);
}

static decomp decompose(q64 q, qo_euler_seq seq)
{
    const unsigned char *ax = qo_euler_seq_row(seq);
    int intrinsic = (int)seq >= 12;
    int i = intrinsic ? ax[0] : ax[2];
    int j = ax[1];
    int k = intrinsic ? ax[2] : ax[0];
    /* eps = +1 when e_i x e_j = +e_(third axis), i.e. (i, j, .) is cyclic. */
    int64_t eps = (j == (int)qo_euler_axis_next((unsigned)i)) ? 1 : -1;
    int64_t a, b, c, d, h, p, t2y, t2x;
    uint64_t s1, s2, n1, n2;
    qo_q28 t1, t2, t3;
    decomp r;
    if (i == k) {
        /* Proper, l = the remaining axis (derivation in euler.c): w = c cos S, q_i = c sin S,
         * q_j = s cos D, eps q_l = s sin D with c, s = cos, sin(t2/2). |a..d| <= 2^30, so
         * every product below is <= 2^60 and every sum <= 2^62. */
        int l = 3 - i - j;
        a = q.v[0]; b = q.v[1 + i]; c = q.v[1 + j]; d = eps < 0 ? -q.v[1 + l] : q.v[1 + l];
        s1 = (uint64_t)smul(a, a) + (uint64_t)smul(b, b);   /* n1^2 = |(w, q_i)|^2 */
        s2 = (uint64_t)smul(c, c) + (uint64_t)smul(d, d);   /* n2^2 = |(q_j, q_l)|^2 */
        n1 = qo_fx_sqrt_u64(s1);
        n2 = qo_fx_sqrt_u64(s2);
        /* n1 n2 <= (s1 + s2)/2 = |q|^2 <= 2^62 (n1, n2 < 2^32) */
        p = (int64_t)qo_fx_umul32_u64((uint32_t)n1, (uint32_t)n2);
        h = half_diff(s1, s2);
        /* t2 = 2 atan2(n2, n1) = atan2(2 n1 n2, n1^2 - n2^2), in [0, pi], one atan2. */
        t2y = p; t2x = h;
        t1 = atan2_i64(smul(b, c) + smul(a, d), smul(a, c) - smul(b, d));
        t3 = atan2_i64(smul(b, c) - smul(a, d), smul(a, c) + smul(b, d));
    } else {
        /* Tait-Bryan (derivation in euler.c): with (x, y, z) = (q_i, q_j, eps q_k),
         * a = w - y, b = x + z, c = w + y, d = z - x, |a..d| <= 2^31: each product <= 2^62,
         * and the two atan2 pairs are the parts of (c + ib)(a -+ id), whose modulus is
         * n1 n2 <= (n1^2 + n2^2)/2 = |q|^2 <= 2^62, so no sum overflows. */
        int64_t x = q.v[1 + i], y = q.v[1 + j], z = eps < 0 ? -q.v[1 + k] : q.v[1 + k];
        a = q.v[0] - y; b = x + z; c = q.v[0] + y; d = z - x;
        s1 = (uint64_t)smul(a, a) + (uint64_t)smul(d, d);   /* <= 2^63: fits unsigned */
        s2 = (uint64_t)smul(b, b) + (uint64_t)smul(c, c);
        n1 = qo_fx_sqrt_u64(s1);
        n2 = qo_fx_sqrt_u64(s2);
        p = (int64_t)qo_fx_umul32_u64((uint32_t)n1, (uint32_t)n2);
        h = half_diff(s2, s1);
        /* t2 = atan2(n2^2 - n1^2, 2 n1 n2) in [-pi/2, pi/2] (no pi/2 constant). */
        t2y = h; t2x = p;
        t1 = atan2_i64(smul(b, a) - smul(c, d), smul(c, a) + smul(b, d));
        t3 = atan2_i64(smul(b, a) + smul(c, d), smul(c, a) - smul(b, d));
        if (eps < 0) t3 = -t3;                        /* |t3| <= pi: no overflow */
    }
    t2 = atan2_i64(t2y, t2x);
    /* The distance to the nearer singularity straight from the norms, one atan2:
     * 2 atan2(min, max) = atan2(2 n1 n2, |n1^2 - n2^2|). Exactly 0 iff one norm is 0. */
    r.margin = atan2_i64(p, h < 0 ? -h : h);
    r.e.a2 = t2;
    r.e.a1 = intrinsic ? t1 : t3;
    r.e.a3 = intrinsic ? t3 : t1;
    return r;
}

/* Given a2 and a3 (Q3.28, any value), the a1 whose composition is nearest q (scaled, so its
 * components are <= 2^30 and |q| <= 2^31): q = A1 * rest (intrinsic) or rest * A1
 * (extrinsic), p = the part of q left for A1, a1 = arg(p.w + i p_axis)^2 = one atan2 of
 * (2uv, u^2 - v^2), already in [-pi, pi] and independent of the sign of p. */
static qo_q28 fit_a1(q64 q, qo_euler_seq seq, qo_q28 a2, qo_q28 a3)
{
    const unsigned char *ax = qo_euler_seq_row(seq);
    q64 c2 = elem_quat(ax[1], a2, -1);
    q64 c3 = elem_quat(ax[2], a3, -1);
    q64 p;
    int64_t u, v;
    /* Products: q (<= 2^30) x Q1.30 (<= 2^30) -> <= 2^60; then (<= 2^31) x Q1.30 -> <= 2^61;
     * |p| <= |q| (1 + 1e-9) <= 2^31 + small, so u^2 + v^2 < 2^62 + small. */
    if ((int)seq >= 12) p = qmul(qmul(q, c3, 30), c2, 30);   /* q = q1 q2 q3 */
    else p = qmul(c2, qmul(c3, q, 30), 30);                  /* q = q3 q2 q1 */
    u = p.v[0];
    v = p.v[1 + ax[0]];
    return atan2_i64(2 * smul(u, v), smul(u - v, u + v));
}

static void set_error_outputs(qo_euler_q28 *out, qo_euler_info_q28 *info)
{
    out->a1 = out->a2 = out->a3 = 0;
    if (info != NULL) { info->locked = 0; info->margin = 0; }
}

/* Shared argument checks (the order of the _f32 core); on success *qs is q scaled. */
static qo_status check_args(qo_quat_q30 q, qo_euler_seq seq, qo_q28 band, q64 *qs)
{
    if (!qo_euler_seq_valid(seq)) return QO_E_ARG;
    if (q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0) return QO_E_DEGENERATE;
    if (band < 0 || band > QO_Q28_HALF_PI) return QO_E_RANGE;
    *qs = scale_pow2(q);
    return QO_OK;
}

qo_status qo_euler_from_quat_band_q30(qo_quat_q30 q, qo_euler_seq seq, qo_q28 band_rad,
                                    qo_euler_q28 *out, qo_euler_info_q28 *info)
{
    q64 qs;
    qo_status st;
    decomp r;
    if (out == NULL) return QO_E_NULL;
    set_error_outputs(out, info);
    st = check_args(q, seq, band_rad, &qs);
    if (st != QO_OK) return st;
    r = decompose(qs, seq);
    if (r.margin <= band_rad) {
        /* scipy's choice: a3 = 0, a1 takes the determined sum/difference. */
        r.e.a3 = 0;
        r.e.a1 = fit_a1(qs, seq, r.e.a2, 0);
    }
    *out = r.e;
    if (info != NULL) { info->locked = r.margin <= band_rad; info->margin = r.margin; }
    return QO_OK;
}

qo_status qo_euler_from_quat_q30(qo_quat_q30 q, qo_euler_seq seq, qo_euler_q28 *out,
                               qo_euler_info_q28 *info)
{
    return qo_euler_from_quat_band_q30(q, seq, QO_EULER_LOCK_BAND_Q28, out, info);
}

/* ---- nearest solution: angles held in Q8.56 (int64) until the one final rounding ---- */

static int64_t q56_from_q28(qo_q28 a) { return (int64_t)a * ((int64_t)1 << 28); }

/* a (Q8.56, |a| < 2^61) plus the multiple of 2pi that brings it nearest ref (Q3.28). */
static int64_t unwrap_toward(int64_t a, qo_q28 ref)
{
    int64_t k = qo_fx_div_floor(q56_from_q28(ref) - a + PI_Q56, TWO_PI_Q56);
    return a + k * TWO_PI_Q56;
}

/* (a - ref) in Q3.28 for the nearness comparison (a is within a few pi of ref). */
static int64_t diff_q28(int64_t a, qo_q28 ref)
{
    return qo_fx_rshift_round_up(a - q56_from_q28(ref), 28);
}

/* The Q8.56 angle rounded to Q3.28; if that does not fit int32 (|angle| >= 8 rad) it is taken
 * one turn back toward zero and *ovf is set. */
static qo_q28 to_q28(int64_t a, int *ovf)
{
    int64_t r = qo_fx_rshift_round_up(a, 28);
    if (r > INT32_MAX) { r = qo_fx_rshift_round_up(a - TWO_PI_Q56, 28); *ovf = 1; }
    else if (r < INT32_MIN) { r = qo_fx_rshift_round_up(a + TWO_PI_Q56, 28); *ovf = 1; }
    return (qo_q28)r;
}

qo_status qo_euler_from_quat_near_q30(qo_quat_q30 q, qo_euler_seq seq, qo_euler_q28 prev,
                                    qo_q28 band, qo_euler_q28 *out, qo_euler_info_q28 *info)
{
    q64 qs;
    qo_status st;
    decomp r;
    int64_t p1, p2, p3, alt1, alt2, alt3, dp1, dp2, dp3, da1, da2, da3;
    int ovf = 0;
    qo_q28 a2_in_range;
    if (out == NULL) return QO_E_NULL;
    set_error_outputs(out, info);
    st = check_args(q, seq, band, &qs);
    if (st != QO_OK) {
        *out = prev; /* hold the joint */
        return st;
    }
    r = decompose(qs, seq);
    /* The second solution: (a1 + pi, pi - a2, a3 + pi) Tait-Bryan, (a1 + pi, -a2, a3 + pi)
     * proper; pi added exactly at 2^-56. */
    alt2 = qo_euler_seq_is_proper(seq) ? -q56_from_q28(r.e.a2) : PI_Q56 - q56_from_q28(r.e.a2);
    p2 = unwrap_toward(q56_from_q28(r.e.a2), prev.a2);
    alt2 = unwrap_toward(alt2, prev.a2);
    dp2 = diff_q28(p2, prev.a2);
    da2 = diff_q28(alt2, prev.a2);
    if (r.margin <= band) {
        /* Locked: keep prev's split (a3 = prev.a3), take the middle angle of the branch nearer
         * prev and fit a1 to it (the in-range value of that branch: a 2pi shift of a2 only
         * flips the sign of its quaternion, which the fit ignores). */
        if ((da2 < 0 ? -da2 : da2) < (dp2 < 0 ? -dp2 : dp2)) {
            p2 = alt2;
            a2_in_range = qo_euler_seq_is_proper(seq) ? -r.e.a2 : (qo_q28)qo_fx_rshift_round_up(PI_Q56 - q56_from_q28(r.e.a2), 28);
        } else {
            a2_in_range = r.e.a2;
        }
        p1 = unwrap_toward(q56_from_q28(fit_a1(qs, seq, a2_in_range, prev.a3)), prev.a1);
        out->a1 = to_q28(p1, &ovf);
        out->a2 = to_q28(p2, &ovf);
        out->a3 = prev.a3;
    } else {
        p1 = unwrap_toward(q56_from_q28(r.e.a1), prev.a1);
        p3 = unwrap_toward(q56_from_q28(r.e.a3), prev.a3);
        alt1 = unwrap_toward(q56_from_q28(r.e.a1) + PI_Q56, prev.a1);
        alt3 = unwrap_toward(q56_from_q28(r.e.a3) + PI_Q56, prev.a3);
        /* Each difference is <= pi in Q3.28 (< 2^29.7): the sums of squares are < 2^61. */
        dp1 = diff_q28(p1, prev.a1); dp3 = diff_q28(p3, prev.a3);
        da1 = diff_q28(alt1, prev.a1); da3 = diff_q28(alt3, prev.a3);
        if (da1 * da1 + da2 * da2 + da3 * da3 < dp1 * dp1 + dp2 * dp2 + dp3 * dp3) {
            p1 = alt1; p2 = alt2; p3 = alt3;
        }
        out->a1 = to_q28(p1, &ovf);
        out->a2 = to_q28(p2, &ovf);
        out->a3 = to_q28(p3, &ovf);
    }
    if (info != NULL) { info->locked = r.margin <= band; info->margin = r.margin; }
    return ovf ? QO_E_OVERFLOW : QO_OK;
}

/* ---- fast tier: 32-bit angle pairs, three atan2, one square root, no quaternion product ----
 *
 * The decomposition above keeps every product exact in int64, which costs four atan2 of 64-bit
 * pairs and, at lock, two sin/cos and two quaternion products on a core without a 64-bit
 * multiply. Here the same angles come from the ARGUMENTS of the two component pairs of the
 * derivation in euler.c instead of from their products: with P and Q the pairs (proper:
 * P = (w, q_i), Q = (q_j, eps q_l); Tait-Bryan: P = (w + y, x + z), Q = (w - y, z - x)),
 * t1 = arg P + arg Q, t3 = arg P - arg Q (proper) or t1 = arg P - arg Q, t3 = arg P + arg Q
 * (Tait-Bryan, then eps t3), and the middle angle from |P|^2 and |Q|^2 with one square root of
 * their product. At lock the angle pair of the vanishing pair is noise, and a1 is twice the
 * argument of the other pair (no fit). Each angle carries up to three atan2 roundings plus the
 * halving of the components below: a few LSB of Q3.28 (measured in tests/core/test_euler.c). */

/* t in (-2 QO_Q28_TWO_PI, 2 QO_Q28_TWO_PI) wrapped into [-QO_Q28_PI, QO_Q28_PI] (one turn). */
static qo_q28 wrap_turn(int32_t t)
{
    if (t > QO_Q28_PI) return t - QO_Q28_TWO_PI;
    if (t < -QO_Q28_PI) return t + QO_Q28_TWO_PI;
    return t;
}

/* v = m 2^e (m truncated) with e even and m < 2^32, m >= 2^30 when v >= 2^30. */
static uint32_t mant_even(uint64_t v, unsigned *e)
{
    unsigned s = qo_fx_bits_above_30_u64(v);
    s += s & 1u;
    *e = s;
    return s == 0 ? (uint32_t)v : s < 32u ? (uint32_t)(v >> s) : (uint32_t)(v >> 32) >> (s - 32u);
}

qo_status qo_euler_from_quat_fast_q30(qo_quat_q30 q, qo_euler_seq seq, qo_q28 band_rad,
                                    qo_euler_q28 *out, qo_euler_info_q28 *info)
{
    const unsigned char *ax;
    int32_t v[4], pr, pi, qr, qi, tp, tq, t1, t2, t3, margin, c;
    uint64_t sp, sq;
    uint32_t hp, hq, mp, mq, m;
    unsigned i, j, k, s, ep, eq;
    int intrinsic, proper, eps_neg, locked, p_small, r;
    if (out == NULL) return QO_E_NULL;
    set_error_outputs(out, info);
    if (!qo_euler_seq_valid(seq)) return QO_E_ARG;
    if (q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0) return QO_E_DEGENERATE;
    if (band_rad < 0 || band_rad > QO_Q28_HALF_PI) return QO_E_RANGE;
    /* Scaled by a power of two so the largest |component| is in [2^29, 2^30): a component of
     * +-1.0 or beyond halves all four (truncation toward zero is odd; the halved INT32_MIN is
     * taken to -(2^30 - 1): 1 part in 2^30), a short quaternion is shifted up (exact). Every
     * sum or difference of two components then fits an int32, and |P|^2 + |Q|^2 =
     * 2 |q|^2 is in [2^59, 2^63). The sign is made canonical (first non-zero component
     * positive), so q and -q give the same bits. */
    v[0] = q.w; v[1] = q.x; v[2] = q.y; v[3] = q.z;
    m = 0;
    for (i = 0; i < 4; i++) m |= qo_fx_abs_u32(v[i]);
    if (m >= (uint32_t)QO_Q30_ONE) {
        for (i = 0; i < 4; i++) {
            v[i] /= 2;
            if (v[i] < 1 - QO_Q30_ONE) v[i] = 1 - QO_Q30_ONE;
        }
    } else {
        s = 0;
        while ((m << s) < ((uint32_t)1 << 21)) s += 8;
        while ((m << s) < ((uint32_t)1 << 29)) s++;
        for (i = 0; i < 4; i++) v[i] *= (int32_t)1 << s;   /* exact: stays below 2^30 */
    }
    if (v[0] < 0 || (v[0] == 0 && (v[1] < 0 || (v[1] == 0 && (v[2] < 0 || (v[2] == 0 && v[3] < 0))))))
        for (i = 0; i < 4; i++) v[i] = -v[i];
    intrinsic = (int)seq >= 12;
    ax = qo_euler_seq_row(seq);
    proper = ax[0] == ax[2];
    i = intrinsic ? ax[0] : ax[2];
    j = ax[1];
    k = proper ? 3u - i - j : (intrinsic ? ax[2] : ax[0]);
    /* eps = -1 when (i, j, .) is anti-cyclic; as in decompose(). */
    eps_neg = j != qo_euler_axis_next(i);
    {
        int32_t x = v[1 + i], y = v[1 + j], z = eps_neg ? -v[1 + k] : v[1 + k];
        if (proper) { pr = v[0]; pi = x; qr = y; qi = z; }
        else { pr = v[0] + y; pi = x + z; qr = v[0] - y; qi = z - x; }
    }
    tp = qo_fx_atan2_q28(pi, pr);
    tq = qo_fx_atan2_q28(qi, qr);
    /* |P|^2 and |Q|^2 (exact) reduced by one power of two so their sum is below 2^30: then
     * their difference fits an int32. 2 |P| |Q| at that scale comes from the two squares
     * normalised apart (so the smaller one keeps its relative precision near lock, where it
     * sets the margin): sqrt(mp mq) 2^((ep + eq)/2), shifted down by s (and up by 1 for the
     * factor 2): r = s - (ep + eq)/2 - 1 >= 0, as 2 |P| |Q| <= |P|^2 + |Q|^2 < 2^(30 + s). */
    sp = qo_fx_sq_u64(pr) + qo_fx_sq_u64(pi);
    sq = qo_fx_sq_u64(qr) + qo_fx_sq_u64(qi);
    s = qo_fx_bits_above_30_u64(sp + sq);
    hp = qo_fx_urshift_round_up_u32(sp, s);
    hq = qo_fx_urshift_round_up_u32(sq, s);
    mp = mant_even(sp, &ep);
    mq = mant_even(sq, &eq);
    r = (int)s - (int)((ep + eq) / 2u) - 1;
    m = (uint32_t)qo_fx_sqrt_u64(qo_fx_umul32_u64(mp, mq));
    c = r <= 0 ? (int32_t)(m << -r) : r > 34 ? 0 : (int32_t)qo_fx_urshift_round_up_u32(m, (unsigned)r);
    if (proper) {
        /* t2 = 2 atan2(|Q|, |P|) in [0, pi]; the margin is the distance to 0 or pi. */
        t2 = qo_fx_atan2_q28(c, (int32_t)hp - (int32_t)hq);
        margin = t2 <= QO_Q28_HALF_PI ? t2 : QO_Q28_PI - t2;
        p_small = t2 > QO_Q28_HALF_PI;
        t1 = wrap_turn(tp + tq);
        t3 = wrap_turn(tp - tq);
    } else {
        /* t2 = 2 atan2(|P|, |Q|) - pi/2 in [-pi/2, pi/2]. */
        t2 = qo_fx_atan2_q28((int32_t)hp - (int32_t)hq, c);
        margin = QO_Q28_HALF_PI - (t2 < 0 ? -t2 : t2);
        if (margin < 0) margin = 0;
        p_small = t2 < 0;
        t1 = wrap_turn(tp - tq);
        t3 = wrap_turn(tp + tq);
        if (eps_neg) t3 = -t3;
    }
    locked = margin <= band_rad;
    if (locked) {
        /* The determined combination C = t1 + sigma t3 is twice the argument of the larger
         * pair (the smaller one's argument is noise); a3 = 0 leaves a1 = C (intrinsic, a1 is
         * t1) or sigma C (extrinsic, a1 is t3). sigma: proper +1 (Q small) / -1 (P small);
         * Tait-Bryan +eps (Q small) / -eps (P small). */
        int sigma_neg = proper ? p_small : (p_small != eps_neg);
        c = wrap_turn(p_small ? (proper ? 2 * tq : -2 * tq) : 2 * tp);
        out->a1 = (!intrinsic && sigma_neg) ? -c : c;
        out->a3 = 0;
    } else {
        out->a1 = intrinsic ? t1 : t3;
        out->a3 = intrinsic ? t3 : t1;
    }
    out->a2 = t2;
    if (info != NULL) { info->locked = locked; info->margin = margin; }
    return QO_OK;
}
