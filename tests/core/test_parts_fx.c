/* The two forms of the fixed core's fast paths give the same bits. lib/src/quat_fx.c takes its
 * ARMv6-M form (16-bit partial products, no 64-bit multiply; QO_FX_NARROW_MUL) only when built
 * for Cortex-M0/M0+ and plain int64 sums elsewhere. Here it is compiled a second time with
 * QO_FX_MUL_PARTS (the ARMv6-M form on this host), its public names renamed to parts_*, and
 * both copies are run on the same inputs (mul, mul_checked, rotate, normalize and
 * normalize_fast): random unit and non-unit quaternions, every
 * component at the fast-range limit (+-1.25) and its neighbours, and the int32 extremes (the
 * general path). Any difference is a bug in one form. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "common/ref.h"

#define QO_FX_MUL_PARTS 1
#define qo_quat_identity_q30 parts_quat_identity_q30
#define qo_quat_mul_q30 parts_quat_mul_q30
#define qo_quat_mul_checked_q30 parts_quat_mul_q30_checked
#define qo_quat_conj_q30 parts_quat_conj_q30
#define qo_quat_inverse_q30 parts_quat_inverse_q30
#define qo_quat_dot_q30 parts_quat_dot_q30
#define qo_quat_norm_q30 parts_quat_norm_q30
#define qo_quat_normalize_q30 parts_quat_normalize_q30
#define qo_quat_normalize_fast_q30 parts_quat_normalize_fast_q30
#define qo_quat_canonical_q30 parts_quat_canonical_q30
#define qo_quat_rotate_q30 parts_quat_rotate_q30
#define qo_quat_angle_between_q30 parts_quat_angle_between_q30
#define qo_fx_quat_from_rotvec parts_fx_quat_from_rotvec
#define qo_quat_exp_q30 parts_quat_exp_q30
#define qo_quat_log_q30 parts_quat_log_q30
#define qo_quat_integrate_q30 parts_quat_integrate_q30
#include "../lib/src/quat_fx.c"
#undef qo_quat_mul_q30
#undef qo_quat_mul_checked_q30
#undef qo_quat_normalize_q30
#undef qo_quat_normalize_fast_q30
#undef qo_quat_rotate_q30

/* The library's own (native) definitions; quat_fx.h was read above under the parts_ names. */
qo_quat_q30 qo_quat_mul_q30(qo_quat_q30 a, qo_quat_q30 b);
qo_status qo_quat_mul_checked_q30(qo_quat_q30 a, qo_quat_q30 b, qo_quat_q30 *out);
qo_status qo_quat_normalize_q30(qo_quat_q30 q, qo_quat_q30 *out);
qo_status qo_quat_normalize_fast_q30(qo_quat_q30 q, qo_quat_q30 *out);
qo_vec3_q30 qo_quat_rotate_q30(qo_quat_q30 q, qo_vec3_q30 v);

static ref_rng rng;
static uint64_t rnd(void) { return ref_rng_next(&rng); }

/* A component: mostly within the fast range, sometimes at its limit +-(1.25 * 2^30 + {-1, 0,
 * 1}), sometimes any int32 (INT32_MIN and INT32_MAX included). */
static int32_t comp(void)
{
    static const int32_t e[] = { 0x50000000, 0x50000000 - 1, 0x50000000 + 1, -0x50000000,
                                 -0x50000000 + 1, -0x50000000 - 1, INT32_MIN, INT32_MAX, 0, 1,
                                 -1, 1 << 30, -(1 << 30) };
    uint64_t r = rnd();
    switch (r % 8u) {
    case 0: return e[(r >> 8) % (sizeof e / sizeof e[0])];
    case 1: return (int32_t)(uint32_t)(r >> 32);
    default: /* within +-1.25 * 2^30, of random magnitude */
        return (int32_t)(((int64_t)(int32_t)(uint32_t)(r >> 32) * 5 / 4) >> (1u + (r >> 8) % 4u));
    }
}

static qo_quat_q30 quat(void)
{
    qo_quat_q30 q;
    q.w = comp(); q.x = comp(); q.y = comp(); q.z = comp();
    return q;
}

static int same_q(qo_quat_q30 a, qo_quat_q30 b)
{
    return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z;
}

static void test_parts_equal_native(void **state)
{
    long i;
    (void)state;
    rng.s = 0x5EED0017u;
    for (i = 0; i < 300000; i++) {
        qo_quat_q30 a = quat(), b = quat(), r1, r2;
        qo_vec3_q30 v = { comp(), comp(), comp() }, v1, v2;
        qo_status s1, s2;
        r1 = qo_quat_mul_q30(a, b);
        r2 = parts_quat_mul_q30(a, b);
        if (!same_q(r1, r2))
            fail_msg("mul (%ld %ld %ld %ld)(%ld %ld %ld %ld) native != parts", (long)a.w,
                     (long)a.x, (long)a.y, (long)a.z, (long)b.w, (long)b.x, (long)b.y, (long)b.z);
        s1 = qo_quat_mul_checked_q30(a, b, &r1);
        s2 = parts_quat_mul_q30_checked(a, b, &r2);
        if (s1 != s2 || !same_q(r1, r2)) fail_msg("mul_checked differs at case %ld", i);
        v1 = qo_quat_rotate_q30(a, v);
        v2 = parts_quat_rotate_q30(a, v);
        if (v1.x != v2.x || v1.y != v2.y || v1.z != v2.z)
            fail_msg("rotate (%ld %ld %ld %ld) by (%ld %ld %ld) native != parts", (long)a.w,
                     (long)a.x, (long)a.y, (long)a.z, (long)v.x, (long)v.y, (long)v.z);
        s1 = qo_quat_normalize_q30(a, &r1);
        s2 = parts_quat_normalize_q30(a, &r2);
        if (s1 != s2 || !same_q(r1, r2)) fail_msg("normalize differs at case %ld", i);
        s1 = qo_quat_normalize_fast_q30(a, &r1);
        s2 = parts_quat_normalize_fast_q30(a, &r2);
        if (s1 != s2 || !same_q(r1, r2)) fail_msg("normalize_fast differs at case %ld", i);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parts_equal_native),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
