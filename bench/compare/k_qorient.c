/* bench/compare/k_qorient.c - qorient float32 kernels of the comparison (see bench.h). The
 * library is called as a user calls it: through its public functions, compiled separately
 * (no inlining across the call), with every status checked by the caller (ignored here).
 * The inputs are copied once into this file's own arrays, as every other library's file does,
 * so that no kernel pays for reading a pointer the others do not have. */
#include "bench.h"
#include "qorient/convert.h"
#include "qorient/euler.h"
#include "qorient/interp.h"
#include "qorient/quat.h"

static qo_quat_f32 g_qa[BK_N], g_qb[BK_N], g_qn[BK_N], g_q[BK_N];
static qo_vec3_f32 g_vin[BK_N];
static qo_mat3_f32 g_min[BK_N];
static float g_t[BK_N];
static qo_vec3_f32 g_v[BK_N];
static qo_mat3_f32 g_m[BK_N];
static qo_euler_f32 g_e[BK_N];

void bk_qorient_load(const bk_input *in)
{
    int i;
    for (i = 0; i < BK_N; i++) {
        g_qa[i] = in->qa[i]; g_qb[i] = in->qb[i]; g_qn[i] = in->qn[i];
        g_vin[i] = in->v[i]; g_min[i] = in->m[i]; g_t[i] = in->t[i];
    }
}

static void fetch(bk_output *o)
{
    int i;
    for (i = 0; i < BK_N; i++) {
        o->q[i] = g_q[i];
        o->v[i] = g_v[i];
        o->m[i] = g_m[i];
        o->e[i][0] = g_e[i].a1; o->e[i][1] = g_e[i].a2; o->e[i][2] = g_e[i].a3;
    }
}

void bk_qorient_mul(void);
void bk_qorient_mul(void)
{
    int i;
    for (i = 0; i < BK_N; i++) g_q[i] = qo_quat_mul_f32(g_qa[i], g_qb[i]);
}

void bk_qorient_rotate(void);
void bk_qorient_rotate(void)
{
    int i;
    for (i = 0; i < BK_N; i++) g_v[i] = qo_quat_rotate_f32(g_qa[i], g_vin[i]);
}

void bk_qorient_normalize(void);
void bk_qorient_normalize(void)
{
    int i;
    for (i = 0; i < BK_N; i++) (void)qo_quat_normalize_f32(g_qn[i], &g_q[i]);
}

void bk_qorient_to_mat3(void);
void bk_qorient_to_mat3(void)
{
    int i;
    for (i = 0; i < BK_N; i++) (void)qo_mat3_from_quat_f32(g_qa[i], &g_m[i]);
}

void bk_qorient_from_mat3(void);
void bk_qorient_from_mat3(void)
{
    int i;
    for (i = 0; i < BK_N; i++) (void)qo_mat3_to_quat_f32(&g_min[i], &g_q[i]);
}

void bk_qorient_from_mat3_trusted(void);
void bk_qorient_from_mat3_trusted(void)
{
    int i;
    for (i = 0; i < BK_N; i++) (void)qo_mat3_to_quat_trusted_f32(&g_min[i], &g_q[i]);
}

static void euler(qo_euler_seq seq)
{
    int i;
    for (i = 0; i < BK_N; i++) (void)qo_euler_from_quat_f32(g_qa[i], seq, &g_e[i], NULL);
}

void bk_qorient_to_euler_XYZ(void);
void bk_qorient_to_euler_XYZ(void) { euler(QO_EULER_XYZ); }
void bk_qorient_to_euler_ZYX(void);
void bk_qorient_to_euler_ZYX(void) { euler(QO_EULER_ZYX); }
void bk_qorient_to_euler_ZXZ(void);
void bk_qorient_to_euler_ZXZ(void) { euler(QO_EULER_ZXZ); }

void bk_qorient_slerp(void);
void bk_qorient_slerp(void)
{
    int i;
    for (i = 0; i < BK_N; i++) (void)qo_interp_slerp_f32(g_qa[i], g_qb[i], g_t[i], &g_q[i]);
}

const bk_kernel bk_qorient_kernels[] = {
    { "qorient", "mul", bk_qorient_mul, fetch },
    { "qorient", "rotate", bk_qorient_rotate, fetch },
    { "qorient", "normalize", bk_qorient_normalize, fetch },
    { "qorient", "to_mat3", bk_qorient_to_mat3, fetch },
    { "qorient", "from_mat3", bk_qorient_from_mat3, fetch },
    { "qorient", "from_mat3_trusted", bk_qorient_from_mat3_trusted, fetch },
    { "qorient", "to_euler_XYZ", bk_qorient_to_euler_XYZ, fetch },
    { "qorient", "to_euler_ZYX", bk_qorient_to_euler_ZYX, fetch },
    { "qorient", "to_euler_ZXZ", bk_qorient_to_euler_ZXZ, fetch },
    { "qorient", "slerp", bk_qorient_slerp, fetch },
    { 0, 0, 0, 0 }
};
