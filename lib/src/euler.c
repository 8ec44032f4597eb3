/* Euler angles, float32. See qorient/euler.h for the contract of each function.
 *
 * Internally every convention is reduced to one intrinsic form
 *     q = q_i(t1) * q_j(t2) * q_k(t3)
 * intrinsic "IJK" (a1, a2, a3): (i, j, k) = the axes as written, t = (a1, a2, a3);
 * extrinsic "ijk" (a1, a2, a3): q = q_k(a3) q_j(a2) q_i(a1), i.e. axes reversed, t1 = a3, t3 = a1.
 * The decomposition of that form follows Bernardes & Viollet (2022), derived afresh here for
 * our Hamilton, active convention (the derivation is summarised next to the code).
 */
#include "qorient/euler.h"
#include "qorient/quat.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "qorient/fmath.h"
#include "euler_seq_internal.h"
#include "fmath_internal.h"

#define HALF_PI_F 1.57079632679490f
/* 2*pi split for Cody-Waite reduction: HI has 8 significant bits, so k*HI is exact for
 * |k| < 2^16 and the reduction of a few thousand turns keeps full float accuracy. */
#define TWO_PI_HI 6.28125f
#define TWO_PI_LO 0.00193530717958648f
#define INV_TWO_PI_F 0.159154943091895f
/* pi split the same way, for the second solution's a + pi. */
#define PI_HI 3.140625f
#define PI_LO 0.000967653589793116f

/* Rotation by angle t (rad) about coordinate axis `axis`. */
static qo_quat_f32 elem_quat(int axis, float t)
{
    qo_quat_f32 q = { 0.0f, 0.0f, 0.0f, 0.0f };
    float h = 0.5f * t;
    qo_fm_sincos_f32_t sc = qo_fm_sincos_f32(h);
    float s = sc.s;
    q.w = sc.c;
    if (axis == 0) q.x = s;
    else if (axis == 1) q.y = s;
    else q.z = s;
    return q;
}

static float quat_comp(qo_quat_f32 q, int axis)
{
    return axis == 0 ? q.x : (axis == 1 ? q.y : q.z);
}

qo_status qo_euler_to_quat_f32(qo_euler_seq seq, qo_euler_f32 e, qo_quat_f32 *out)
{
    const unsigned char *ax;
    qo_quat_f32 q1, q2, q3;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    if (!qo_euler_seq_valid(seq)) return QO_E_ARG;
    if (!isfinite(e.a1) || !isfinite(e.a2) || !isfinite(e.a3)) return QO_E_NONFINITE;
    ax = qo_euler_seq_row(seq);
    q1 = elem_quat(ax[0], e.a1);
    q2 = elem_quat(ax[1], e.a2);
    q3 = elem_quat(ax[2], e.a3);
    if ((int)seq >= 12) *out = qo_quat_mul_f32(qo_quat_mul_f32(q1, q2), q3); /* body axes */
    else *out = qo_quat_mul_f32(q3, qo_quat_mul_f32(q2, q1));                /* world axes */
    return QO_OK;
}

/* a + 2*pi*k for the integer k that brings it nearest ref. The small correction k*LO goes in
 * first while the value is still small, the exact k*HI last: one rounding at the size of the
 * result, not three. */
static float unwrap_toward(float a, float ref)
{
    float k = roundf((ref - a) * INV_TWO_PI_F);
    return (a + k * TWO_PI_LO) + k * TWO_PI_HI;
}

/* a + pi with one rounding (PI_F itself is 8.7e-8 off pi). */
static float add_pi(float a)
{
    return (a + PI_LO) + PI_HI;
}

/* arg(u + iv)^2 = 2 arg(u + iv), already in [-pi, pi] (no wrap, no 2*pi constant error). */
static float double_arg(float u, float v)
{
    return qo_fm_atan2_f32(2.0f * u * v, (u - v) * (u + v));
}

/* The full (unlocked) decomposition of q, plus the lock margin. */
typedef struct decomp {
    qo_euler_f32 e;  /* principal solution, scipy ranges */
    float margin;    /* rad, [0, pi/2] */
} decomp;

/* Every quantity below is a ratio or an angle of q's components, so q needs no normalising
 * (which would round each component once more): an exact power-of-two scaling is enough to
 * keep the squares away from overflow and underflow. Requires q finite and non-zero. */
static qo_quat_f32 scale_pow2(qo_quat_f32 q)
{
    float m = fabsf(q.w);
    if (fabsf(q.x) > m) m = fabsf(q.x);
    if (fabsf(q.y) > m) m = fabsf(q.y);
    if (fabsf(q.z) > m) m = fabsf(q.z);
    /* Scale step by step: a subnormal-only q needs 2^160, which as one factor would overflow
     * float to Inf (and 0 * Inf = NaN); each step is exact and stays below 2^60. */
    while (m < 0x1p-20f) {
        m *= 0x1p40f;
        q.w *= 0x1p40f; q.x *= 0x1p40f; q.y *= 0x1p40f; q.z *= 0x1p40f;
    }
    while (m > 0x1p20f) {
        m *= 0x1p-40f;
        q.w *= 0x1p-40f; q.x *= 0x1p-40f; q.y *= 0x1p-40f; q.z *= 0x1p-40f;
    }
    return q;
}

/* skip_band >= 0: the caller only needs to know whether margin <= skip_band, so the margin's
 * atan2 is skipped when it is certainly larger (margin is then reported as pi/2). */
static decomp decompose(qo_quat_f32 q, qo_euler_seq seq, float skip_band)
{
    const unsigned char *ax = qo_euler_seq_row(seq);
    int intrinsic = (int)seq >= 12;
    int i = intrinsic ? ax[0] : ax[2];
    int j = ax[1];
    int k = intrinsic ? ax[2] : ax[0];
    /* eps = +1 when e_i x e_j = +e_(third axis), i.e. (i, j, .) is cyclic. */
    float eps = (j == (int)qo_euler_axis_next((unsigned)i)) ? 1.0f : -1.0f;
    /* the components by index (1 + axis): a load each instead of quat_comp's branches (the
     * struct is four floats without padding, as qorient/quat.h's SIMD bodies assume) */
    float qc[4];
    float t1, t2, t3, n1, n2, lo, hi, ny[4], nx[4], at[4];
    int skip;
    decomp r;
    memcpy(qc, &q, sizeof qc);
    if (i == k) {
        /* Proper, l = the remaining axis. Expanding q_i(t1) q_j(t2) q_i(t3) with c = cos(t2/2),
         * s = sin(t2/2), S = (t1 + t3)/2, D = (t1 - t3)/2:
         *   w = c cos S,  q_i = c sin S,  q_j = s cos D,  eps q_l = s sin D.
         * So t2 = 2 atan2(|(q_j, q_l)|, |(w, q_i)|) in [0, pi]: singular at 0 (D undefined)
         * and pi (S undefined). t1 = S + D and t3 = S - D are the arguments of the complex
         * products (a + ib)(c + id) and (a + ib)(c - id): one atan2 each, in [-pi, pi]. */
        int l = 3 - i - j;
        float a = q.w, b = qc[1 + i], c = qc[1 + j], d = eps * qc[1 + l];
        n1 = qo_fm_sqrt_nonneg(a * a + b * b);
        n2 = qo_fm_sqrt_nonneg(c * c + d * d);
        ny[0] = n2; nx[0] = n1;
        ny[1] = b * c + a * d; nx[1] = a * c - b * d;
        ny[2] = b * c - a * d; nx[2] = a * c + b * d;
    } else {
        /* Tait-Bryan. With t3' = eps t3 and (x, y, z) = (q_i, q_j, eps q_k), the product
         * q_i(t1) q_j(t2) q_k(t3) is the even-permutation one, and
         *   a = w - y = sqrt2 cos(p/2) cos D,   b = x + z = sqrt2 sin(p/2) sin S,
         *   c = w + y = sqrt2 sin(p/2) cos S,   d = z - x = -sqrt2 cos(p/2) sin D,
         * where p = t2 + pi/2, S = (t1 + t3')/2, D = (t1 - t3')/2. So p = 2 atan2(n2, n1) with
         * n1 = |(a,d)|, n2 = |(b,c)|, i.e. t2 = atan2(n2^2 - n1^2, 2 n1 n2) in [-pi/2, pi/2]
         * (one atan2, no pi/2 constant): singular at -pi/2 (n2 = 0, S undefined) and +pi/2
         * (n1 = 0, D undefined). t1 = S + D = arg((c + ib)(a - id)),
         * t3' = S - D = arg((c + ib)(a + id)). */
        float x = qc[1 + i], y = qc[1 + j], z = eps * qc[1 + k];
        float a = q.w - y, b = x + z, c = q.w + y, d = z - x;
        n1 = qo_fm_sqrt_nonneg(a * a + d * d);
        n2 = qo_fm_sqrt_nonneg(b * b + c * c);
        ny[0] = (n2 - n1) * (n2 + n1); nx[0] = 2.0f * n1 * n2;
        ny[1] = b * a - c * d; nx[1] = c * a + b * d;
        ny[2] = b * a + c * d; nx[2] = c * a - b * d;
    }
    /* The distance to the nearer singularity straight from the two norms (no subtraction
     * from pi, so it keeps its accuracy down to 0). */
    lo = n1 < n2 ? n1 : n2;
    hi = n1 < n2 ? n2 : n1;
    /* margin = 2 atan(lo/hi) >= (pi/2) lo/hi on [0, 1] (atan is concave there): when that
     * bound clears the band by 1 % (far more than atan2's 2.5 ulp) and lo/hi is far from
     * underflow, the margin exceeds the band and its atan2 (a quarter of the cost of the
     * whole decomposition) is not needed. */
    skip = !QO_FM_ATAN2X4_WIDE && skip_band >= 0.0f && lo > 1e-30f * hi &&
           1.5707963f * lo > 1.01f * skip_band * hi;
    /* The three or four atan2 are independent: one call computes them. 4-wide (SSE2) the
     * margin's lane costs nothing extra and the bound is not tested; the lock decision is the
     * same either way. */
    ny[3] = lo; nx[3] = hi;
    qo_fm_atan2x4_f32(ny, nx, at, skip ? 3 : 4);
    r.margin = skip ? HALF_PI_F : 2.0f * at[3];
    if (i == k) {
        t2 = 2.0f * at[0];
        t1 = at[1];
        t3 = at[2];
    } else {
        t2 = at[0];
        t1 = at[1];
        t3 = eps * at[2];
    }
    r.e.a2 = t2;
    r.e.a1 = intrinsic ? t1 : t3;
    r.e.a3 = intrinsic ? t3 : t1;
    return r;
}

/* Given a2 and a3, the a1 whose composition is nearest q: with q = A1 * rest (intrinsic) or
 * rest * A1 (extrinsic), p = the part of q left for A1 and a1 = 2 atan2(p . axis, p.w), which
 * maximises |<q_axis(a1), p>|. Result in [-pi, pi]. */
static float fit_a1(qo_quat_f32 q, qo_euler_seq seq, float a2, float a3)
{
    const unsigned char *ax = qo_euler_seq_row(seq);
    qo_quat_f32 c2 = qo_quat_conj_f32(elem_quat(ax[1], a2));
    qo_quat_f32 c3 = qo_quat_conj_f32(elem_quat(ax[2], a3));
    qo_quat_f32 p;
    if ((int)seq >= 12) p = qo_quat_mul_f32(qo_quat_mul_f32(q, c3), c2); /* q = q1 q2 q3 */
    else p = qo_quat_mul_f32(c2, qo_quat_mul_f32(c3, q));                /* q = q3 q2 q1 */
    return double_arg(p.w, quat_comp(p, ax[0]));
}

static void set_error_outputs(qo_euler_f32 *out, qo_euler_info_f32 *info)
{
    out->a1 = out->a2 = out->a3 = 0.0f;
    if (info != NULL) { info->locked = 0; info->margin = 0.0f; }
}

/* Shared argument checks; on success *qn is q scaled by a power of two (same rotation). */
static qo_status check_args(qo_quat_f32 q, qo_euler_seq seq, float band, qo_quat_f32 *qn)
{
    *qn = q;
    if (!qo_euler_seq_valid(seq)) return QO_E_ARG;
    if (!isfinite(band)) return QO_E_NONFINITE;
    if (!qo_quat_is_finite_f32(q)) return QO_E_NONFINITE;
    if (q.w == 0.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f) return QO_E_DEGENERATE;
    if (!(band >= 0.0f && band <= HALF_PI_F)) return QO_E_RANGE;
    *qn = scale_pow2(q);
    return QO_OK;
}

/* The decomposition of a checked, scaled q (band in [0, pi/2]). */
static inline void to_euler_checked(qo_quat_f32 qn, qo_euler_seq seq, float band_rad,
                             qo_euler_f32 *out, qo_euler_info_f32 *info)
{
    decomp r = decompose(qn, seq, info == NULL ? band_rad : -1.0f);
    if (r.margin <= band_rad) {
        /* scipy's choice: a3 = 0, a1 takes the determined sum/difference. */
        r.e.a3 = 0.0f;
        r.e.a1 = fit_a1(qn, seq, r.e.a2, 0.0f);
    }
    *out = r.e;
    if (info != NULL) { info->locked = r.margin <= band_rad; info->margin = r.margin; }
}

qo_status qo_euler_from_quat_band_f32(qo_quat_f32 q, qo_euler_seq seq, float band_rad,
                                    qo_euler_f32 *out, qo_euler_info_f32 *info)
{
    qo_quat_f32 qn;
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    set_error_outputs(out, info);
    st = check_args(q, seq, band_rad, &qn);
    if (st != QO_OK) return st;
    to_euler_checked(qn, seq, band_rad, out, info);
    return QO_OK;
}

/* |v|'s bits: as integers they order like the magnitudes, NaN above Inf above every finite. */
static uint32_t abs_bits(float v)
{
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    return u & 0x7fffffffu;
}

qo_status qo_euler_from_quat_f32(qo_quat_f32 q, qo_euler_seq seq, qo_euler_f32 *out,
                               qo_euler_info_f32 *info)
{
    /* The common case without check_args' separate tests: the largest |component| in
     * [2^-20, 2^20] means q is finite and non-zero and scale_pow2 would leave it as it is;
     * the band is the constant. Everything else goes the checked way (same results). */
    uint32_t m = abs_bits(q.w), b;
    b = abs_bits(q.x); if (b > m) m = b;
    b = abs_bits(q.y); if (b > m) m = b;
    b = abs_bits(q.z); if (b > m) m = b;
    if (out != NULL && (unsigned)seq < (unsigned)QO_EULER_SEQ_COUNT_ &&
        m - 0x35800000u <= 0x49800000u - 0x35800000u) {   /* 2^-20 ... 2^20 */
        to_euler_checked(q, seq, QO_EULER_LOCK_BAND_F32, out, info);
        return QO_OK;
    }
    return qo_euler_from_quat_band_f32(q, seq, QO_EULER_LOCK_BAND_F32, out, info);
}

static float sq(float v) { return v * v; }

qo_status qo_euler_from_quat_near_f32(qo_quat_f32 q, qo_euler_seq seq, qo_euler_f32 prev,
                                    float band, qo_euler_f32 *out, qo_euler_info_f32 *info)
{
    qo_quat_f32 qn;
    qo_status st;
    decomp r;
    qo_euler_f32 p, alt;
    float alt2;
    int prev_ok = isfinite(prev.a1) && isfinite(prev.a2) && isfinite(prev.a3);
    if (out == NULL) return QO_E_NULL;
    set_error_outputs(out, info);
    if (!prev_ok) return qo_euler_seq_valid(seq) ? QO_E_NONFINITE : QO_E_ARG;
    st = check_args(q, seq, band, &qn);
    if (st != QO_OK) {
        *out = prev; /* hold the joint */
        return st;
    }
    r = decompose(qn, seq, -1.0f);
    /* The second solution: (a1 + pi, pi - a2, a3 + pi) Tait-Bryan, (a1 + pi, -a2, a3 + pi)
     * proper (a rotation by pi about the first axis conjugates the middle one into its
     * negative, and the two pi's combine into the identity). */
    alt2 = qo_euler_seq_is_proper(seq) ? -r.e.a2 : add_pi(-r.e.a2);
    p.a2 = unwrap_toward(r.e.a2, prev.a2);
    alt.a2 = unwrap_toward(alt2, prev.a2);
    if (r.margin <= band) {
        /* Locked: keep prev's split (a3 = prev.a3), take the middle angle of the branch
         * nearer prev and fit a1 to it. */
        if (fabsf(alt.a2 - prev.a2) < fabsf(p.a2 - prev.a2)) p.a2 = alt.a2;
        p.a3 = prev.a3;
        p.a1 = unwrap_toward(fit_a1(qn, seq, p.a2, p.a3), prev.a1);
    } else {
        p.a1 = unwrap_toward(r.e.a1, prev.a1);
        p.a3 = unwrap_toward(r.e.a3, prev.a3);
        alt.a1 = unwrap_toward(add_pi(r.e.a1), prev.a1);
        alt.a3 = unwrap_toward(add_pi(r.e.a3), prev.a3);
        if (sq(alt.a1 - prev.a1) + sq(alt.a2 - prev.a2) + sq(alt.a3 - prev.a3) <
            sq(p.a1 - prev.a1) + sq(p.a2 - prev.a2) + sq(p.a3 - prev.a3)) {
            p = alt;
        }
    }
    *out = p;
    if (info != NULL) { info->locked = r.margin <= band; info->margin = r.margin; }
    return QO_OK;
}
