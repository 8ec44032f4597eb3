/* Euler angles (qorient/euler.h, float32; qorient/euler_fx.h, Q1.30 in / Q3.28 out): all 24
 * conventions against a double-precision reference (products of elementary rotations,
 * tests/common/ref.c), scipy's documented examples, hand-derived values, exactly singular and
 * just-off-singular inputs, bad inputs and the nearest-solution decomposition.
 *
 * One body per behaviour both cores have (docs/TESTING.md, "One body for both cores"): each
 * body takes a `core` through cmocka's prestate - float32, fixed point, and for the
 * quaternion-to-angles bodies the fixed fast tier (qo_euler_from_quat_fast_q30) - whose adapters
 * take doubles, round them to what that core holds (float32, or Q1.30 / Q3.28 rounded to
 * nearest and saturated) and give the results back as doubles. The reference is computed from
 * the value the core was given, and each core is judged with the tolerances of its table row.
 * BOTH(fn) registers a body for float32 and fixed, ALL3(fn) for the fast tier too: one cmocka
 * line per core, and a failure message starts with the core's name.
 *
 * Layout: sequence names (no core) | shared bodies: from_euler, to_euler, gimbal lock, bad
 * inputs, nearest solution | float32 only (NaN, Inf, subnormal and huge components) | fixed
 * only (raw int32 inputs for the exact function and the fast tier, the Q3.28 range end of the
 * nearest variant, band limits in LSB). Fixed seeds (splitmix64); every failure names the core,
 * the convention and the inputs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#define CORES_OWN_TABLE   /* Euler's table below: lock band, fast tier, angles */
#include "common/cores.h"
#include "common/dq.h"
#include "qorient/euler.h"
#include "qorient/euler_fx.h"
#include "qorient/fxmath.h"

/* The convention names (ref_euler_names) are tests/common/ref.c's copy, in the enum's order
 * (ABI), with the axes derived from the letters: the reference shares nothing with the code
 * under test. */

static ref_rng rng;

static double wrap_d(double a) { return a - 2 * PI * floor((a + PI) / (2 * PI)); }
static double ang_diff(double a, double b) { return fabs(wrap_d(a - b)); }
static double dmax(double a, double b) { return a > b ? a : b; }

static double singular_value(int seq, int which)
{
    if (ref_euler_proper(seq)) return which ? PI : 0.0;
    return which ? PI / 2 : -PI / 2;
}

/* ---- the cores behind one interface ------------------------------------------------------ */
typedef struct einfo { int locked; double margin; } einfo;

typedef struct core {
    const char *name;
    int fixed;          /* 0: float32; 1: fixed point (exact function or fast tier) */
    double band;        /* its default lock band, rad (as held by the core) */
    double tol_from;    /* from_euler: largest component error */
    double tol_from_sum; /* from_euler: sum of the component errors, and the rotation error */
    double tol_fine;    /* recomposition bound off lock: the 1e-6 goal (float32), or what the
                         * fixed method's error analysis gives: each angle within ~2 LSB of
                         * Q3.28 (atan2 1 LSB + 30-bit argument reduction), so 3 angles plus
                         * the input's rounding stay below 5e-8 */
    double tol_lock;    /* the same at an exactly singular input: 1e-5 goal / 5e-8 fixed */
    double tol_noise;   /* recomposition of a singular input with each component moved by up
                         * to 2 steps: 1e-5 (float32); 2 * band + tol_lock (fixed) */
    double a_max;       /* the largest angle the core's angle type holds, rad */
    double (*rq)(double v);              /* the component value the core holds for v */
    double (*ra)(double a);              /* the angle value the core holds for a */
    double (*nudge)(double v, int units); /* v moved by `units` steps of its last place */
    /* out may be NULL (passed on as NULL) */
    qo_status (*from_euler)(int seq, const double a[3], dq *out);
    /* use_default: the default-band function (band ignored); out and info may be NULL */
    qo_status (*to_euler)(dq q, int seq, int use_default, double band, double out[3], einfo *info);
    qo_status (*near)(dq q, int seq, const double prev[3], double band, double out[3], einfo *info);
} core;

/* The conversions of a prefix P (f: float32, x: fixed): P##_in(v, scale) is v as the core's
 * scalar (float32; or rounded to nearest and saturated, ref_to_fixed), P##_QS and P##_AS the
 * scales of a component and an angle; DEFINE_EULER_ADAPTERS writes the wrappers from them,
 * the same text for both cores. Outputs start as garbage (9, 7) so that an output the library
 * does not write shows. */
static float f_in(double v, double scale) { (void)scale; return (float)v; }
#define f_QS 1.0
#define f_AS 1.0
static int32_t x_in(double v, double scale) { return ref_to_fixed(v, scale); }
#define x_QS Q30
#define x_AS Q28

#define DEFINE_EULER_ADAPTERS(P, SFX, QT, ET, IT)                                               \
    static double P##_rq(double v) { return P##_in(v, P##_QS) / P##_QS; }                       \
    static double P##_ra(double a) { return P##_in(a, P##_AS) / P##_AS; }                       \
    static QT P##_quat(dq q)                                                                    \
    {                                                                                           \
        QT r;                                                                                   \
        r.w = P##_in(q.w, P##_QS); r.x = P##_in(q.x, P##_QS);                                   \
        r.y = P##_in(q.y, P##_QS); r.z = P##_in(q.z, P##_QS);                                   \
        return r;                                                                               \
    }                                                                                           \
    static ET P##_angles(const double a[3])                                                     \
    {                                                                                           \
        ET e;                                                                                   \
        e.a1 = P##_in(a[0], P##_AS); e.a2 = P##_in(a[1], P##_AS); e.a3 = P##_in(a[2], P##_AS);  \
        return e;                                                                               \
    }                                                                                           \
    static void P##_back(ET e, IT i, double out[3], einfo *info)                                \
    {                                                                                           \
        if (out) { out[0] = e.a1 / P##_AS; out[1] = e.a2 / P##_AS; out[2] = e.a3 / P##_AS; }    \
        if (info) { info->locked = i.locked; info->margin = i.margin / P##_AS; }                \
    }                                                                                           \
    static qo_status P##_from_euler(int seq, const double a[3], dq *out)                              \
    {                                                                                           \
        QT q;                                                                                   \
        qo_status st;                                                                           \
        q.w = q.x = q.y = q.z = 7;                                                              \
        st = qo_euler_to_quat_##SFX((qo_euler_seq)seq, P##_angles(a), out ? &q : NULL);       \
        if (out) {                                                                              \
            out->w = q.w / P##_QS; out->x = q.x / P##_QS;                                       \
            out->y = q.y / P##_QS; out->z = q.z / P##_QS;                                       \
        }                                                                                       \
        return st;                                                                              \
    }                                                                                           \
    static qo_status P##_to(dq q, int seq, int use_default, double band, double out[3],         \
                            einfo *info)                                                        \
    {                                                                                           \
        ET e = { 9, 9, 9 };                                                                     \
        IT i = { 7, 9 };                                                                        \
        qo_status st = use_default                                                              \
            ? qo_euler_from_quat_##SFX(P##_quat(q), (qo_euler_seq)seq, out ? &e : NULL,           \
                                     info ? &i : NULL)                                          \
            : qo_euler_from_quat_band_##SFX(P##_quat(q), (qo_euler_seq)seq, P##_in(band, P##_AS), \
                                          out ? &e : NULL, info ? &i : NULL);                   \
        P##_back(e, i, out, info);                                                              \
        return st;                                                                              \
    }                                                                                           \
    static qo_status P##_near(dq q, int seq, const double prev[3], double band, double out[3],  \
                              einfo *info)                                                      \
    {                                                                                           \
        ET e = { 9, 9, 9 };                                                                     \
        IT i = { 7, 9 };                                                                        \
        qo_status st = qo_euler_from_quat_near_##SFX(P##_quat(q), (qo_euler_seq)seq,              \
                                                   P##_angles(prev), P##_in(band, P##_AS),      \
                                                   out ? &e : NULL, info ? &i : NULL);          \
        P##_back(e, i, out, info);                                                              \
        return st;                                                                              \
    }

DEFINE_EULER_ADAPTERS(f, f32, qo_quat_f32, qo_euler_f32, qo_euler_info_f32)
DEFINE_EULER_ADAPTERS(x, q30, qo_quat_q30, qo_euler_q28, qo_euler_info_q28)

static double f_nudge(double v, int u)
{
    float f = (float)v;
    for (; u > 0; u--) f = nextafterf(f, INFINITY);
    for (; u < 0; u++) f = nextafterf(f, -INFINITY);
    return f;
}
static double x_nudge(double v, int u)
{
    int64_t r = (int64_t)x_in(v, Q30) + u;
    if (r > INT32_MAX) r = INT32_MAX;
    if (r < INT32_MIN) r = INT32_MIN;
    return (double)r / Q30;
}

/* The fast tier (qo_euler_from_quat_fast_q30) as to_euler: the band form, given the default
 * band for use_default; from_euler and near are the exact core's (it has neither). */
static qo_status xf_to(dq q, int seq, int use_default, double band, double out[3], einfo *info)
{
    qo_euler_q28 e = { 9, 9, 9 };
    qo_euler_info_q28 i = { 7, 9 };
    qo_status st = qo_euler_from_quat_fast_q30(x_quat(q), (qo_euler_seq)seq,
                                             use_default ? QO_EULER_LOCK_BAND_Q28 : x_in(band, Q28),
                                             out ? &e : NULL, info ? &i : NULL);
    x_back(e, i, out, info);
    return st;
}

#define X_BAND (27.0 / Q28) /* QO_EULER_LOCK_BAND_Q28 */
#define X_AMAX (2147483647.0 / Q28) /* INT32_MAX as Q3.28: 7.99999999 rad */
static const core CORE_F32 = { "float32", 0, 2e-6, 1e-6, 1e-6, 1e-6, 1e-5, 1e-5, 1e30,
                               f_rq, f_ra, f_nudge, f_from_euler, f_to, f_near };
/* Q1.30 output: each component a few LSB (9.3e-10) from exact. */
static const core CORE_FX = { "fixed", 1, X_BAND, 1e-8, 4e-8, 5e-8, 5e-8, 2 * X_BAND + 5e-8,
                               X_AMAX, x_rq, x_ra, x_nudge, x_from_euler, x_to, x_near };
/* fast tier: three atan2 of 32-bit pairs, each angle a few LSB */
static const core CORE_FX_FAST = { "fixed fast", 1, X_BAND, 1e-8, 4e-8, 5e-8, 5e-8,
                                    2 * X_BAND + 5e-8, X_AMAX, x_rq, x_ra, x_nudge, x_from_euler,
                                    xf_to, x_near };

/* The quaternion the core holds for q, as exact doubles (not normalised). */
static dq held(const core *c, dq q)
{
    dq r;
    r.w = c->rq(q.w); r.x = c->rq(q.x); r.y = c->rq(q.y); r.z = c->rq(q.z);
    return r;
}

/* How far the angles, composed in double, are from the rotation q. */
static double recompose_err(int seq, const double e[3], dq q)
{
    return dq_angle(ref_quat_from_euler(ref_euler_names[seq], e[0], e[1], e[2]), q);
}

static void check_ranges(const core *c, int seq, const double e[3], const char *what)
{
    double pi = c->ra(PI), hpi = c->ra(PI / 2);
    int ok = e[0] >= -pi && e[0] <= pi && e[2] >= -pi && e[2] <= pi;
    if (ref_euler_proper(seq)) ok = ok && e[1] >= 0.0 && e[1] <= pi;
    else ok = ok && e[1] >= -hpi && e[1] <= hpi;
    if (!ok) fail_msg("%s %s %s: angles (%.10g %.10g %.10g) outside scipy's ranges", c->name, what,
                      ref_euler_names[seq], e[0], e[1], e[2]);
}

/* ---- sequence names (one parser for both cores) ------------------------------------------ */
static void test_seq_parse_and_name(void **state)
{
    int i;
    qo_euler_seq s;
    (void)state;
    for (i = 0; i < 24; i++) {
        qo_status st = qo_euler_seq_parse(ref_euler_names[i], &s);
        if (st != QO_OK || (int)s != i)
            fail_msg("parse(\"%s\") gave status %d seq %d, want %d", ref_euler_names[i], (int)st, (int)s, i);
        assert_string_equal(qo_euler_seq_name((qo_euler_seq)i), ref_euler_names[i]);
        assert_int_equal(qo_euler_seq_is_intrinsic((qo_euler_seq)i), i >= 12);
        assert_int_equal(qo_euler_seq_is_proper((qo_euler_seq)i), ref_euler_proper(i));
    }
    assert_string_equal(qo_euler_seq_name(QO_EULER_SEQ_COUNT_), "invalid");
    assert_string_equal(qo_euler_seq_name((qo_euler_seq)-1), "invalid");
    assert_int_equal(qo_euler_seq_is_intrinsic(QO_EULER_SEQ_COUNT_), 0);
    assert_int_equal(qo_euler_seq_is_proper((qo_euler_seq)99), 0);
    assert_int_equal(QO_EULER_XYZ, 12);
    assert_int_equal(QO_EULER_zyz, 11);
}

static void test_seq_parse_rejects(void **state)
{
    static const char *const bad[] = {
        "", "x", "xy", "xyzx", "xyz ", " xyz", "xxy", "xyy", "XXZ", "zzz", "xYz", "XyZ", "xyZ",
        "abc", "xy1", "XY", "uvw", "x-y", "XYZXYZ", "wxy", "{yz",
    };
    size_t i;
    qo_euler_seq s;
    (void)state;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        s = QO_EULER_ZYX;
        if (qo_euler_seq_parse(bad[i], &s) != QO_E_ARG || s != QO_EULER_SEQ_COUNT_)
            fail_msg("parse(\"%s\") accepted or left out unset (%d)", bad[i], (int)s);
    }
    s = QO_EULER_ZYX;
    assert_int_equal(qo_euler_seq_parse(NULL, &s), QO_E_NULL);
    assert_int_equal(s, QO_EULER_SEQ_COUNT_);
    assert_int_equal(qo_euler_seq_parse("xyz", NULL), QO_E_NULL);
}

/* ---- from_euler (float32, fixed) ----------------------------------------------------------- */
static void test_euler_to_quat_random_all24(void **state)
{
    const core *c = *state;
    int seq, n;
    rng.s = 0x1234567ull;
    for (seq = 0; seq < 24; seq++) {
        for (n = 0; n < 500; n++) {
            /* Most in one turn; some wider, as the angles are periodic: to 10 rad, or to the
             * end of Q3.28 ([-8, 8)). */
            double span = (n % 5 == 0) ? fmin(10.0, c->a_max - 0.01) : PI, a[3], err, sum, ang;
            dq q, r;
            a[0] = c->ra(ref_rng_range(&rng, -span, span));
            a[1] = c->ra(ref_rng_range(&rng, -span, span));
            a[2] = c->ra(ref_rng_range(&rng, -span, span));
            assert_int_equal(c->from_euler(seq, a, &q), QO_OK);
            r = ref_quat_from_euler(ref_euler_names[seq], a[0], a[1], a[2]);
            /* Same sign as the product, not only the same rotation (scipy's as_quat). */
            err = fmax(fmax(fabs(q.w - r.w), fabs(q.x - r.x)), fmax(fabs(q.y - r.y), fabs(q.z - r.z)));
            sum = fabs(q.w - r.w) + fabs(q.x - r.x) + fabs(q.y - r.y) + fabs(q.z - r.z);
            ang = dq_angle(q, r);
            if (err > c->tol_from || sum > c->tol_from_sum || ang > c->tol_from_sum)
                fail_msg("%s euler_to_quat %s (%.10g %.10g %.10g): component error %.3g (sum %.3g, "
                         "rotation %.3g)", c->name, ref_euler_names[seq], a[0], a[1], a[2], err, sum, ang);
        }
    }
}

/* The rotation of q applied to v, in double, against the expected image (x, y, z). */
static void expect_image(const core *c, const char *what, dq q, ref_vec3 v, double x, double y,
                         double z)
{
    ref_vec3 r = ref_quat_rotate(q, v);
    if (fabs(r.x - x) > 1e-6 || fabs(r.y - y) > 1e-6 || fabs(r.z - z) > 1e-6)
        fail_msg("%s %s: image (%.10g %.10g %.10g), want (%g %g %g)", c->name, what, r.x, r.y,
                 r.z, x, y, z);
}

/* scipy's documented examples and hand-derived values (exact answers, not code output). */
static void test_euler_to_quat_known_values(void **state)
{
    const core *c = *state;
    const double h = sqrt(0.5), d90 = c->ra(PI / 2);
    const ref_vec3 vx = { 1, 0, 0 }, vz = { 0, 0, 1 };
    double a[3], b[3], tol = c->tol_from + 1e-9, tol_same = fmin(1e-7, tol);
    dq q, q2;
    int seq;
    /* scipy as_rotvec docs: from_euler('YX', (-90, -90)) is 120 deg about -(1,1,1)/sqrt3, i.e.
     * q = (0.5, -0.5, -0.5, -0.5). A 3-letter intrinsic "YXZ" with a3 = 0 is the same. */
    a[0] = -d90; a[1] = -d90; a[2] = 0.0;
    assert_int_equal(c->from_euler(QO_EULER_YXZ, a, &q), QO_OK);
    if (fabs(q.w - 0.5) > tol || fabs(q.x + 0.5) > tol || fabs(q.y + 0.5) > tol ||
        fabs(q.z + 0.5) > tol)
        fail_msg("%s YXZ(-90,-90,0) = (%.10g %.10g %.10g %.10g)", c->name, q.w, q.x, q.y, q.z);
    /* scipy: from_euler('z', 90).as_quat() = [0, 0, 0.7071, 0.7071] (x, y, z, w). Here as the
     * yaw of intrinsic ZYX (aerospace yaw-pitch-roll): it turns x into y. */
    a[0] = d90; a[1] = 0.0; a[2] = 0.0;
    assert_int_equal(c->from_euler(QO_EULER_ZYX, a, &q), QO_OK);
    if (fabs(q.w - h) > tol || fabs(q.z - h) > tol || q.x != 0.0 || q.y != 0.0)
        fail_msg("%s ZYX yaw 90 = (%.10g %.10g %.10g %.10g)", c->name, q.w, q.x, q.y, q.z);
    expect_image(c, "ZYX yaw 90 of x", q, vx, 0, 1, 0);
    /* Intrinsic vs extrinsic differ: XYZ (90, 90, 0) = Rx(90) Ry(90) sends z to x;
     * xyz (90, 90, 0) = Ry(90) Rx(90) sends z to -y. */
    a[0] = d90; a[1] = d90; a[2] = 0.0;
    assert_int_equal(c->from_euler(QO_EULER_XYZ, a, &q), QO_OK);
    expect_image(c, "XYZ (90, 90, 0) of z", q, vz, 1, 0, 0);
    assert_int_equal(c->from_euler(QO_EULER_xyz, a, &q), QO_OK);
    expect_image(c, "xyz (90, 90, 0) of z", q, vz, 0, -1, 0);
    /* Zero angles: the identity exactly, every convention. */
    a[0] = a[1] = a[2] = 0.0;
    for (seq = 0; seq < 24; seq++) {
        assert_int_equal(c->from_euler(seq, a, &q), QO_OK);
        if (q.w != 1.0 || q.x != 0.0 || q.y != 0.0 || q.z != 0.0)
            fail_msg("%s %s zero angles: (%.10g %.10g %.10g %.10g)", c->name, ref_euler_names[seq],
                     q.w, q.x, q.y, q.z);
    }
    /* Intrinsic XYZ (a, b, c) is extrinsic zyx (c, b, a): the same quaternion. */
    a[0] = c->ra(0.3); a[1] = c->ra(-1.1); a[2] = c->ra(2.5);
    b[0] = a[2]; b[1] = a[1]; b[2] = a[0];
    assert_int_equal(c->from_euler(QO_EULER_XYZ, a, &q), QO_OK);
    assert_int_equal(c->from_euler(QO_EULER_zyx, b, &q2), QO_OK);
    if (fabs(q.w - q2.w) > tol_same || fabs(q.x - q2.x) > tol_same || fabs(q.y - q2.y) > tol_same ||
        fabs(q.z - q2.z) > tol_same)
        fail_msg("%s XYZ vs zyx differ: (%.10g %.10g %.10g %.10g) vs (%.10g %.10g %.10g %.10g)",
                 c->name, q.w, q.x, q.y, q.z, q2.w, q2.x, q2.y, q2.z);
    /* 360 deg about one axis is -identity (the product's sign is kept). */
    a[0] = c->ra(2 * PI); a[1] = 0.0; a[2] = 0.0;
    assert_int_equal(c->from_euler(QO_EULER_XYZ, a, &q), QO_OK);
    if (fabs(q.w + 1.0) > tol) fail_msg("%s 2pi about X: w = %.10g", c->name, q.w);
}

/* Bad sequences: QO_E_ARG and the identity; NULL out. An angle past the core's range (1e39:
 * Inf in float32, saturated to INT32_MAX in Q3.28) in each place: float32 rejects it with
 * QO_E_NONFINITE and the identity, fixed point takes the saturated angle as any other. */
static void test_euler_to_quat_bad_inputs(void **state)
{
    const core *c = *state;
    const double a[3] = { 0.1, 0.2, 0.3 };
    dq q;
    int i;
    assert_int_equal(c->from_euler(QO_EULER_xyz, a, NULL), QO_E_NULL);
    assert_int_equal(c->from_euler(QO_EULER_SEQ_COUNT_, a, &q), QO_E_ARG);
    if (q.w != 1.0 || q.x != 0.0 || q.y != 0.0 || q.z != 0.0)
        fail_msg("%s euler_to_quat bad seq: out is not the identity", c->name);
    assert_int_equal(c->from_euler(-3, a, &q), QO_E_ARG);
    assert_true(q.w == 1.0 && q.x == 0.0 && q.y == 0.0 && q.z == 0.0);
    for (i = 0; i < 6; i++) {
        double b[3], err;
        dq r;
        qo_status st;
        b[0] = c->ra(a[0]); b[1] = c->ra(a[1]); b[2] = c->ra(a[2]);
        b[i / 2] = c->ra(i % 2 ? -1e39 : 1e39);
        st = c->from_euler(QO_EULER_ZXZ, b, &q);
        if (st != (c->fixed ? QO_OK : QO_E_NONFINITE))
            fail_msg("%s euler_to_quat angle %d = %g: status %d", c->name, i / 2, b[i / 2], (int)st);
        if (st != QO_OK) {
            assert_true(q.w == 1.0 && q.x == 0.0 && q.y == 0.0 && q.z == 0.0);
            continue;
        }
        r = ref_quat_from_euler(ref_euler_names[QO_EULER_ZXZ], b[0], b[1], b[2]);
        err = fmax(fmax(fabs(q.w - r.w), fabs(q.x - r.x)), fmax(fabs(q.y - r.y), fabs(q.z - r.z)));
        if (err > c->tol_from)
            fail_msg("%s euler_to_quat saturated angle %d: error %.3g", c->name, i / 2, err);
    }
}

/* ---- to_euler: generic (float32, fixed, fixed fast) --------------------------------------- */
/* Uniform random rotation: 4 uniforms, rejected outside the unit ball, normalised. */
static dq random_unit(void)
{
    dq r;
    double nn;
    do {
        r.w = ref_rng_range(&rng, -1, 1); r.x = ref_rng_range(&rng, -1, 1);
        r.y = ref_rng_range(&rng, -1, 1); r.z = ref_rng_range(&rng, -1, 1);
        nn = r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z;
    } while (nn > 1.0 || nn < 1e-3);
    return dq_unit(r);
}

static void test_euler_from_quat_random_rotations_all24(void **state)
{
    const core *c = *state;
    int seq, n;
    rng.s = 42;
    for (seq = 0; seq < 24; seq++) {
        for (n = 0; n < 500; n++) {
            /* the reference is the rounded input itself */
            dq q = held(c, random_unit()), qn = dq_neg(q);
            double e[3], e2[3], err;
            einfo info, info2;
            assert_int_equal(c->to_euler(q, seq, 1, 0, e, &info), QO_OK);
            check_ranges(c, seq, e, "random");
            err = recompose_err(seq, e, q);
            if (err > c->tol_fine)
                fail_msg("%s euler_from_quat %s of q=(%.10g %.10g %.10g %.10g): (%.10g %.10g %.10g) "
                         "recomposes %.3g rad off", c->name, ref_euler_names[seq], q.w, q.x, q.y, q.z,
                         e[0], e[1], e[2], err);
            if (info.locked != (info.margin <= c->band))
                fail_msg("%s %s: locked %d with margin %.3g", c->name, ref_euler_names[seq],
                         info.locked, info.margin);
            /* q and -q: the same angles (exactly: the method is even in q). */
            assert_int_equal(c->to_euler(qn, seq, 1, 0, e2, &info2), QO_OK);
            if (e2[0] != e[0] || e2[1] != e[1] || e2[2] != e[2] || info2.margin != info.margin)
                fail_msg("%s %s: -q gave (%.10g %.10g %.10g), q (%.10g %.10g %.10g)", c->name,
                         ref_euler_names[seq], e2[0], e2[1], e2[2], e[0], e[1], e[2]);
            /* info may be NULL: same angles. */
            assert_int_equal(c->to_euler(q, seq, 1, 0, e2, NULL), QO_OK);
            assert_true(e2[0] == e[0] && e2[1] == e[1] && e2[2] == e[2]);
        }
    }
}

/* Angles in scipy's ranges, away from lock, come back as given (mod 2pi near +-pi). */
static void test_euler_from_quat_recovers_angles_all24(void **state)
{
    const core *c = *state;
    int seq, n;
    rng.s = 7;
    for (seq = 0; seq < 24; seq++) {
        for (n = 0; n < 300; n++) {
            double a1 = ref_rng_range(&rng, -PI, PI), a3 = ref_rng_range(&rng, -PI, PI), a2, margin;
            double e[3];
            dq q;
            einfo info;
            if (ref_euler_proper(seq)) {
                a2 = ref_rng_range(&rng, 0.05, PI - 0.05);
                margin = fmin(a2, PI - a2);
            } else {
                a2 = ref_rng_range(&rng, -PI / 2 + 0.05, PI / 2 - 0.05);
                margin = PI / 2 - fabs(a2);
            }
            q = ref_quat_from_euler(ref_euler_names[seq], a1, a2, a3);
            if (n % 2) q = dq_neg(q); /* q and -q */
            q = held(c, q);
            assert_int_equal(c->to_euler(q, seq, 1, 0, e, &info), QO_OK);
            /* a1, a3 are conditioned like 1/margin near lock. */
            if (ang_diff(e[0], a1) > 2e-5 || fabs(e[1] - a2) > 2e-6 || ang_diff(e[2], a3) > 2e-5 ||
                info.locked || fabs(info.margin - margin) > 2e-6)
                fail_msg("%s %s (%.10g %.10g %.10g) came back as (%.10g %.10g %.10g) locked %d "
                         "margin %.10g", c->name, ref_euler_names[seq], a1, a2, a3, e[0], e[1], e[2],
                         info.locked, info.margin);
        }
    }
}

/* scipy's as_euler docs: rotvec (0, 0, pi/2) is zxy (90, 0, 0); rotvec (0, -pi/3, 0) is
 * zxy (0, 0, -60). Hand-derived: identity gives zeros for Tait-Bryan; for proper sequences it
 * is exactly singular: locked, margin 0, a3 = 0, a1 = 0. */
static void test_euler_from_quat_known_values(void **state)
{
    const core *c = *state;
    dq q = { sqrt(0.5), 0, 0, sqrt(0.5) };
    const dq id = { 1, 0, 0, 0 };
    double e[3];
    einfo info;
    assert_int_equal(c->to_euler(held(c, q), QO_EULER_zxy, 1, 0, e, &info), QO_OK);
    if (fabs(e[0] - PI / 2) > 1e-6 || fabs(e[1]) > 1e-6 || fabs(e[2]) > 1e-6 || info.locked ||
        fabs(info.margin - PI / 2) > 1e-6)
        fail_msg("%s zxy of 90 about z: (%.10g %.10g %.10g)", c->name, e[0], e[1], e[2]);
    q.w = sqrt(0.75); q.x = 0.0; q.y = -0.5; q.z = 0.0;
    assert_int_equal(c->to_euler(held(c, q), QO_EULER_zxy, 1, 0, e, &info), QO_OK);
    if (fabs(e[0]) > 1e-6 || fabs(e[1]) > 1e-6 || fabs(e[2] + PI / 3) > 1e-6)
        fail_msg("%s zxy of -60 about y: (%.10g %.10g %.10g)", c->name, e[0], e[1], e[2]);
    assert_int_equal(c->to_euler(id, QO_EULER_ZYX, 1, 0, e, &info), QO_OK);
    if (fabs(e[0]) > 1e-7 || fabs(e[1]) > 1e-7 || fabs(e[2]) > 1e-7 || info.locked)
        fail_msg("%s ZYX of identity: (%.10g %.10g %.10g)", c->name, e[0], e[1], e[2]);
    assert_int_equal(c->to_euler(id, QO_EULER_ZXZ, 1, 0, e, &info), QO_OK);
    if (!info.locked || info.margin != 0.0 || e[2] != 0.0 || fabs(e[0]) > 1e-7 || e[1] != 0.0)
        fail_msg("%s ZXZ of identity: (%.10g %.10g %.10g) locked %d margin %.3g", c->name, e[0],
                 e[1], e[2], info.locked, info.margin);
}

/* ---- the shared edge table --------------------------------------------------------------
 * Quaternions given in double (non-unit allowed); each core takes the value it can hold
 * (2.0 saturates to INT32_MAX in Q1.30; 2^-30 is one LSB). Each entry is run for every
 * convention: status, ranges, the lock flag against the margin, recomposition against the
 * held input, plus the hand-derived angles where the entry states them. */
typedef struct edge {
    const char *what;
    dq q;
    qo_status want;
    int seq;              /* -1: all 24; else only this one (for known angles) */
    int want_locked;      /* -1: don't care */
    double a1, a2, a3;    /* checked when seq >= 0 */
} edge;

#define H 0.70710678118654752
#define LSB (1.0 / Q30)
#define QMAX (2147483647.0 / Q30)   /* INT32_MAX as Q1.30: 1.999999999 */
static const edge k_edges[] = {
    { "identity", { 1, 0, 0, 0 }, QO_OK, -1, -1, 0, 0, 0 },
    { "-identity", { -1, 0, 0, 0 }, QO_OK, -1, -1, 0, 0, 0 },
    { "identity ZYX", { 1, 0, 0, 0 }, QO_OK, QO_EULER_ZYX, 0, 0, 0, 0 },
    { "identity ZXZ (singular at 0)", { 1, 0, 0, 0 }, QO_OK, QO_EULER_ZXZ, 1, 0, 0, 0 },
    { "identity xyx (singular at 0)", { 1, 0, 0, 0 }, QO_OK, QO_EULER_xyx, 1, 0, 0, 0 },
    { "180 about x", { 0, 1, 0, 0 }, QO_OK, -1, -1, 0, 0, 0 },
    { "180 about y", { 0, 0, 1, 0 }, QO_OK, -1, -1, 0, 0, 0 },
    { "180 about z", { 0, 0, 0, -1 }, QO_OK, -1, -1, 0, 0, 0 },
    { "180 about (1,1,0)", { 0, H, H, 0 }, QO_OK, -1, -1, 0, 0, 0 },
    { "180 about (1,1,1)", { 0, 0.57735026918962576, 0.57735026918962576, 0.57735026918962576 },
      QO_OK, -1, -1, 0, 0, 0 },
    { "180 about x, ZXZ = (0, pi, 0) (singular at pi)", { 0, 1, 0, 0 }, QO_OK, QO_EULER_ZXZ, 1,
      0, PI, 0 },
    { "180 about z, XYZ = (0, 0, pi) (range end)", { 0, 0, 0, 1 }, QO_OK, QO_EULER_XYZ, 0,
      0, 0, PI },
    { "180 about x, XYZ = (pi, 0, 0) (range end)", { 0, 1, 0, 0 }, QO_OK, QO_EULER_XYZ, 0,
      PI, 0, 0 },
    { "ZYX pitch +90 (exactly singular)", { H, 0, H, 0 }, QO_OK, QO_EULER_ZYX, 1,
      0, PI / 2, 0 },
    { "ZYX pitch -90 (exactly singular)", { H, 0, -H, 0 }, QO_OK, QO_EULER_ZYX, 1,
      0, -PI / 2, 0 },
    { "zero", { 0, 0, 0, 0 }, QO_E_DEGENERATE, -1, -1, 0, 0, 0 },
    { "-0 / zero again", { -0.0, 0, -0.0, 0 }, QO_E_DEGENERATE, -1, -1, 0, 0, 0 },
    /* saturated components: INT32_MAX / INT32_MIN as Q1.30 (the float core holds 2.0) */
    { "saturated (MAX, 0, 0, MAX) = 90 about z", { QMAX, 0, 0, QMAX }, QO_OK, QO_EULER_ZYX, 0,
      PI / 2, 0, 0 },
    { "saturated (MIN, 0, 0, MIN) = 90 about z", { -2.0, 0, 0, -2.0 }, QO_OK, QO_EULER_ZYX, 0,
      PI / 2, 0, 0 },
    { "saturated (MIN, MIN, MIN, MIN)", { -2.0, -2.0, -2.0, -2.0 }, QO_OK, -1, -1, 0, 0, 0 },
    { "saturated (MAX, MIN, MAX, MIN)", { QMAX, -2.0, QMAX, -2.0 }, QO_OK, -1, -1, 0, 0, 0 },
    { "saturated (MIN, 0, 0, 0) = identity", { -2.0, 0, 0, 0 }, QO_OK, QO_EULER_XYZ, 0, 0, 0, 0 },
    { "saturated (MAX, 0, MAX, 0): XYZ pitch 90, singular", { QMAX, 0, QMAX, 0 }, QO_OK,
      QO_EULER_XYZ, 1, 0, PI / 2, 0 },
    { "one LSB (0, 0, 0, 1 LSB) = 180 about z", { 0, 0, 0, LSB }, QO_OK, QO_EULER_ZYX, 0,
      PI, 0, 0 },
    { "tiny (1 LSB, 0, 0, 1 LSB) = 90 about z", { LSB, 0, 0, LSB }, QO_OK, QO_EULER_ZYX, 0,
      PI / 2, 0, 0 },
    { "tiny random-ish (3, -1, 2, 5) LSB", { 3 * LSB, -LSB, 2 * LSB, 5 * LSB }, QO_OK, -1, -1,
      0, 0, 0 },
};

static void run_edge(const core *c, const edge *t, int seq)
{
    dq q = held(c, t->q);
    double e[3];
    einfo info;
    qo_status st = c->to_euler(q, seq, 1, 0, e, &info);
    if (st != t->want)
        fail_msg("%s edge '%s' %s: status %d, want %d", c->name, t->what, ref_euler_names[seq], (int)st,
                 (int)t->want);
    if (st != QO_OK) {
        if (e[0] != 0.0 || e[1] != 0.0 || e[2] != 0.0 || info.locked != 0 || info.margin != 0.0)
            fail_msg("%s edge '%s': error outputs not zero", c->name, t->what);
        return;
    }
    check_ranges(c, seq, e, t->what);
    if (info.locked != (info.margin <= c->band) || info.margin < 0.0 || info.margin > PI / 2 + 1e-6)
        fail_msg("%s edge '%s' %s: locked %d margin %.3g", c->name, t->what, ref_euler_names[seq],
                 info.locked, info.margin);
    if (recompose_err(seq, e, q) > (info.locked ? 2.0 * info.margin + c->tol_lock : c->tol_fine))
        fail_msg("%s edge '%s' %s: (%.10g %.10g %.10g) recomposes %.3g off", c->name, t->what,
                 ref_euler_names[seq], e[0], e[1], e[2], recompose_err(seq, e, q));
    if (t->seq >= 0) {
        if ((t->want_locked >= 0 && info.locked != t->want_locked) ||
            ang_diff(e[0], t->a1) > 1e-6 || fabs(e[1] - t->a2) > 1e-6 ||
            ang_diff(e[2], t->a3) > 1e-6 || (info.locked && e[2] != 0.0))
            fail_msg("%s edge '%s': (%.10g %.10g %.10g) locked %d, want (%.10g %.10g %.10g) "
                     "locked %d", c->name, t->what, e[0], e[1], e[2], info.locked, t->a1, t->a2,
                     t->a3, t->want_locked);
    }
}

static void test_edge_table(void **state)
{
    const core *c = *state;
    size_t i;
    int seq;
    for (i = 0; i < sizeof k_edges / sizeof k_edges[0]; i++) {
        if (k_edges[i].seq >= 0) run_edge(c, &k_edges[i], k_edges[i].seq);
        else for (seq = 0; seq < 24; seq++) run_edge(c, &k_edges[i], seq);
    }
}

/* ---- gimbal lock (float32, fixed, fixed fast) --------------------------------------------- */
static void test_exactly_singular_all24(void **state)
{
    const core *c = *state;
    int seq, which, n;
    rng.s = 99;
    for (seq = 0; seq < 24; seq++)
        for (which = 0; which < 2; which++)
            for (n = 0; n < 200; n++) {
                double a1 = ref_rng_range(&rng, -PI, PI), a3 = ref_rng_range(&rng, -PI, PI);
                double a2 = singular_value(seq, which), e[3], en[3], s[3], err;
                dq q = held(c, ref_quat_from_euler(ref_euler_names[seq], a1, a2, a3)), qs;
                einfo info, infon;
                /* 1. the exact rotation rounded to the core's components */
                assert_int_equal(c->to_euler(q, seq, 1, 0, e, &info), QO_OK);
                err = recompose_err(seq, e, q);
                if (!info.locked || e[2] != 0.0 || err > c->tol_lock || fabs(e[1] - a2) > 1e-5)
                    fail_msg("%s singular %s (%.10g %.10g %.10g): locked %d margin %.3g -> "
                             "(%.10g %.10g %.10g) recomposes %.3g off", c->name, ref_euler_names[seq],
                             a1, a2, a3, info.locked, info.margin, e[0], e[1], e[2], err);
                check_ranges(c, seq, e, "singular");
                /* -q: bit-identical angles and margin, also on the fitted (locked) path */
                assert_int_equal(c->to_euler(dq_neg(q), seq, 1, 0, en, &infon), QO_OK);
                if (en[0] != e[0] || en[1] != e[1] || en[2] != e[2] ||
                    infon.margin != info.margin || infon.locked != info.locked)
                    fail_msg("%s singular %s: -q gave (%.10g %.10g %.10g), q (%.10g %.10g "
                             "%.10g)", c->name, ref_euler_names[seq], en[0], en[1], en[2], e[0], e[1], e[2]);
                /* 2. built as a user would: the core's own from_euler with the value nearest
                 * the singular angle */
                s[0] = c->ra(a1); s[1] = c->ra(a2); s[2] = c->ra(a3);
                assert_int_equal(c->from_euler(seq, s, &qs), QO_OK);
                assert_int_equal(c->to_euler(qs, seq, 1, 0, e, &info), QO_OK);
                err = recompose_err(seq, e, ref_quat_from_euler(ref_euler_names[seq], s[0], a2, s[2]));
                if (!info.locked || e[2] != 0.0 || err > c->tol_lock)
                    fail_msg("%s singular via euler_to_quat %s (%.10g %.10g %.10g): locked %d "
                             "margin %.3g err %.3g", c->name, ref_euler_names[seq], s[0], s[1], s[2],
                             info.locked, info.margin, err);
                /* 3. then every component moved by up to 2 steps (noise from an upstream
                 * computation): still flagged */
                qs.w = c->nudge(qs.w, (int)(ref_rng_next(&rng) % 5) - 2);
                qs.x = c->nudge(qs.x, (int)(ref_rng_next(&rng) % 5) - 2);
                qs.y = c->nudge(qs.y, (int)(ref_rng_next(&rng) % 5) - 2);
                qs.z = c->nudge(qs.z, (int)(ref_rng_next(&rng) % 5) - 2);
                assert_int_equal(c->to_euler(qs, seq, 1, 0, e, &info), QO_OK);
                err = recompose_err(seq, e, qs);
                if (!info.locked || err > 2.0 * info.margin + c->tol_lock || err > c->tol_noise)
                    fail_msg("%s singular + 2 step noise %s q=(%.10g %.10g %.10g %.10g): "
                             "locked %d margin %.3g err %.3g", c->name, ref_euler_names[seq], qs.w,
                             qs.x, qs.y, qs.z, info.locked, info.margin, err);
                /* 4. the band form with band 0 still flags a margin of exactly 0 */
                assert_int_equal(c->to_euler(q, seq, 0, 0.0, e, &info), QO_OK);
                if (info.locked != (info.margin == 0.0))
                    fail_msg("%s band 0 %s: locked %d margin %.3g", c->name, ref_euler_names[seq],
                             info.locked, info.margin);
            }
}

/* Hand-derived free-angle choice (a3 = 0, a1 takes the rest):
 *   ZYX (y, +pi/2, r) = Rz(y) Ry(pi/2) Rx(r) = Rz(y - r) Ry(pi/2)  ->  (y - r, pi/2, 0)
 *   ZYX (y, -pi/2, r)                          = Rz(y + r) Ry(-pi/2) -> (y + r, -pi/2, 0)
 *   ZXZ (a, 0, c) -> (a + c, 0, 0);  ZXZ (a, pi, c) = Rz(a - c) Rx(pi) -> (a - c, pi, 0)
 *   zxz (a, pi, c) = Rz(c) Rx(pi) Rz(a) = Rz(c - a) Rx(pi) = Rx(pi) Rz(a - c) -> (a - c, pi, 0)
 * and two exactly representable singular quaternions: ZYX pitch 90 alone, 180 about x in ZXZ. */
static void test_singular_free_angle_choice(void **state)
{
    static const struct { int seq; double a1, a2, a3, w1; } k[] = {
        { QO_EULER_ZYX, 0.7, PI / 2, 0.2, 0.5 },
        { QO_EULER_ZYX, 0.7, -PI / 2, 0.2, 0.9 },
        { QO_EULER_ZXZ, 0.5, 0.0, 0.4, 0.9 },
        { QO_EULER_ZXZ, 0.5, PI, 0.4, 0.1 },
        { QO_EULER_zxz, 0.5, PI, 0.4, 0.1 },
        { QO_EULER_XYX, -2.5, 0.0, -1.0, -3.5 + 2 * PI },
    };
    const core *c = *state;
    const dq pitch90 = { sqrt(0.5), 0, sqrt(0.5), 0 }, x180 = { 0, 1, 0, 0 };
    double e[3];
    einfo info;
    size_t i;
    for (i = 0; i < sizeof k / sizeof k[0]; i++) {
        dq q = held(c, ref_quat_from_euler(ref_euler_names[k[i].seq], k[i].a1, k[i].a2, k[i].a3));
        assert_int_equal(c->to_euler(q, k[i].seq, 1, 0, e, &info), QO_OK);
        if (!info.locked || ang_diff(e[0], k[i].w1) > 2e-6 || fabs(e[1] - k[i].a2) > 1e-6 ||
            e[2] != 0.0)
            fail_msg("%s free angle %s (%g %g %g): got (%.10g %.10g %.10g) locked %d, want a1 "
                     "%.10g", c->name, ref_euler_names[k[i].seq], k[i].a1, k[i].a2, k[i].a3, e[0],
                     e[1], e[2], info.locked, k[i].w1);
    }
    assert_int_equal(c->to_euler(held(c, pitch90), QO_EULER_ZYX, 1, 0, e, &info), QO_OK);
    if (!info.locked || info.margin >= 1e-6 || fabs(e[1] - PI / 2) > 1e-6)
        fail_msg("%s ZYX pitch 90: (%.10g %.10g %.10g) locked %d margin %.3g", c->name, e[0],
                 e[1], e[2], info.locked, info.margin);
    assert_int_equal(c->to_euler(held(c, x180), QO_EULER_ZXZ, 1, 0, e, &info), QO_OK);
    if (!info.locked || info.margin != 0.0 || fabs(e[1] - PI) > 1e-6 ||
        recompose_err(QO_EULER_ZXZ, e, x180) >= 1e-6)
        fail_msg("%s ZXZ 180 about x: (%.10g %.10g %.10g) locked %d margin %.3g", c->name, e[0],
                 e[1], e[2], info.locked, info.margin);
}

static void test_just_off_singular_all24(void **state)
{
    static const double offs[] = { 1e-5, 1e-4, 1e-3, 0.01, 0.035 };
    const core *c = *state;
    /* offsets relative to the core's own band: a third of it (flagged) and 3x (not) */
    const double rel[2] = { c->band / 3.0, 3.0 * c->band };
    int seq, which, k, n, side;
    rng.s = 2024;
    for (seq = 0; seq < 24; seq++)
        for (which = 0; which < 2; which++)
            for (side = 0; side < 2; side++)
                for (n = 0; n < 20; n++) {
                    double a1 = ref_rng_range(&rng, -PI, PI), a3 = ref_rng_range(&rng, -PI, PI);
                    double s = singular_value(seq, which);
                    /* toward the inside of the range; past the end (side 1) is the other
                     * branch of a nearby rotation, equally valid input */
                    double inward = (s > 0.0) ? -1.0 : 1.0, e[3], err;
                    einfo info;
                    for (k = 0; k < 7; k++) {
                        double off = k < 5 ? offs[k] : rel[k - 5];
                        double a2 = s + (side ? -inward : inward) * off;
                        dq q = held(c, ref_quat_from_euler(ref_euler_names[seq], a1, a2, a3));
                        int want_locked = (k == 5);
                        assert_int_equal(c->to_euler(q, seq, 1, 0, e, &info), QO_OK);
                        err = recompose_err(seq, e, q);
                        if (info.locked != want_locked ||
                            err > (info.locked ? 2.0 * info.margin + c->tol_lock : c->tol_fine) ||
                            fabs(info.margin - off) > 1e-6 + 1e-4 * off)
                            fail_msg("%s %s (%.10g %.10g %.10g), %.3g off lock: locked %d margin "
                                     "%.6g, recomposes %.3g off", c->name, ref_euler_names[seq], a1, a2,
                                     a3, off, info.locked, info.margin, err);
                        check_ranges(c, seq, e, "near-singular");
                        /* A caller band of just under 2 deg (0.034907): flagged iff margin <=
                         * band, the forced a3 = 0 costs at most 2*margin, 0.035 rad never
                         * flagged. */
                        assert_int_equal(c->to_euler(q, seq, 0, 0.0349, e, &info), QO_OK);
                        err = recompose_err(seq, e, q);
                        if (info.locked != (info.margin <= c->ra(0.0349)) ||
                            (off > 0.0349 && info.locked) ||
                            err > (info.locked ? 2.0 * info.margin + c->tol_lock : c->tol_fine) ||
                            (info.locked && e[2] != 0.0))
                            fail_msg("%s band 0.0349 %s (%.10g %.10g %.10g): locked %d margin "
                                     "%.6g err %.3g", c->name, ref_euler_names[seq], a1, a2, a3,
                                     info.locked, info.margin, err);
                    }
                }
}

/* Range ends: every combination of a1, a3 in {-pi, -pi/2, 0, pi/2, pi} and a2 at the ends and
 * middle of its range (ends are singular): recomposes, stays in range, flagged iff singular. */
static void test_range_ends_all24(void **state)
{
    static const double e13[] = { -PI, -PI / 2, 0.0, PI / 2, PI };
    const core *c = *state;
    int seq, i1, i2, i3;
    for (seq = 0; seq < 24; seq++)
        for (i1 = 0; i1 < 5; i1++)
            for (i2 = 0; i2 < 3; i2++)
                for (i3 = 0; i3 < 5; i3++) {
                    double a2 = ref_euler_proper(seq) ? (i2 == 0 ? 0.0 : (i2 == 1 ? PI / 2 : PI))
                                                    : (i2 == 0 ? -PI / 2 : (i2 == 1 ? 0.0 : PI / 2));
                    dq q = held(c, ref_quat_from_euler(ref_euler_names[seq], e13[i1], a2, e13[i3]));
                    double e[3], err, bound;
                    einfo info;
                    assert_int_equal(c->to_euler(q, seq, 1, 0, e, &info), QO_OK);
                    err = recompose_err(seq, e, q);
                    bound = fmin(1e-5, info.locked ? 2.0 * info.margin + c->tol_lock : c->tol_fine);
                    check_ranges(c, seq, e, "range ends");
                    if (err > bound || info.locked != (i2 != 1))
                        fail_msg("%s range ends %s (%.10g %.10g %.10g) -> (%.10g %.10g %.10g) "
                                 "locked %d err %.3g", c->name, ref_euler_names[seq], e13[i1], a2, e13[i3],
                                 e[0], e[1], e[2], info.locked, err);
                }
}

/* ---- bad inputs (float32, fixed, fixed fast) ---------------------------------------------- */
/* The documented error: status `want`; the band form writes zeros and info { 0, 0 }, the
 * nearest form writes prev (as the core holds it) and locked 0; the default-band form, when
 * band is the default, gives the same status and zeros. */
static void expect_error(const core *c, dq q, int seq, double band, qo_status want, const char *what)
{
    double e[3], prev[3] = { 0.5, 0.25, -0.5 };
    einfo info;
    qo_status st = c->to_euler(q, seq, 0, band, e, &info);
    if (st != want || e[0] != 0.0 || e[1] != 0.0 || e[2] != 0.0 || info.locked != 0 ||
        info.margin != 0.0)
        fail_msg("%s %s: band status %d (want %d), out (%g %g %g) info {%d %g}", c->name, what,
                 (int)st, (int)want, e[0], e[1], e[2], info.locked, info.margin);
    st = c->near(q, seq, prev, band, e, &info);
    if (st != want || e[0] != c->ra(prev[0]) || e[1] != c->ra(prev[1]) ||
        e[2] != c->ra(prev[2]) || info.locked != 0)
        fail_msg("%s %s: near status %d (want %d), out (%g %g %g) is not prev", c->name, what,
                 (int)st, (int)want, e[0], e[1], e[2]);
    if (band == c->band) {
        st = c->to_euler(q, seq, 1, 0, e, NULL);
        if (st != want || e[0] != 0.0 || e[1] != 0.0 || e[2] != 0.0)
            fail_msg("%s %s: default status %d, out (%g %g %g)", c->name, what, (int)st, e[0],
                     e[1], e[2]);
    }
}

static void test_euler_from_quat_bad_inputs(void **state)
{
    const core *c = *state;
    const dq ok = { 0.9, 0.1, 0.2, 0.3 }, zero = { 0, 0, 0, 0 }, negzero = { -0.0, 0, -0.0, 0 };
    const double prev[3] = { 0, 0, 0 };
    double e[3];
    einfo info;
    expect_error(c, zero, QO_EULER_xyx, c->band, QO_E_DEGENERATE, "zero q");
    expect_error(c, negzero, QO_EULER_XYZ, c->band, QO_E_DEGENERATE, "-0 q");
    expect_error(c, ok, QO_EULER_SEQ_COUNT_, c->band, QO_E_ARG, "bad seq");
    expect_error(c, ok, -1, c->band, QO_E_ARG, "negative seq");
    expect_error(c, zero, 99, c->band, QO_E_ARG, "bad seq before zero q");
    expect_error(c, ok, QO_EULER_XYZ, -1e-3, QO_E_RANGE, "negative band");
    expect_error(c, ok, QO_EULER_XYZ, 1.6, QO_E_RANGE, "band > pi/2");
    expect_error(c, zero, QO_EULER_XYZ, 1.6, QO_E_DEGENERATE, "zero q before band");
    assert_int_equal(c->to_euler(ok, QO_EULER_XYZ, 1, 0, NULL, &info), QO_E_NULL);
    assert_int_equal(c->to_euler(ok, QO_EULER_XYZ, 0, 0.1, NULL, &info), QO_E_NULL);
    assert_int_equal(c->near(ok, QO_EULER_XYZ, prev, 0.1, NULL, &info), QO_E_NULL);
    /* Band limits themselves are accepted; pi/2 flags everything. */
    assert_int_equal(c->to_euler(held(c, ok), QO_EULER_XYZ, 0, 0.0, e, &info), QO_OK);
    assert_int_equal(info.locked, 0);
    assert_int_equal(c->to_euler(held(c, ok), QO_EULER_XYZ, 0, c->ra(PI / 2), e, &info), QO_OK);
    assert_int_equal(info.locked, 1);
    assert_true(recompose_err(QO_EULER_XYZ, e, held(c, ok)) <= 2.0 * info.margin + 1e-6);
}

/* ---- nearest solution (float32, fixed) ----------------------------------------------------- */

/* Follows a path of true joint angles through a singularity; the nearest decomposition must
 * track it (including outside scipy's ranges) without jumps. */
static void run_path(const core *c, int seq, double a1_0, double a1_1, double a2_0, double a2_1,
                     double a3_0, double a3_1, int steps, double band, double track_tol,
                     const char *what)
{
    double mid2 = 0.5 * (a2_0 + a2_1);
    int singular_mid = fabs(mid2 - PI / 2) < 1e-12 || fabs(mid2 + PI / 2) < 1e-12 ||
                       fabs(mid2) < 1e-12 || fabs(mid2 - PI) < 1e-12;
    double prev[3], out[3];
    einfo info;
    int k;
    prev[0] = c->ra(a1_0); prev[1] = c->ra(a2_0); prev[2] = c->ra(a3_0);
    for (k = 0; k <= steps; k++) {
        double t = (double)k / steps;
        double a1 = a1_0 + (a1_1 - a1_0) * t, a2 = a2_0 + (a2_1 - a2_0) * t;
        double a3 = a3_0 + (a3_1 - a3_0) * t, err, jump, dev;
        dq q;
        if (2 * k == steps) a2 = mid2; /* the midpoint exactly */
        q = held(c, ref_quat_from_euler(ref_euler_names[seq], a1, a2, a3));
        assert_int_equal(c->near(q, seq, prev, band, out, &info), QO_OK);
        err = recompose_err(seq, out, q);
        jump = dmax(fabs(out[0] - prev[0]), dmax(fabs(out[1] - prev[1]), fabs(out[2] - prev[2])));
        dev = dmax(fabs(out[0] - a1), dmax(fabs(out[1] - a2), fabs(out[2] - a3)));
        /* off lock: 2x the generic bound (float32: its outputs leave [-pi, pi], coarser spacing) */
        if (err > (info.locked ? 2.0 * info.margin + c->tol_lock : 2.0 * c->tol_fine) || jump > 0.06 ||
            dev > (info.margin > 0.03 ? track_tol : 0.06) || (info.locked && out[2] != prev[2]) ||
            (2 * k == steps && singular_mid && !info.locked))
            fail_msg("%s %s %s step %d: true (%.6f %.6f %.6f) got (%.6f %.6f %.6f) prev "
                     "(%.6f %.6f %.6f) locked %d margin %.3g err %.3g", c->name, what,
                     ref_euler_names[seq], k, a1, a2, a3, out[0], out[1], out[2], prev[0], prev[1],
                     prev[2], info.locked, info.margin, err);
        prev[0] = out[0]; prev[1] = out[1]; prev[2] = out[2];
    }
}

static void test_near_through_singularity_all24(void **state)
{
    const core *c = *state;
    int seq;
    for (seq = 0; seq < 24; seq++) {
        double s = ref_euler_proper(seq) ? 0.0 : PI / 2;
        /* a2 crosses the singular value (leaving scipy's range on the far side), a1 and a3 move
         * meanwhile; 100 steps of 0.004 rad in a2. Default band and a 0.01 rad hold band. */
        run_path(c, seq, 0.3, 1.1, s - 0.2, s + 0.2, -0.5, 0.1, 100, c->band, 1e-4,
                 "through lock (default band)");
        run_path(c, seq, 0.3, 1.1, s + 0.2, s - 0.2, -0.5, 0.1, 100, 0.01, 1e-4,
                 "through lock (0.01 band)");
        if (ref_euler_proper(seq))
            run_path(c, seq, -2.0, -1.0, PI - 0.2, PI + 0.2, 2.0, 2.5, 100, 0.01, 1e-4,
                     "through pi");
        else
            run_path(c, seq, -2.0, -1.0, -s + 0.2, -s - 0.2, 2.0, 2.5, 100, 0.01, 1e-4,
                     "through -pi/2");
    }
}

static void test_near_across_wrap_and_turns(void **state)
{
    const core *c = *state;
    int seq;
    for (seq = 0; seq < 24; seq++) {
        double mid = ref_euler_proper(seq) ? 1.0 : 0.3;
        /* a1 crosses +pi, a3 crosses -pi: no 2pi jumps. */
        run_path(c, seq, 3.0, 3.4, mid, mid + 0.1, -3.0, -3.4, 40, c->band, 1e-4, "across wrap");
        /* Counting past pi, up to 4.8 rad (Q3.28 holds 8 - pi of headroom; longer runs of the
         * fixed core are test_fx_near_range_end). */
        run_path(c, seq, -4.8, 4.8, mid, mid, 0.5, -0.5, 200, c->band, 1e-4, "turns");
        /* Several turns of the first joint where the angle type holds them: keeps counting. */
        if (c->a_max > 20.0)
            run_path(c, seq, 0.0, 20.0, mid, mid, 0.5, -0.5, 400, c->band, 1e-4, "turns to 20 rad");
    }
}

static void test_near_picks_branch_and_locks(void **state)
{
    const core *c = *state;
    int seq;
    rng.s = 555;
    for (seq = 0; seq < 24; seq++) {
        double a1 = ref_rng_range(&rng, -2.5, 2.5), a3 = ref_rng_range(&rng, -2.5, 2.5);
        double a2 = ref_euler_proper(seq) ? 1.2 : 0.6;
        double alt2 = ref_euler_proper(seq) ? -a2 : PI - a2;
        dq q = held(c, ref_quat_from_euler(ref_euler_names[seq], a1, a2, a3));
        double prev[3], out[3];
        einfo info;
        /* prev near the alternative branch, one turn down on a1 (stays inside Q3.28) */
        prev[0] = a1 + PI - 2 * PI + 0.05; prev[1] = alt2 - 0.05; prev[2] = a3 + PI - 0.05;
        assert_int_equal(c->near(q, seq, prev, 0.0, out, &info), QO_OK);
        if (fabs(out[0] - (a1 - PI)) > 1e-5 || fabs(out[1] - alt2) > 1e-5 ||
            fabs(out[2] - (a3 + PI)) > 1e-5 || recompose_err(seq, out, q) > 1e-5)
            fail_msg("%s near %s alt branch: got (%.7f %.7f %.7f) want (%.7f %.7f %.7f)",
                     c->name, ref_euler_names[seq], out[0], out[1], out[2], a1 - PI, alt2, a3 + PI);
        /* prev near the alternative branch two turns up on a1, where the angle type holds it */
        if (c->a_max > 20.0) {
            prev[0] = a1 + PI + 4 * PI + 0.05; prev[1] = alt2 - 0.05; prev[2] = a3 + PI - 0.05;
            assert_int_equal(c->near(q, seq, prev, 0.0, out, &info), QO_OK);
            if (fabs(out[0] - (a1 + 5 * PI)) > 1e-5 || fabs(out[1] - alt2) > 1e-5 ||
                fabs(out[2] - (a3 + PI)) > 1e-5 || recompose_err(seq, out, q) > 1e-5)
                fail_msg("%s near %s alt branch 2 turns up: got (%.7f %.7f %.7f) want (%.7f %.7f "
                         "%.7f)", c->name, ref_euler_names[seq], out[0], out[1], out[2], a1 + 5 * PI,
                         alt2, a3 + PI);
        }
        /* prev near the principal branch */
        prev[0] = a1 - 0.1; prev[1] = a2 + 0.1; prev[2] = a3 + 0.1;
        assert_int_equal(c->near(q, seq, prev, 0.0, out, &info), QO_OK);
        if (fabs(out[0] - a1) > 1e-5 || fabs(out[1] - a2) > 1e-5 || fabs(out[2] - a3) > 1e-5)
            fail_msg("%s near %s principal: got (%.7f %.7f %.7f)", c->name, ref_euler_names[seq],
                     out[0], out[1], out[2]);
        /* Exactly singular: a3 stays at prev.a3 exactly and the result composes to q. */
        q = held(c, ref_quat_from_euler(ref_euler_names[seq], a1, singular_value(seq, 1), a3));
        prev[0] = 0.25; prev[1] = singular_value(seq, 1); prev[2] = 7.5;
        assert_int_equal(c->near(q, seq, prev, c->band, out, &info), QO_OK);
        if (!info.locked || out[2] != c->ra(7.5) || recompose_err(seq, out, q) > 1e-5 ||
            fabs(out[0] - 0.25) > PI)
            fail_msg("%s near %s at lock: locked %d got (%.7f %.7f %.7f) err %.3g", c->name,
                     ref_euler_names[seq], info.locked, out[0], out[1], out[2], recompose_err(seq, out, q));
    }
}

/* ---- float32 only: NaN, Inf, subnormal and huge components --------------------------------- */
static void test_f32_euler_to_quat_nan(void **state)
{
    const core *c = &CORE_F32;
    int i;
    (void)state;
    for (i = 0; i < 3; i++) {
        double a[3] = { 0.1, 0.2, 0.3 };
        dq q;
        a[i] = NAN;
        if (c->from_euler(QO_EULER_ZXZ, a, &q) != QO_E_NONFINITE)
            fail_msg("float32 euler_to_quat accepted a NaN angle %d", i);
        assert_true(q.w == 1.0 && q.x == 0.0 && q.y == 0.0 && q.z == 0.0);
    }
}

/* A non-unit input is normalised: 1e-20 and 1e20 times the yaw quaternion; subnormal and
 * near-FLT_MAX components are scaled, not rejected, not overflowing; a tiny but not yet
 * subnormal singular input is still flagged (the margin is a ratio). */
static void test_f32_euler_from_quat_scaled_inputs(void **state)
{
    static const struct { const char *what; dq q; int seq; double a1, a2, tol; int locked; } k[] = {
        { "yaw 90 x 1e-20", { 0.70710678118655e-20, 0, 0, 0.70710678118655e-20 }, QO_EULER_ZYX,
          PI / 2, 0, 1e-6, 0 },
        { "yaw 90 x 1e20", { 0.70710678118655e20, 0, 0, 0.70710678118655e20 }, QO_EULER_ZYX,
          PI / 2, 0, 1e-6, 0 },
        { "subnormal yaw 90", { 1e-40, 0, 0, 1e-40 }, QO_EULER_ZYX, PI / 2, 0, 1e-5, 0 },
        { "3e38: 90 about x", { 3e38, 3e38, 0, 0 }, QO_EULER_XYZ, PI / 2, 0, 1e-6, 0 },
        { "pitch 90 x 1e-30", { 0.70710678118655e-30, 0, 0.70710678118655e-30, 0 }, QO_EULER_ZYX,
          0, PI / 2, 1e-6, 1 },
    };
    const core *c = &CORE_F32;
    size_t i;
    (void)state;
    for (i = 0; i < sizeof k / sizeof k[0]; i++) {
        double e[3];
        einfo info;
        assert_int_equal(c->to_euler(k[i].q, k[i].seq, 1, 0, e, &info), QO_OK);
        if ((!k[i].locked && fabs(e[0] - k[i].a1) > k[i].tol) || fabs(e[1] - k[i].a2) > k[i].tol ||
            (!k[i].locked && fabs(e[2]) > 1e-6) || info.locked != k[i].locked)
            fail_msg("float32 %s: (%.9g %.9g %.9g) locked %d", k[i].what, e[0], e[1], e[2],
                     info.locked);
        assert_int_equal(c->to_euler(k[i].q, k[i].seq, 1, 0, e, NULL), QO_OK);
        if (!k[i].locked && fabs(e[0] - k[i].a1) > k[i].tol)
            fail_msg("float32 %s without info: a1 %.9g", k[i].what, e[0]);
    }
}

/* Non-finite components, band and prev: QO_E_NONFINITE with the documented outputs. */
static void test_f32_euler_from_quat_nonfinite(void **state)
{
    const core *c = &CORE_F32;
    const dq ok = { 0.9, 0.1, 0.2, 0.3 };
    int i;
    (void)state;
    for (i = 0; i < 8; i++) {
        dq q = ok;
        switch (i) {
        case 0: q.w = NAN; break;
        case 1: q.x = INFINITY; break;
        case 2: q.y = -INFINITY; break;
        case 3: q.z = NAN; break;
        case 4: q.w = NAN; q.x = NAN; q.y = NAN; q.z = NAN; break;
        case 5: q.x = 3e38; q.y = INFINITY; break;
        case 6: q.w = -NAN; break;
        default: q.z = -INFINITY; break;
        }
        expect_error(c, q, QO_EULER_ZYX, c->band, QO_E_NONFINITE, "non-finite q");
    }
    expect_error(c, ok, QO_EULER_XYZ, NAN, QO_E_NONFINITE, "NaN band");
    expect_error(c, ok, QO_EULER_XYZ, INFINITY, QO_E_NONFINITE, "Inf band");
    /* A non-finite prev: zeros, not a copy of the NaN. */
    for (i = 0; i < 3; i++) {
        double prev[3] = { 0, 0, 0 }, e[3] = { 9, 9, 9 };
        einfo info;
        prev[i] = i == 0 ? NAN : (i == 1 ? INFINITY : -INFINITY);
        assert_int_equal(c->near(ok, QO_EULER_XYZ, prev, 0.1, e, &info), QO_E_NONFINITE);
        assert_true(e[0] == 0.0 && e[1] == 0.0 && e[2] == 0.0 && info.locked == 0);
    }
}

/* ---- fixed only: raw int32 inputs, the Q3.28 range end, band limits in LSB ----------------- */

/* Q3.28 ends at +-8 rad: the nearest solution past it comes back one turn nearer zero with
 * QO_E_OVERFLOW, still a valid decomposition. Inside the range: QO_OK even at 7.99 rad. */
static void test_fx_near_range_end(void **state)
{
    int seq;
    (void)state;
    for (seq = 0; seq < 24; seq++) {
        double mid = ref_euler_proper(seq) ? 1.0 : 0.3, prev[3], out[3];
        einfo info;
        /* true a1 = 8.2 rad (= 8.2 - 2pi = 1.917 in range), prev at 7.9 */
        dq q = held(&CORE_FX, ref_quat_from_euler(ref_euler_names[seq], 8.2, mid, -0.4));
        qo_status st;
        prev[0] = 7.9; prev[1] = mid; prev[2] = -0.4;
        st = x_near(q, seq, prev, CORE_FX.band, out, &info);
        if (st != QO_E_OVERFLOW || fabs(out[0] - (8.2 - 2 * PI)) > 1e-6 ||
            fabs(out[1] - mid) > 1e-6 || fabs(out[2] + 0.4) > 1e-6 || info.locked ||
            recompose_err(seq, out, q) > 1e-6)
            fail_msg("fixed near %s past 8 rad: status %d out (%.9f %.9f %.9f)", ref_euler_names[seq],
                     (int)st, out[0], out[1], out[2]);
        /* true a3 = -7.95 rad: fits, QO_OK, counted turn kept */
        q = held(&CORE_FX, ref_quat_from_euler(ref_euler_names[seq], 0.2, mid, -7.95));
        prev[0] = 0.2; prev[1] = mid; prev[2] = -7.9;
        st = x_near(q, seq, prev, CORE_FX.band, out, &info);
        if (st != QO_OK || fabs(out[2] + 7.95) > 1e-6 || recompose_err(seq, out, q) > 1e-6)
            fail_msg("fixed near %s at -7.95 rad: status %d out (%.9f %.9f %.9f)", ref_euler_names[seq],
                     (int)st, out[0], out[1], out[2]);
    }
}

/* Every int32 angle is a valid from_euler input; INT32_MIN/MAX angles against double. */
static void test_fx_euler_to_quat_extreme_angles(void **state)
{
    static const int32_t v[] = { INT32_MIN, INT32_MIN + 1, -1, 0, 1, INT32_MAX - 1, INT32_MAX,
                                 843314857 /* pi */, -843314857, 421657428 /* pi/2 */ };
    size_t i, j;
    int seq;
    (void)state;
    for (seq = 0; seq < 24; seq += 5)
        for (i = 0; i < sizeof v / sizeof v[0]; i++)
            for (j = 0; j < sizeof v / sizeof v[0]; j++) {
                qo_euler_q28 e;
                qo_quat_q30 q;
                dq r;
                double err;
                e.a1 = v[i]; e.a2 = v[j]; e.a3 = v[(i + j) % (sizeof v / sizeof v[0])];
                assert_int_equal(qo_euler_to_quat_q30((qo_euler_seq)seq, e, &q), QO_OK);
                r = ref_quat_from_euler(ref_euler_names[seq], e.a1 / Q28, e.a2 / Q28, e.a3 / Q28);
                err = fmax(fmax(fabs(q.w / Q30 - r.w), fabs(q.x / Q30 - r.x)),
                           fmax(fabs(q.y / Q30 - r.y), fabs(q.z / Q30 - r.z)));
                if (err > 1e-8)
                    fail_msg("fixed euler_to_quat %s raw (%d %d %d): error %.3g", ref_euler_names[seq],
                             (int)e.a1, (int)e.a2, (int)e.a3, err);
            }
}

/* Raw int32 quaternions of every size (full range down to a few LSB, non-unit, saturated)
 * and prev anywhere in Q3.28: no overflow (UBSan watches every int64 step), outputs in range,
 * recomposition at the fixed core's precision, the near variant's status OK or OVERFLOW only
 * when an output had to be taken one turn back (then it still composes to q). */
static void test_fx_random_raw_inputs(void **state)
{
    static const core *const k_cores[2] = { &CORE_FX, &CORE_FX_FAST };
    int seq, n;
    (void)state;
    rng.s = 0xF1C5EDull;
    for (seq = 0; seq < 24; seq++)
        for (n = 0; n < 400; n++) {
            qo_quat_q30 q;
            qo_euler_q28 e, prev, o;
            qo_euler_info_q28 info;
            qo_status st;
            unsigned sh = (unsigned)(ref_rng_next(&rng) % 31);
            int k;
            double ee[3], oo[3], tol;
            dq r;
            q.w = (int32_t)(uint32_t)ref_rng_next(&rng) >> sh; q.x = (int32_t)(uint32_t)ref_rng_next(&rng) >> sh;
            q.y = (int32_t)(uint32_t)ref_rng_next(&rng) >> sh; q.z = (int32_t)(uint32_t)ref_rng_next(&rng) >> sh;
            if (n % 50 == 0) q.w = INT32_MIN;
            if (n % 50 == 1) q.x = INT32_MAX;
            if (q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0) q.z = 1;
            r.w = q.w; r.x = q.x; r.y = q.y; r.z = q.z;
            /* the exact function and the fast tier (which rescales the same way), one bound */
            for (k = 1; k <= 2; k++) {
                st = k == 1 ? qo_euler_from_quat_q30(q, (qo_euler_seq)seq, &e, &info)
                            : qo_euler_from_quat_fast_q30(q, (qo_euler_seq)seq, QO_EULER_LOCK_BAND_Q28,
                                                        &e, &info);
                ee[0] = e.a1 / Q28; ee[1] = e.a2 / Q28; ee[2] = e.a3 / Q28;
                /* a few-LSB quaternion is still exact input; components >= 1.0 lose 1 bit */
                tol = info.locked ? 2.0 * info.margin / Q28 + 5e-8 : 5e-8;
                if (st != QO_OK || recompose_err(seq, ee, r) > tol)
                    fail_msg("%s raw %s q=(%d %d %d %d): status %d (%.10g %.10g %.10g) err %.3g",
                             k_cores[k - 1]->name, ref_euler_names[seq], (int)q.w, (int)q.x, (int)q.y, (int)q.z,
                             (int)st, ee[0], ee[1], ee[2], recompose_err(seq, ee, r));
                check_ranges(k_cores[k - 1], seq, ee, "raw");
            }
            prev.a1 = (int32_t)(uint32_t)ref_rng_next(&rng); prev.a2 = (int32_t)(uint32_t)ref_rng_next(&rng);
            prev.a3 = (int32_t)(uint32_t)ref_rng_next(&rng);
            st = qo_euler_from_quat_near_q30(q, (qo_euler_seq)seq, prev,
                                           (qo_q28)(ref_rng_next(&rng) % 1000), &o, &info);
            oo[0] = o.a1 / Q28; oo[1] = o.a2 / Q28; oo[2] = o.a3 / Q28;
            tol = info.locked ? 2.0 * info.margin / Q28 + 5e-8 : 5e-8;
            if ((st != QO_OK && st != QO_E_OVERFLOW) || recompose_err(seq, oo, r) > tol ||
                (info.locked && o.a3 != prev.a3))
                fail_msg("fixed raw near %s q=(%d %d %d %d) prev (%d %d %d): status %d "
                         "(%.10g %.10g %.10g) err %.3g", ref_euler_names[seq], (int)q.w, (int)q.x,
                         (int)q.y, (int)q.z, (int)prev.a1, (int)prev.a2, (int)prev.a3, (int)st,
                         oo[0], oo[1], oo[2], recompose_err(seq, oo, r));
            /* OVERFLOW only if some output is more than pi from its prev (taken back a turn) */
            if (st == QO_E_OVERFLOW && fabs(oo[0] - prev.a1 / Q28) <= PI + 1e-6 &&
                fabs(oo[1] - prev.a2 / Q28) <= PI + 1e-6 && fabs(oo[2] - prev.a3 / Q28) <= PI + 1e-6)
                fail_msg("fixed raw near %s: OVERFLOW but every output is within pi of prev",
                         ref_euler_names[seq]);
            if (st == QO_OK && (fabs(oo[0] - prev.a1 / Q28) > PI + 1e-6 ||
                                fabs(oo[2] - prev.a3 / Q28) > PI + 1e-6))
                fail_msg("fixed raw near %s: OK but an output is more than pi from prev "
                         "(%.10g %.10g %.10g) prev (%.10g %.10g %.10g)", ref_euler_names[seq], oo[0],
                         oo[1], oo[2], prev.a1 / Q28, prev.a2 / Q28, prev.a3 / Q28);
        }
}

/* The band one LSB past QO_Q28_HALF_PI and INT32_MIN: QO_E_RANGE, zeros / prev. */
static void test_fx_band_limits(void **state)
{
    const qo_quat_q30 q = { QO_Q30_ONE, 0, 0, 0 };
    qo_euler_q28 prev = { 3, 0, 0 }, e = { 9, 9, 9 };
    qo_euler_info_q28 info;
    (void)state;
    assert_int_equal(qo_euler_from_quat_band_q30(q, QO_EULER_XYZ, QO_Q28_HALF_PI + 1, &e, &info),
                     QO_E_RANGE);
    assert_true(e.a1 == 0 && e.a2 == 0 && e.a3 == 0 && info.locked == 0 && info.margin == 0);
    assert_int_equal(qo_euler_from_quat_near_q30(q, QO_EULER_XYZ, prev, INT32_MIN, &e, &info),
                     QO_E_RANGE);
    assert_true(e.a1 == 3 && e.a2 == 0 && e.a3 == 0);
}

/* One cmocka line per core (BOTH, ALL3: common/cores.h), so that a failure names the core;
 * quaternion -> angles runs on the fast tier too (ALL3). */
int main(void)
{
    const struct CMUnitTest tests[] = {
        /* sequence names */
        cmocka_unit_test(test_seq_parse_and_name),
        cmocka_unit_test(test_seq_parse_rejects),
        /* shared bodies */
        BOTH(test_euler_to_quat_random_all24),
        BOTH(test_euler_to_quat_known_values),
        BOTH(test_euler_to_quat_bad_inputs),
        ALL3(test_euler_from_quat_random_rotations_all24),
        ALL3(test_euler_from_quat_recovers_angles_all24),
        ALL3(test_euler_from_quat_known_values),
        ALL3(test_edge_table),
        ALL3(test_exactly_singular_all24),
        ALL3(test_singular_free_angle_choice),
        ALL3(test_just_off_singular_all24),
        ALL3(test_range_ends_all24),
        ALL3(test_euler_from_quat_bad_inputs),
        BOTH(test_near_through_singularity_all24),
        BOTH(test_near_across_wrap_and_turns),
        BOTH(test_near_picks_branch_and_locks),
        /* float32 only */
        cmocka_unit_test(test_f32_euler_to_quat_nan),
        cmocka_unit_test(test_f32_euler_from_quat_scaled_inputs),
        cmocka_unit_test(test_f32_euler_from_quat_nonfinite),
        /* fixed only */
        cmocka_unit_test(test_fx_near_range_end),
        cmocka_unit_test(test_fx_euler_to_quat_extreme_angles),
        cmocka_unit_test(test_fx_random_raw_inputs),
        cmocka_unit_test(test_fx_band_limits),
    };
    return cmocka_run_group_tests_name("euler (float32, fixed, fixed fast)", tests, NULL, NULL);
}
