/*
 * bench/qemu/ops.c - one operation run n times on a Cortex-M under QEMU, for instruction
 * counts. Usage (semihosting command line): ops.elf <op> <n>.
 * run.sh executes every op with n = 0 and n = 8 and counts executed instructions (one
 * instruction per translation block, -d exec): (count(8) - count(0)) / 8 per call, minus the
 * same figure for "nop" (loop, indirect call, input selection: the harness, not the op).
 * The 8 inputs are generic (no special case), the same for float and fixed.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "qorient/convert.h"
#include "qorient/convert_fx.h"
#include "qorient/euler.h"
#include "qorient/euler_fx.h"
#include "qorient/fxconv.h"
#include "qorient/fxmath.h"
#include "qorient/interp.h"
#include "qorient/interp_fx.h"
#include "qorient/quat.h"
#include "qorient/quat_fx.h"

#define NIN 8
static const qo_quat_f32 k_qa[NIN] = {
    { 0.5395f, -0.2130f, 0.7071f, 0.4050f }, { 0.1254f, 0.9050f, -0.3321f, 0.2336f },
    { -0.6124f, 0.3536f, 0.3536f, 0.6124f }, { 0.8776f, 0.0000f, -0.4794f, 0.0000f },
    { 0.2706f, 0.6533f, 0.2706f, -0.6533f }, { 0.9239f, 0.2209f, 0.2209f, 0.2209f },
    { -0.0998f, 0.5646f, 0.6120f, -0.5454f }, { 0.7301f, -0.4082f, 0.1826f, 0.5164f } };
static const qo_quat_f32 k_qb[NIN] = {
    { 0.9659f, 0.2588f, 0.0000f, 0.0000f }, { 0.4082f, -0.4082f, 0.8165f, 0.0000f },
    { 0.3000f, 0.5000f, -0.7000f, 0.4123f }, { 0.0500f, 0.7000f, 0.7000f, 0.1300f },
    { 0.6000f, 0.0000f, 0.6000f, 0.5292f }, { -0.3162f, 0.3162f, 0.6325f, 0.6325f },
    { 0.7071f, 0.0000f, 0.0000f, 0.7071f }, { 0.1826f, 0.3651f, 0.5477f, 0.7303f } };
static const qo_vec3_f32 k_v[NIN] = {
    { 0.3f, -0.8f, 0.5f }, { -0.9f, 0.1f, 0.4f }, { 0.2f, 0.2f, -0.95f }, { 0.7f, 0.7f, 0.1f },
    { -0.5f, 0.5f, 0.7f }, { 0.0f, -0.6f, 0.8f }, { 0.9f, -0.3f, -0.3f }, { -0.4f, -0.4f, 0.8f } };
static const float k_t[NIN] = { 0.1f, 0.9f, 0.37f, 0.5f, 0.73f, 0.25f, 0.61f, 0.05f };
static const float k_s[NIN] = { 0.7f, 0.031f, 0.93f, 0.4f, 0.55f, 0.0123f, 0.81f, 0.2f };
static const float k_ang[NIN] = { 0.3f, -2.9f, 1.4f, -0.7f, 2.2f, -1.6f, 3.1f, -0.05f };

/* Prepared per-format inputs (setup, not counted: identical for n = 0 and n = 8). */
static qo_quat_f32 g_qn[NIN];
static qo_mat3_f32 g_m[NIN];
static qo_q30 g_s30[NIN], g_y30[NIN], g_x30[NIN];
static qo_q28 g_a28[NIN];
static qo_quat_q30 g_xa[NIN], g_xb[NIN], g_xn[NIN];
static qo_vec3_q30 g_xv[NIN];
static qo_mat3_q30 g_xm[NIN];
static qo_q30 g_xt[NIN];

/* Results go to volatile sinks so nothing is optimised away. */
static volatile float g_sink_f;
static volatile int32_t g_sink_i;

static void sink_q(qo_quat_f32 q) { g_sink_f = q.w; g_sink_f = q.x; g_sink_f = q.y; g_sink_f = q.z; }

static void op_nop(int i) { g_sink_i = i; }
static void op_f_mul(int i) { sink_q(qo_quat_mul_f32(k_qa[i], k_qb[i])); }
static void op_f_rotate(int i)
{
    qo_vec3_f32 r = qo_quat_rotate_f32(k_qa[i], k_v[i]);
    g_sink_f = r.x; g_sink_f = r.y; g_sink_f = r.z;
}
static void op_f_normalize(int i) { qo_quat_f32 q; (void)qo_quat_normalize_f32(g_qn[i], &q); sink_q(q); }
static void op_f_to_mat3(int i)
{
    qo_mat3_f32 m;
    (void)qo_mat3_from_quat_f32(k_qa[i], &m);
    g_sink_f = m.m[0][0]; g_sink_f = m.m[1][1]; g_sink_f = m.m[2][2];
}
static void op_f_from_mat3(int i) { qo_quat_f32 q; (void)qo_mat3_to_quat_f32(&g_m[i], &q); sink_q(q); }
static void op_f_to_euler_ZYX(int i)
{
    qo_euler_f32 e;
    (void)qo_euler_from_quat_f32(k_qa[i], QO_EULER_ZYX, &e, NULL);
    g_sink_f = e.a1; g_sink_f = e.a2; g_sink_f = e.a3;
}
static void op_f_slerp(int i) { qo_quat_f32 q; (void)qo_interp_slerp_f32(k_qa[i], k_qb[i], k_t[i], &q); sink_q(q); }
static void op_f_sqrt(int i) { g_sink_f = sqrtf(k_s[i]); }
static void op_f_sin(int i) { g_sink_f = sinf(k_ang[i]); }
static void op_f_atan2(int i) { g_sink_f = atan2f(k_v[i].y, k_v[i].x); }
static void op_x_sqrt(int i) { qo_q30 r; (void)qo_fx_sqrt_q30(g_s30[i], &r); g_sink_i = r; }
static void op_x_sin(int i) { g_sink_i = qo_fx_sin_q28(g_a28[i]); }
static void op_x_atan2(int i) { g_sink_i = qo_fx_atan2_q28(g_y30[i], g_x30[i]); }

static void sink_x(qo_quat_q30 q) { g_sink_i = q.w; g_sink_i = q.x; g_sink_i = q.y; g_sink_i = q.z; }
static void op_x_mul(int i) { sink_x(qo_quat_mul_q30(g_xa[i], g_xb[i])); }
static void op_x_rotate(int i)
{
    qo_vec3_q30 r = qo_quat_rotate_q30(g_xa[i], g_xv[i]);
    g_sink_i = r.x; g_sink_i = r.y; g_sink_i = r.z;
}
static void op_x_normalize(int i) { qo_quat_q30 q; (void)qo_quat_normalize_q30(g_xn[i], &q); sink_x(q); }
static void op_x_to_mat3(int i)
{
    qo_mat3_q30 m;
    (void)qo_mat3_from_quat_q30(g_xa[i], &m);
    g_sink_i = m.m[0][0]; g_sink_i = m.m[1][1]; g_sink_i = m.m[2][2];
}
static void op_x_to_euler_ZYX(int i)
{
    qo_euler_q28 e;
    (void)qo_euler_from_quat_q30(g_xa[i], QO_EULER_ZYX, &e, NULL);
    g_sink_i = e.a1; g_sink_i = e.a2; g_sink_i = e.a3;
}
static void op_x_slerp(int i) { qo_quat_q30 q; (void)qo_interp_slerp_q30(g_xa[i], g_xb[i], g_xt[i], &q); sink_x(q); }
static void op_x_from_mat3(int i) { qo_quat_q30 q; (void)qo_mat3_to_quat_q30(&g_xm[i], &q); sink_x(q); }

typedef struct op { const char *name; void (*fn)(int); } op;
static const op k_ops[] = {
    { "nop", op_nop },
    { "f_mul", op_f_mul }, { "f_rotate", op_f_rotate }, { "f_normalize", op_f_normalize },
    { "f_to_mat3", op_f_to_mat3 }, { "f_from_mat3", op_f_from_mat3 },
    { "f_to_euler_ZYX", op_f_to_euler_ZYX }, { "f_slerp", op_f_slerp },
    { "f_sqrt", op_f_sqrt }, { "f_sin", op_f_sin }, { "f_atan2", op_f_atan2 },
    { "x_mul", op_x_mul }, { "x_rotate", op_x_rotate }, { "x_normalize", op_x_normalize },
    { "x_to_mat3", op_x_to_mat3 }, { "x_from_mat3", op_x_from_mat3 },
    { "x_to_euler_ZYX", op_x_to_euler_ZYX }, { "x_slerp", op_x_slerp },
    { "x_sqrt", op_x_sqrt }, { "x_sin", op_x_sin }, { "x_atan2", op_x_atan2 },
    { 0, 0 } };

int main(int argc, char **argv)
{
    int i, n;
    const op *o;
    if (argc < 3) return 2;
    n = atoi(argv[2]);
    for (i = 0; i < NIN; i++) {
        qo_quat_f32 q = k_qa[i];
        q.w *= 1.7f; q.x *= 1.7f; q.y *= 1.7f; q.z *= 1.7f;   /* non-unit normalise input */
        g_qn[i] = q;
        (void)qo_mat3_from_quat_f32(k_qa[i], &g_m[i]);
        g_s30[i] = qo_q30_from_f32(k_s[i]);
        g_y30[i] = qo_q30_from_f32(k_v[i].y);
        g_x30[i] = qo_q30_from_f32(k_v[i].x);
        g_a28[i] = qo_q28_from_f32(k_ang[i]);
        g_xa[i] = qo_q30_quat_from_f32(k_qa[i]);
        (void)qo_quat_normalize_q30(g_xa[i], &g_xa[i]);
        g_xb[i] = qo_q30_quat_from_f32(k_qb[i]);
        (void)qo_quat_normalize_q30(g_xb[i], &g_xb[i]);
        g_xn[i] = qo_q30_quat_from_f32(k_qa[i]);
        g_xn[i].w /= 2; g_xn[i].x /= 2; g_xn[i].y /= 2; g_xn[i].z /= 2;   /* non-unit */
        g_xv[i] = qo_q30_vec3_from_f32(k_v[i]);
        g_xm[i] = qo_q30_mat3_from_f32(&g_m[i]);
        g_xt[i] = qo_q30_from_f32(k_t[i]);
    }
    for (o = k_ops; o->name != NULL; o++)
        if (!strcmp(o->name, argv[1])) break;
    if (o->name == NULL) return 3;
    for (i = 0; i < n; i++) o->fn(i % NIN);
    return 0;
}
