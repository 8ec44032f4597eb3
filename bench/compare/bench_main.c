/*
 * bench/compare/bench_main.c - `make bench`: qorient against cglm, Eigen and libfixmath on the
 * same inputs, in one process.
 *
 *   bench [--reps R]      time every kernel R times (interleaved: rep 1 of every kernel, then
 *                         rep 2, ...) and print, per kernel, the median and minimum ns per call,
 *                         then the accuracy of every kernel against a double reference.
 *   bench --once          run every kernel once (for callgrind: instructions per call are the
 *                         collected Ir of bk_<lib>_<op> divided by BK_N).
 *
 * Output lines (tab separated, parsed by tools/bench.sh):
 *   time  <lib> <op> <median ns/call> <min ns/call>
 *   acc   <lib> <op> <max error> <mean error> <unit>
 *
 * Error measures (all against double computations of tests/common/ref.c on the same inputs,
 * as the library received them):
 *   quaternion outputs   max |component difference| after aligning the sign (q and -q are the
 *                        same rotation); unit quaternions, so this is about half the angle error
 *   vector / matrix      max |component difference| (unit-length inputs)
 *   Euler angles         rotation angle (rad) between the input and the angles composed back
 *                        in double in the sequence's convention (independent of angle ranges)
 *   fixed primitives     |f(x) - result| with x the library's own quantised input
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "common/ref.h"

static bk_input g_in;
static bk_output g_out;

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static void make_inputs(bk_input *in)
{
    ref_rng r = { 0x9e3779b97f4a7c15ull };
    int i, s;
    for (i = 0; i < BK_N; i++) {
        ref_quat a = ref_rng_quat(&r), b = ref_rng_quat(&r);
        double k = ref_rng_range(&r, 0.5, 2.0);
        ref_mat3 m = ref_quat_to_mat3(a);
        in->qa[i] = ref_quat_to_f32(a);
        in->qb[i] = ref_quat_to_f32(b);
        in->qn[i].w = (float)(a.w * k); in->qn[i].x = (float)(a.x * k);
        in->qn[i].y = (float)(a.y * k); in->qn[i].z = (float)(a.z * k);
        in->v[i].x = (float)ref_rng_range(&r, -1, 1);
        in->v[i].y = (float)ref_rng_range(&r, -1, 1);
        in->v[i].z = (float)ref_rng_range(&r, -1, 1);
        in->m[i] = ref_mat3_to_f32(&m);
        in->t[i] = (float)ref_rng_unit(&r);
    }
    for (s = 0; s < BK_FX_SETS; s++) {
        for (i = 0; i < BK_N; i++) {
            in->fx_unit[s][i] = ref_rng_range(&r, 1e-3, 1.0);
            in->fx_ang[s][i] = ref_rng_range(&r, -REF_PI, REF_PI);
            in->fx_y[s][i] = ref_rng_range(&r, -1, 1);
            in->fx_x[s][i] = ref_rng_range(&r, -1, 1);
        }
    }
}

/* ---- double references ---------------------------------------------------------------- */

static ref_quat ref_slerp(ref_quat a, ref_quat b, double t)
{
    ref_quat d, s, r;
    double th, wa, wb, dot = a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
    if (dot < 0) { b.w = -b.w; b.x = -b.x; b.y = -b.y; b.z = -b.z; }
    d.w = a.w - b.w; d.x = a.x - b.x; d.y = a.y - b.y; d.z = a.z - b.z;
    s.w = a.w + b.w; s.x = a.x + b.x; s.y = a.y + b.y; s.z = a.z + b.z;
    th = 2.0 * atan2(ref_quat_norm(d), ref_quat_norm(s));
    if (th < 1e-12) return ref_quat_normalize(a);
    wa = sin((1 - t) * th) / sin(th);
    wb = sin(t * th) / sin(th);
    r.w = wa * a.w + wb * b.w; r.x = wa * a.x + wb * b.x;
    r.y = wa * a.y + wb * b.y; r.z = wa * a.z + wb * b.z;
    return ref_quat_normalize(r);
}

/* Elementary rotation quaternion about axis 0/1/2 by angle a (rad). */
static ref_quat ref_axis_quat(int axis, double a)
{
    ref_quat q = { cos(a / 2), 0, 0, 0 };
    if (axis == 0) q.x = sin(a / 2);
    else if (axis == 1) q.y = sin(a / 2);
    else q.z = sin(a / 2);
    return q;
}

/* Quaternion of intrinsic Euler angles e in the upper-case sequence seq ("XYZ"...):
 * q = q_A1(e1) q_A2(e2) q_A3(e3). */
static ref_quat ref_from_euler_intrinsic(const char *seq, const double e[3])
{
    ref_quat q = ref_axis_quat(seq[0] - 'X', e[0]);
    q = ref_quat_mul(q, ref_axis_quat(seq[1] - 'X', e[1]));
    return ref_quat_mul(q, ref_axis_quat(seq[2] - 'X', e[2]));
}

static double quat_err(ref_quat got, ref_quat want)
{
    double p = 0, n = 0, d;
    d = fabs(got.w - want.w); if (d > p) p = d;
    d = fabs(got.x - want.x); if (d > p) p = d;
    d = fabs(got.y - want.y); if (d > p) p = d;
    d = fabs(got.z - want.z); if (d > p) p = d;
    d = fabs(got.w + want.w); if (d > n) n = d;
    d = fabs(got.x + want.x); if (d > n) n = d;
    d = fabs(got.y + want.y); if (d > n) n = d;
    d = fabs(got.z + want.z); if (d > n) n = d;
    if (!(p == p) || !(n == n)) return INFINITY;
    return p < n ? p : n;
}

static double vec_err(ref_vec3 got, ref_vec3 want)
{
    double e = fabs(got.x - want.x);
    if (fabs(got.y - want.y) > e) e = fabs(got.y - want.y);
    if (fabs(got.z - want.z) > e) e = fabs(got.z - want.z);
    return e == e ? e : INFINITY;
}

static double mat_err(const qo_mat3_f32 *got, const ref_mat3 *want)
{
    double e = 0;
    int r, c;
    for (r = 0; r < 3; r++)
        for (c = 0; c < 3; c++) {
            double d = fabs(got->m[r][c] - want->m[r][c]);
            if (!(d == d)) return INFINITY;
            if (d > e) e = d;
        }
    return e;
}

/* Fixed-point primitive reference of op on the real inputs in (x, y) (the library's own
 * quantised inputs, which its fetch function reports in out->s_in). */
static double fx_ref(const char *op, double x, double y)
{
    if (!strcmp(op, "fx_sqrt")) return sqrt(x);
    if (!strcmp(op, "fx_sin")) return sin(x);
    if (!strcmp(op, "fx_cos")) return cos(x);
    return atan2(y, x);
}

static ref_quat ref_q(const double d[4])
{
    ref_quat q;
    q.w = d[0]; q.x = d[1]; q.y = d[2]; q.z = d[3];
    return q;
}

static ref_vec3 ref_v(const double d[3])
{
    ref_vec3 v;
    v.x = d[0]; v.y = d[1]; v.z = d[2];
    return v;
}

/* Error of output i of kernel op; sets *unit. Float kernels are checked against their float
 * inputs, fixed-point kernels against their own quantised inputs (o->qin, o->vin). */
static double op_error(const char *op, const bk_output *o, int i, const char **unit)
{
    const bk_input *in = &g_in;
    int fx = !strncmp(op, "fx_", 3);
    ref_quat a = fx ? ref_q(o->qin[0][i]) : ref_quat_from_f32(in->qa[i]);
    ref_quat b = fx ? ref_q(o->qin[1][i]) : ref_quat_from_f32(in->qb[i]);
    ref_quat n = fx ? ref_q(o->qin[2][i]) : ref_quat_from_f32(in->qn[i]);
    ref_vec3 v = fx ? ref_v(o->vin[i]) : ref_vec3_from_f32(in->v[i]);
    ref_quat gq = fx ? ref_q(o->qd[i]) : ref_quat_from_f32(o->q[i]);
    ref_vec3 gv = fx ? ref_v(o->vd[i]) : ref_vec3_from_f32(o->v[i]);
    *unit = "abs";
    if (!strcmp(op, "mul") || !strcmp(op, "fx_quat_mul")) return quat_err(gq, ref_quat_mul(a, b));
    if (!strcmp(op, "rotate") || !strcmp(op, "fx_quat_rotate")) return vec_err(gv, ref_quat_rotate(a, v));
    if (!strcmp(op, "normalize") || !strcmp(op, "fx_quat_normalize"))
        return quat_err(gq, ref_quat_normalize(n));
    if (!strcmp(op, "to_mat3")) {
        ref_mat3 m = ref_quat_to_mat3(a);
        return mat_err(&o->m[i], &m);
    }
    if (!strcmp(op, "from_mat3") || !strcmp(op, "from_mat3_trusted")) {
        ref_mat3 m = ref_mat3_from_f32(&in->m[i]);
        return quat_err(gq, ref_mat3_to_quat(&m));
    }
    if (!strcmp(op, "slerp") || !strcmp(op, "fx_slerp"))
        return quat_err(gq, ref_slerp(ref_quat_normalize(a), ref_quat_normalize(b), in->t[i]));
    if (!strncmp(op, "to_euler_", 9) || !strncmp(op, "fx_to_euler_", 12)) {
        const char *seq = strrchr(op, '_') + 1;
        *unit = "rad";
        return ref_quat_angle_between(a, ref_from_euler_intrinsic(seq, o->e[i]));
    }
    if (fx) {
        double e = fabs(o->s[i] - fx_ref(op, o->s_in[i][0], o->s_in[i][1]));
        *unit = strcmp(op, "fx_atan2") ? "abs" : "rad";
        return e == e ? e : INFINITY;
    }
    fprintf(stderr, "bench: no reference for op %s\n", op);
    exit(2);
}

/* ---- driver --------------------------------------------------------------------------- */

#define MAX_KERNELS 96
#define MAX_REPS 201

static const bk_kernel *g_k[MAX_KERNELS];
static int g_nk;

static void add_kernels(const bk_kernel *ks)
{
    for (; ks->run != NULL; ks++) {
        if (g_nk < MAX_KERNELS) g_k[g_nk++] = ks;
    }
}

static void select_set(int s)
{
    bk_fixmath_set(s);
    bk_qofx_set(s);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double g_ns[MAX_KERNELS][MAX_REPS];

int main(int argc, char **argv)
{
    int reps = 41, once = 0, i, k, r;
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--once")) once = 1;
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc) reps = atoi(argv[++i]);
        else { fprintf(stderr, "usage: bench [--reps R] [--once]\n"); return 2; }
    }
    if (reps < 1 || reps > MAX_REPS) { fprintf(stderr, "bench: reps in 1..%d\n", MAX_REPS); return 2; }
    make_inputs(&g_in);
    bk_qorient_load(&g_in);
    bk_cglm_load(&g_in);
    bk_eigen_load(&g_in);
    bk_fixmath_load(&g_in);
    bk_qofx_load(&g_in);
    add_kernels(bk_qorient_kernels);
    add_kernels(bk_cglm_kernels);
    add_kernels(bk_eigen_kernels);
    add_kernels(bk_qofx_kernels);
    add_kernels(bk_fixmath_kernels);

    if (once) {
        select_set(0);
        for (k = 0; k < g_nk; k++) g_k[k]->run();
        return 0;
    }
    for (k = 0; k < g_nk; k++) g_k[k]->run();   /* warm caches and branch predictors */
    for (r = 0; r < reps; r++) {
        select_set(r % BK_FX_SETS);
        for (k = 0; k < g_nk; k++) {
            double t0 = now_ns();
            g_k[k]->run();
            g_ns[k][r] = (now_ns() - t0) / BK_N;
        }
    }
    for (k = 0; k < g_nk; k++) {
        qsort(g_ns[k], (size_t)reps, sizeof g_ns[k][0], cmp_double);
        printf("time\t%s\t%s\t%.3f\t%.3f\n", g_k[k]->lib, g_k[k]->op, g_ns[k][reps / 2], g_ns[k][0]);
    }
    select_set(0);
    for (k = 0; k < g_nk; k++) {
        double mx = 0, sum = 0;
        const char *unit = "abs";
        g_k[k]->run();
        g_k[k]->fetch(&g_out);
        for (i = 0; i < BK_N; i++) {
            double e = op_error(g_k[k]->op, &g_out, i, &unit);
            if (e > mx) mx = e;
            sum += e;
        }
        printf("acc\t%s\t%s\t%.3e\t%.3e\t%s\n", g_k[k]->lib, g_k[k]->op, mx, sum / BK_N, unit);
    }
    return 0;
}
