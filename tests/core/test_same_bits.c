/*
 * The same bits on every target: a fixed set of inputs (built from integers only, so the inputs
 * themselves do not depend on any libm) goes through every float32 function that uses a
 * transcendental kernel - qorient/fmath.h itself, quat exp/log/angle/integrate, every
 * conversion, all 24 Euler conventions both ways, slerp, nlerp, squad, Bezier - and an FNV-1a
 * digest of each output's bits (and status) is compared with the committed table
 * tests/common/same_bits.h. The table was made on x86-64; the test runs unchanged on aarch64
 * and armhf (qemu-user, make test-qemu) and bare metal on Cortex-M0/M4F/M7 (core test), so a
 * difference of one ulp anywhere on any target fails here with the function and the case.
 *
 * Regenerate the table after an intended change of results:
 *   QORIENT_SAME_BITS_PRINT=1 build/tests/test_same_bits | sed -n '/same_bits.h:/,/^};/p' \
 *       > tests/common/same_bits.h
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "qorient/convert.h"
#include "qorient/euler.h"
#include "qorient/fmath.h"
#include "qorient/interp.h"
#include "qorient/quat.h"

#define N_CASES 48
enum { F_KERNELS, F_QUAT, F_CONVERT, F_EULER, F_INTERP, F_COUNT };
static const char *const family[F_COUNT] = { "fmath", "quat", "convert", "euler", "interp" };

/* the committed digests: same_bits_expected[family][case] */
#include "common/same_bits.h"

static uint32_t digest[F_COUNT][N_CASES];

static void mix_u32(uint32_t *h, uint32_t v)
{
    int i;
    for (i = 0; i < 4; i++) {
        *h ^= (v >> (8 * i)) & 0xffu;
        *h *= 16777619u;
    }
}

static void mix_f(uint32_t *h, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    mix_u32(h, u);
}

static void mix_q(uint32_t *h, qo_quat_f32 q)
{
    mix_f(h, q.w); mix_f(h, q.x); mix_f(h, q.y); mix_f(h, q.z);
}

/* splitmix64 on integers only: deterministic everywhere */
static uint64_t next(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

/* a float in [-scale, scale) from 24 random bits: exact conversion, no libm */
static float unit_f(uint64_t *s, float scale)
{
    int32_t i = (int32_t)(next(s) >> 40) - 8388608;
    return (float)i * (scale / 8388608.0f);
}

static qo_quat_f32 rand_q(uint64_t *s)
{
    qo_quat_f32 q;
    q.w = unit_f(s, 1.0f); q.x = unit_f(s, 1.0f); q.y = unit_f(s, 1.0f); q.z = unit_f(s, 1.0f);
    return q;
}

static void run_case(int c)
{
    uint64_t s = 0x51DEB175ULL + (uint64_t)c;
    uint32_t *h;
    qo_quat_f32 a = rand_q(&s), b = rand_q(&s), q0, q1, q2, q3, r, keys[4], ctl[4];
    qo_vec3_f32 v, ax, v1;
    qo_mat3_f32 m;
    qo_euler_f32 e;
    qo_euler_info_f32 info;
    float ang, x = unit_f(&s, 8.0f), y = unit_f(&s, 8.0f), big = unit_f(&s, 1e30f);
    int k, seq;
    qo_fm_sincos_f32_t sc;
    /* some cases on the edges: identical, antipodal, near-lock, a quarter turn */
    if (c == 1) b = a;
    if (c == 2) { b.w = -a.w; b.x = -a.x; b.y = -a.y; b.z = -a.z; }
    if (c == 3) { a.w = 0.70710677f; a.x = 0.0f; a.y = 0.70710677f; a.z = 0.0f; }
    if (c == 4) { a.w = 1.0f; a.x = 1e-7f; a.y = 0.0f; a.z = 0.0f; }

    h = &digest[F_KERNELS][c];
    *h = 2166136261u;
    sc = qo_fm_sincos_f32(x); mix_f(h, sc.s); mix_f(h, sc.c);
    sc = qo_fm_sincos_f32(big); mix_f(h, sc.s); mix_f(h, sc.c);
    mix_f(h, qo_fm_atan2_f32(y, x)); mix_f(h, qo_fm_atan2_f32(x, -y));
    mix_f(h, qo_fm_asin_f32(a.w)); mix_f(h, qo_fm_acos_f32(a.x));
    mix_f(h, qo_fm_exp_f32(x)); mix_f(h, qo_fm_log_f32(fabsf(y) + 1e-30f));

    h = &digest[F_QUAT][c];
    *h = 2166136261u;
    mix_u32(h, (uint32_t)qo_quat_normalize_f32(a, &q0)); mix_q(h, q0);
    mix_q(h, qo_quat_mul_f32(a, b));
    v.x = x; v.y = y; v.z = unit_f(&s, 4.0f);
    r = q0;
    mix_f(h, qo_quat_rotate_f32(r, v).x); mix_f(h, qo_quat_rotate_f32(r, v).y);
    mix_f(h, qo_quat_angle_between_f32(a, b));
    v1.x = a.x; v1.y = a.y; v1.z = a.z;
    mix_u32(h, (uint32_t)qo_quat_exp_f32(v1, &q1)); mix_q(h, q1);
    mix_u32(h, (uint32_t)qo_quat_log_f32(a, &v1)); mix_f(h, v1.x); mix_f(h, v1.y); mix_f(h, v1.z);
    mix_u32(h, (uint32_t)qo_quat_integrate_f32(a, v, 0.01f * x, &q1)); mix_q(h, q1);

    h = &digest[F_CONVERT][c];
    *h = 2166136261u;
    mix_u32(h, (uint32_t)qo_quat_to_mat3_f32(a, &m));
    for (k = 0; k < 9; k++) mix_f(h, m.m[k / 3][k % 3]);
    mix_u32(h, (uint32_t)qo_quat_from_mat3_f32(&m, &q1)); mix_q(h, q1);
    mix_u32(h, (uint32_t)qo_quat_from_mat3_ortho_f32(&m, &q1)); mix_q(h, q1);
    mix_u32(h, (uint32_t)qo_quat_to_axis_angle_f32(a, &ax, &ang));
    mix_f(h, ax.x); mix_f(h, ax.y); mix_f(h, ax.z); mix_f(h, ang);
    mix_u32(h, (uint32_t)qo_quat_from_axis_angle_f32(v, x, &q1)); mix_q(h, q1);
    mix_u32(h, (uint32_t)qo_quat_to_rotvec_f32(a, &ax)); mix_f(h, ax.x); mix_f(h, ax.y); mix_f(h, ax.z);
    mix_u32(h, (uint32_t)qo_quat_from_rotvec_f32(v, &q1)); mix_q(h, q1);

    h = &digest[F_EULER][c];
    *h = 2166136261u;
    for (seq = 0; seq < (int)QO_EULER_SEQ_COUNT_; seq++) {
        mix_u32(h, (uint32_t)qo_quat_to_euler_f32(a, (qo_euler_seq)seq, &e, &info));
        mix_f(h, e.a1); mix_f(h, e.a2); mix_f(h, e.a3); mix_u32(h, (uint32_t)info.locked);
        mix_f(h, info.margin);
        e.a1 = x; e.a2 = 0.25f * y; e.a3 = v.z;
        mix_u32(h, (uint32_t)qo_quat_from_euler_f32((qo_euler_seq)seq, e, &q1)); mix_q(h, q1);
    }

    h = &digest[F_INTERP][c];
    *h = 2166136261u;
    for (k = 0; k <= 8; k++) {
        float t = (float)k * 0.125f;
        mix_u32(h, (uint32_t)qo_quat_slerp_f32(a, b, t, &q1)); mix_q(h, q1);
        mix_u32(h, (uint32_t)qo_quat_nlerp_f32(a, b, t, &q1)); mix_q(h, q1);
    }
    q2 = rand_q(&s); q3 = rand_q(&s);
    keys[0] = a; keys[1] = b; keys[2] = q2; keys[3] = q3;
    mix_u32(h, (uint32_t)qo_quat_squad_controls_f32(keys, 4, ctl));
    for (k = 0; k < 4; k++) mix_q(h, ctl[k]);
    mix_u32(h, (uint32_t)qo_quat_squad_f32(b, ctl[1], ctl[2], q2, 0.375f, &q1)); mix_q(h, q1);
    mix_u32(h, (uint32_t)qo_quat_bezier3_f32(a, b, q2, q3, 0.625f, &q1)); mix_q(h, q1);
}

static void test_same_bits(void **state)
{
    int c, f, bad = 0;
    const char *print = getenv("QORIENT_SAME_BITS_PRINT");
    (void)state;
    for (c = 0; c < N_CASES; c++) run_case(c);
    if (print != NULL && print[0] != '\0') {
        printf("/* tests/common/same_bits.h: digests of tests/core/test_same_bits.c (made on x86-64; how: see\n"
               " * that file's comment). Every target must reproduce them bit for bit. */\n"
               "static const uint32_t same_bits_expected[%d][%d] = {\n", F_COUNT, N_CASES);
        for (f = 0; f < F_COUNT; f++) {
            printf("    { /* %s */\n", family[f]);
            for (c = 0; c < N_CASES; c++)
                printf("%s0x%08lxu,%s", (c % 6 == 0) ? "        " : " ", (unsigned long)digest[f][c],
                       (c % 6 == 5) ? "\n" : "");
            printf("    },\n");
        }
        printf("};\n");
        return;
    }
    for (f = 0; f < F_COUNT; f++)
        for (c = 0; c < N_CASES; c++)
            if (digest[f][c] != same_bits_expected[f][c]) {
                print_error("different bits: %s, case %d: digest 0x%08lx, expected 0x%08lx\n",
                            family[f], c, (unsigned long)digest[f][c],
                            (unsigned long)same_bits_expected[f][c]);
                bad++;
            }
    if (bad) fail_msg("%d digests differ from tests/common/same_bits.h", bad);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_bits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
