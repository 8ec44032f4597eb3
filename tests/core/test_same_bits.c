/*
 * The same bits on every target: a fixed set of inputs (built from integers only, so the inputs
 * themselves do not depend on any libm) goes through every float32 function that uses a
 * transcendental kernel - qorient/fmath.h itself, quat exp/log/angle/integrate, every
 * conversion, all 24 Euler conventions both ways, slerp, nlerp, squad, Bezier - and through
 * the float32 modules built on them - the gimbal (orientation path, step with hold band and
 * limits, tracking filter), the joint spline (every profile), the motion planner (both
 * profiles, every sync mode, target states, sampled along the plan) and the trajectory
 * (keyframes and a queue of moving targets) - and an FNV-1a
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
#include "qorient/gimbal.h"
#include "qorient/interp.h"
#include "qorient/motion.h"
#include "qorient/quat.h"
#include "qorient/spline.h"
#include "qorient/traj.h"

#define N_CASES 48
enum { F_KERNELS, F_QUAT, F_CONVERT, F_EULER, F_INTERP, F_GIMBAL, F_SPLINE, F_MOTION, F_TRAJ, F_COUNT };
static const char *const family[F_COUNT] = { "fmath",  "quat",   "convert", "euler", "interp",
                                             "gimbal", "spline", "motion",  "traj" };

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

static void mix_fs(uint32_t *h, const float *f, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) mix_f(h, f[i]);
}

/* gimbal: a path through the four keys (slerp or spline by case), sampled and fed to the
 * gimbal (each of the 24 conventions in turn, rate-limited on odd cases, position-limited on
 * every third) and on to the tracking filter (jerk-limited on odd cases). Case 3 starts on
 * the singular pitch of ZYX, so the hold band and the prediction through it are covered. */
static void run_gimbal(int c, const qo_quat_f32 *keys_in)
{
    uint32_t *h = &digest[F_GIMBAL][c];
    static const float kt[4] = { 0.0f, 0.5f, 1.25f, 2.0f };
    qo_gimbal_settings_f32 gs = qo_gimbal_settings_default;
    qo_gimbal_track_settings_f32 ts = qo_gimbal_track_settings_default;
    qo_quat_f32 keys[4], ka[4], kb[4], q;
    qo_gimbal_f32 g;
    qo_gimbal_sample_f32 o;
    qo_gimbal_track_f32 tr;
    qo_gimbal_track_sample_f32 to;
    qo_gimbal_path_f32 path;
    int k;
    *h = 2166136261u;
    mix_u32(h, (uint32_t)qo_gimbal_path_init_f32(&path, kt, keys_in, 4,
                                                  (c & 2) ? QO_GIMBAL_PATH_SPLINE : QO_GIMBAL_PATH_SLERP, keys, ka, kb));
    gs.seq = (c == 3) ? QO_EULER_ZYX : (qo_euler_seq)(c % (int)QO_EULER_SEQ_COUNT_);
    if (c & 1) gs.vmax = 2.0f;
    if (c % 3 == 0) { gs.min[1] = -1.0f; gs.max[1] = 1.0f; }
    mix_u32(h, (uint32_t)qo_gimbal_init_f32(&g, &gs));
    ts.amax = 20.0f;
    if (c & 1) ts.jmax = 400.0f;
    mix_u32(h, (uint32_t)qo_gimbal_track_init_f32(&tr, &ts));
    for (k = 0; k <= 24; k++) {
        float t = (float)k * 0.1f - 0.2f;
        mix_u32(h, (uint32_t)qo_gimbal_path_sample_f32(&path, t, &q)); mix_q(h, q);
        mix_u32(h, (uint32_t)qo_gimbal_step_f32(&g, t, q, &o));
        mix_f(h, o.angles.a1); mix_f(h, o.angles.a2); mix_f(h, o.angles.a3); mix_f(h, o.margin);
        mix_u32(h, (uint32_t)o.locked); mix_u32(h, o.clipped);
        mix_u32(h, (uint32_t)qo_gimbal_track_step_f32(&tr, t, o.angles, &to));
        mix_f(h, to.angles.a1); mix_f(h, to.angles.a2); mix_f(h, to.angles.a3);
        mix_fs(h, to.rate, 3); mix_fs(h, to.acc, 3); mix_f(h, to.err); mix_u32(h, (uint32_t)to.settled);
    }
}

/* spline: 2 joints through 5 keys at uneven times, the profile and end condition by case,
 * sampled before, across and after the keys (positions, velocities, accelerations, clamps). */
static void run_spline(int c, uint64_t *s)
{
    uint32_t *h = &digest[F_SPLINE][c];
    float t[5], p[10], kv[10], ka[10], coef[5 + 6 + 60], pos[2], vel[2], acc[2], lo[2], hi[2];
    int8_t cl[2];
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    int k;
    *h = 2166136261u;
    t[0] = unit_f(s, 1.0f);
    for (k = 1; k < 5; k++) t[k] = t[k - 1] + 0.25f + 0.5f * (unit_f(s, 1.0f) + 1.0f);
    for (k = 0; k < 10; k++) { p[k] = unit_f(s, 3.0f); kv[k] = unit_f(s, 2.0f); ka[k] = unit_f(s, 4.0f); }
    set.profile = (qo_spline_profile)(c % 5);
    set.end = (c & 8) ? QO_SPLINE_END_NATURAL : QO_SPLINE_END_CLAMPED;
    set.key_vel = kv;
    if (c & 16) set.key_acc = ka;
    if (c % 7 == 0) { lo[0] = lo[1] = -2.0f; hi[0] = hi[1] = 2.0f; set.pos_min = lo; set.pos_max = hi; }
    mix_u32(h, (uint32_t)qo_spline_init_f32(2, 5, t, p, &set, coef, sizeof coef / sizeof coef[0], &sp));
    for (k = 0; k <= 40; k++) {
        float ts = t[0] - 0.1f + (t[4] - t[0] + 0.2f) * ((float)k / 40.0f);
        mix_u32(h, (uint32_t)qo_spline_sample_f32(&sp, ts, pos, vel, acc, cl));
        mix_fs(h, pos, 2); mix_fs(h, vel, 2); mix_fs(h, acc, 2);
        mix_u32(h, (uint32_t)(cl[0] + 2 * cl[1] + 4));
    }
}

static void sample_plan(uint32_t *h, const qo_motion_planner_f32 *pl, float from, float span)
{
    float pos[3], vel[3], acc[3];
    int k;
    for (k = 0; k <= 20; k++) {
        mix_u32(h, (uint32_t)qo_motion_sample_f32(pl, from + span * ((float)k / 20.0f), pos, vel, acc));
        mix_fs(h, pos, 3); mix_fs(h, vel, 3); mix_fs(h, acc, 3);
    }
}

/* motion: 3 joints with random (on odd cases asymmetric) limits, the profile and sync mode by
 * case; a move to targets sampled along its plan, then a re-plan half way to a moving target
 * state, sampled likewise, then the velocity interface and a brake. */
static void run_motion(int c, uint64_t *s)
{
    uint32_t *h = &digest[F_MOTION][c];
    qo_motion_limits_f32 lim[3];
    qo_motion_joint_f32 jt[3];
    qo_motion_planner_f32 pl;
    qo_motion_settings_f32 set;
    float start[3], goal[3], gv[3], ga[3], tm;
    uint32_t clamped = 0;
    int j;
    *h = 2166136261u;
    for (j = 0; j < 3; j++) {
        lim[j] = qo_motion_limits_default;
        lim[j].vmax = 1.5f + unit_f(s, 1.0f);
        lim[j].amax = 4.0f + 2.0f * unit_f(s, 1.0f);
        lim[j].jmax = 30.0f + 10.0f * unit_f(s, 1.0f);
        if (c & 1) { lim[j].vmin = -0.5f * lim[j].vmax; lim[j].amin = -0.75f * lim[j].amax; }
        if (c % 5 == 0) { lim[j].pmin = -2.0f; lim[j].pmax = 2.0f; }
        start[j] = unit_f(s, 2.0f);
        goal[j] = unit_f(s, 4.0f);
        gv[j] = 0.4f * unit_f(s, 1.0f) * lim[j].vmax;
        ga[j] = (c & 2) ? 0.0f : 0.25f * unit_f(s, 1.0f) * lim[j].amax;
    }
    set.profile = (c & 2) ? QO_MOTION_TRAPEZOID : QO_MOTION_SCURVE;
    set.sync = (qo_motion_sync)((c >> 2) % 4);
    mix_u32(h, (uint32_t)qo_motion_init_f32(&pl, jt, 3, lim, start, 0.5f, &set));
    mix_u32(h, (uint32_t)qo_motion_set_target_f32(&pl, 0.5f, goal, &clamped)); mix_u32(h, clamped);
    tm = qo_motion_duration_f32(&pl);
    mix_f(h, tm); mix_u32(h, (uint32_t)qo_motion_sync_used(&pl)); mix_u32(h, pl.unsynced);
    sample_plan(h, &pl, 0.5f, tm);
    tm = 0.5f + 0.5f * tm;
    for (j = 0; j < 3; j++) goal[j] = -goal[j];
    mix_u32(h, (uint32_t)qo_motion_set_target_state_f32(&pl, tm, goal, gv, ga, &clamped));
    mix_u32(h, clamped);
    mix_f(h, qo_motion_duration_f32(&pl)); mix_u32(h, (uint32_t)qo_motion_sync_used(&pl));
    sample_plan(h, &pl, tm, qo_motion_duration_f32(&pl) + 0.5f);
    tm += 0.5f * qo_motion_duration_f32(&pl);
    mix_u32(h, (uint32_t)qo_motion_set_velocity_f32(&pl, tm, gv));
    sample_plan(h, &pl, tm, qo_motion_duration_f32(&pl));
    tm += 0.25f;
    mix_u32(h, (uint32_t)qo_motion_brake_f32(&pl, tm));
    sample_plan(h, &pl, tm, qo_motion_duration_f32(&pl));
}

/* traj: keyframes (the spline behind it, in nanoseconds from an origin far from 0) and a queue
 * of timed targets carrying velocities (the planner re-planned at each target's time). */
static void run_traj(int c, uint64_t *s)
{
    uint32_t *h = &digest[F_TRAJ][c];
    qo_traj tr;
    qo_traj_ns tns[4], t0 = (qo_traj_ns)1000000007 * (qo_traj_ns)(c + 1);
    qo_spline_settings_f32 ss = qo_spline_settings_default;
    qo_motion_limits_f32 lim[2];
    qo_motion_joint_f32 jt[2];
    float store[4 + 4 * 2 * 2 + 4 + 6 + 4 * 2 * 6], p[2], v[2], pos[2], vel[2], acc[2];
    int k;
    *h = 2166136261u;
    ss.profile = (qo_spline_profile)((c + 1) % 5);
    mix_u32(h, (uint32_t)qo_traj_init_keys(&tr, 2, &ss, 2, tns, 4, store, sizeof store / sizeof store[0]));
    for (k = 0; k < 4; k++) {
        p[0] = unit_f(s, 2.0f); p[1] = unit_f(s, 2.0f); v[0] = unit_f(s, 1.0f); v[1] = unit_f(s, 1.0f);
        mix_u32(h, (uint32_t)qo_traj_push(&tr, t0 + (qo_traj_ns)k * 700000001, p, v, NULL));
    }
    for (k = 0; k <= 30; k++) {
        mix_u32(h, (uint32_t)qo_traj_sample(&tr, t0 + (qo_traj_ns)k * 77777777 - 100000000, pos, vel, acc, NULL));
        mix_fs(h, pos, 2); mix_fs(h, vel, 2); mix_fs(h, acc, 2);
    }
    lim[0] = lim[1] = qo_motion_limits_default;
    lim[0].vmax = 2.0f; lim[0].amax = 5.0f; lim[0].jmax = 40.0f;
    lim[1].vmax = 1.0f; lim[1].amax = 3.0f; lim[1].jmax = 25.0f;
    mix_u32(h, (uint32_t)qo_traj_init_targets(&tr, 2, lim, NULL, jt, tns, 4, store, 4 * 2 * 2));
    p[0] = 0.0f; p[1] = 0.0f;
    mix_u32(h, (uint32_t)qo_traj_push(&tr, t0, p, NULL, NULL));
    for (k = 1; k < 4; k++) {
        p[0] = unit_f(s, 3.0f); p[1] = unit_f(s, 3.0f); v[0] = unit_f(s, 0.8f); v[1] = unit_f(s, 0.4f);
        mix_u32(h, (uint32_t)qo_traj_push(&tr, t0 + (qo_traj_ns)k * 900000000, p, v, NULL));
    }
    for (k = 0; k <= 40; k++) {
        mix_u32(h, (uint32_t)qo_traj_sample(&tr, t0 + (qo_traj_ns)k * 111111111, pos, vel, acc, NULL));
        mix_fs(h, pos, 2); mix_fs(h, vel, 2); mix_fs(h, acc, 2);
    }
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
    mix_u32(h, (uint32_t)qo_mat3_from_quat_f32(a, &m));
    for (k = 0; k < 9; k++) mix_f(h, m.m[k / 3][k % 3]);
    mix_u32(h, (uint32_t)qo_mat3_to_quat_f32(&m, &q1)); mix_q(h, q1);
    mix_u32(h, (uint32_t)qo_mat3_to_quat_ortho_f32(&m, &q1)); mix_q(h, q1);
    mix_u32(h, (uint32_t)qo_axis_angle_from_quat_f32(a, &ax, &ang));
    mix_f(h, ax.x); mix_f(h, ax.y); mix_f(h, ax.z); mix_f(h, ang);
    mix_u32(h, (uint32_t)qo_axis_angle_to_quat_f32(v, x, &q1)); mix_q(h, q1);
    mix_u32(h, (uint32_t)qo_rotvec_from_quat_f32(a, &ax)); mix_f(h, ax.x); mix_f(h, ax.y); mix_f(h, ax.z);
    mix_u32(h, (uint32_t)qo_rotvec_to_quat_f32(v, &q1)); mix_q(h, q1);

    h = &digest[F_EULER][c];
    *h = 2166136261u;
    for (seq = 0; seq < (int)QO_EULER_SEQ_COUNT_; seq++) {
        mix_u32(h, (uint32_t)qo_euler_from_quat_f32(a, (qo_euler_seq)seq, &e, &info));
        mix_f(h, e.a1); mix_f(h, e.a2); mix_f(h, e.a3); mix_u32(h, (uint32_t)info.locked);
        mix_f(h, info.margin);
        e.a1 = x; e.a2 = 0.25f * y; e.a3 = v.z;
        mix_u32(h, (uint32_t)qo_euler_to_quat_f32((qo_euler_seq)seq, e, &q1)); mix_q(h, q1);
    }

    h = &digest[F_INTERP][c];
    *h = 2166136261u;
    for (k = 0; k <= 8; k++) {
        float t = (float)k * 0.125f;
        mix_u32(h, (uint32_t)qo_interp_slerp_f32(a, b, t, &q1)); mix_q(h, q1);
        mix_u32(h, (uint32_t)qo_interp_nlerp_f32(a, b, t, &q1)); mix_q(h, q1);
    }
    q2 = rand_q(&s); q3 = rand_q(&s);
    keys[0] = a; keys[1] = b; keys[2] = q2; keys[3] = q3;
    mix_u32(h, (uint32_t)qo_interp_squad_controls_f32(keys, 4, ctl));
    for (k = 0; k < 4; k++) mix_q(h, ctl[k]);
    mix_u32(h, (uint32_t)qo_interp_squad_f32(b, ctl[1], ctl[2], q2, 0.375f, &q1)); mix_q(h, q1);
    mix_u32(h, (uint32_t)qo_interp_bezier3_f32(a, b, q2, q3, 0.625f, &q1)); mix_q(h, q1);

    run_gimbal(c, keys);
    run_spline(c, &s);
    run_motion(c, &s);
    run_traj(c, &s);
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
