/* bench/compare/k_qofx.c - qorient fixed-point kernels of the comparison (see bench.h):
 * the primitives of qorient/fxmath.h (Q1.30 values, Q3.28 angles) and the Q1.30 quaternion
 * operations of qorient/quat_fx.h, on the same real inputs
 * as libfixmath's Q16.16 kernels, cycled over the same BK_FX_SETS input sets. */
#include <math.h>

#include "bench.h"
#include "qorient/euler_fx.h"
#include "qorient/fxmath.h"
#include "qorient/interp_fx.h"
#include "qorient/quat_fx.h"

static qo_q30 g_x[BK_FX_SETS][BK_N], g_ay[BK_FX_SETS][BK_N], g_ax[BK_FX_SETS][BK_N];
static qo_q28 g_ang[BK_FX_SETS][BK_N];
static int g_set, g_kind;
static int32_t g_s[BK_N];
static qo_quat_q30 g_qa[BK_FX_SETS][BK_N], g_qb[BK_FX_SETS][BK_N], g_qn[BK_FX_SETS][BK_N];
static qo_vec3_q30 g_v[BK_N];
static qo_quat_q30 g_q[BK_N];
static qo_vec3_q30 g_vo[BK_N];
static qo_euler_q28 g_e[BK_N];
static qo_q30 g_t[BK_N];

static int32_t fx(double v, double one)
{
    double t = v * one;
    return (int32_t)(t < 0 ? t - 0.5 : t + 0.5);
}

#define Q30 1073741824.0
#define Q28 268435456.0

/* set s > 0 moves w by s LSB, as for libfixmath (timing only; accuracy uses set 0) */
/* q normalised in double, times k, rounded: a fixed-point user holds Q1.30-unit quaternions
 * (the float inputs are unit only to float32 rounding, 6e-8, which rotate would show). */
static qo_quat_q30 to_q30(qo_quat_f32 q, double k, int s)
{
    qo_quat_q30 r;
    double n = sqrt((double)q.w * q.w + (double)q.x * q.x + (double)q.y * q.y + (double)q.z * q.z);
    k /= n;
    r.w = fx(q.w * k, Q30) + s; r.x = fx(q.x * k, Q30); r.y = fx(q.y * k, Q30); r.z = fx(q.z * k, Q30);
    return r;
}

static void put_q(double d[4], qo_quat_q30 q)
{
    d[0] = q.w / Q30; d[1] = q.x / Q30; d[2] = q.y / Q30; d[3] = q.z / Q30;
}

void bk_qofx_load(const bk_input *in)
{
    int s, i;
    for (s = 0; s < BK_FX_SETS; s++) {
        for (i = 0; i < BK_N; i++) {
            g_x[s][i] = fx(in->fx_unit[s][i], Q30);
            g_ang[s][i] = fx(in->fx_ang[s][i], Q28);
            g_ay[s][i] = fx(in->fx_y[s][i], Q30);
            g_ax[s][i] = fx(in->fx_x[s][i], Q30);
            g_qa[s][i] = to_q30(in->qa[i], 1.0, s);
            g_qb[s][i] = to_q30(in->qb[i], 1.0, s);
            g_qn[s][i] = to_q30(in->qn[i], 0.5, s);   /* as libfixmath's: inside [-2, 2) */
        }
    }
    for (i = 0; i < BK_N; i++) {
        g_v[i].x = fx(in->v[i].x, Q30); g_v[i].y = fx(in->v[i].y, Q30); g_v[i].z = fx(in->v[i].z, Q30);
        g_t[i] = fx(in->t[i], Q30);
    }
}

void bk_qofx_set(int set) { g_set = set; }

static void fetch(bk_output *o)
{
    int i;
    o->fx_set = g_set;
    for (i = 0; i < BK_N; i++) {
        if (g_kind == 0) {
            o->s[i] = g_s[i] / Q30; o->s_in[i][0] = g_x[g_set][i] / Q30; o->s_in[i][1] = 0;
        } else if (g_kind == 1) {
            o->s[i] = g_s[i] / Q30; o->s_in[i][0] = g_ang[g_set][i] / Q28; o->s_in[i][1] = 0;
        } else {
            o->s[i] = g_s[i] / Q28;
            o->s_in[i][0] = g_ax[g_set][i] / Q30; o->s_in[i][1] = g_ay[g_set][i] / Q30;
        }
        o->qd[i][0] = g_q[i].w / Q30; o->qd[i][1] = g_q[i].x / Q30;
        o->qd[i][2] = g_q[i].y / Q30; o->qd[i][3] = g_q[i].z / Q30;
        put_q(o->qin[0][i], g_qa[g_set][i]);
        put_q(o->qin[1][i], g_qb[g_set][i]);
        put_q(o->qin[2][i], g_qn[g_set][i]);
        o->vin[i][0] = g_v[i].x / Q30; o->vin[i][1] = g_v[i].y / Q30; o->vin[i][2] = g_v[i].z / Q30;
        o->e[i][0] = g_e[i].a1 / Q28; o->e[i][1] = g_e[i].a2 / Q28; o->e[i][2] = g_e[i].a3 / Q28;
        o->vd[i][0] = g_vo[i].x / Q30; o->vd[i][1] = g_vo[i].y / Q30; o->vd[i][2] = g_vo[i].z / Q30;
    }
}

void bk_qofx_fx_sqrt(void);
void bk_qofx_fx_sqrt(void)
{
    int i;
    const qo_q30 *x = g_x[g_set];
    g_kind = 0;
    for (i = 0; i < BK_N; i++) (void)qo_fx_sqrt_q30(x[i], &g_s[i]);
}

void bk_qofx_fx_sin(void);
void bk_qofx_fx_sin(void)
{
    int i;
    const qo_q28 *a = g_ang[g_set];
    g_kind = 1;
    for (i = 0; i < BK_N; i++) g_s[i] = qo_fx_sin_q28(a[i]);
}

void bk_qofx_fx_cos(void);
void bk_qofx_fx_cos(void)
{
    int i;
    const qo_q28 *a = g_ang[g_set];
    g_kind = 1;
    for (i = 0; i < BK_N; i++) g_s[i] = qo_fx_cos_q28(a[i]);
}

void bk_qofx_fx_atan2(void);
void bk_qofx_fx_atan2(void)
{
    int i;
    const qo_q30 *y = g_ay[g_set], *x = g_ax[g_set];
    g_kind = 2;
    for (i = 0; i < BK_N; i++) g_s[i] = qo_fx_atan2_q28(y[i], x[i]);
}

void bk_qofx_fx_quat_mul(void);
void bk_qofx_fx_quat_mul(void)
{
    int i;
    const qo_quat_q30 *a = g_qa[g_set], *b = g_qb[g_set];
    for (i = 0; i < BK_N; i++) g_q[i] = qo_quat_mul_q30(a[i], b[i]);
}

void bk_qofx_fx_quat_normalize(void);
void bk_qofx_fx_quat_normalize(void)
{
    int i;
    const qo_quat_q30 *a = g_qn[g_set];
    for (i = 0; i < BK_N; i++) (void)qo_quat_normalize_q30(a[i], &g_q[i]);
}

void bk_qofx_fx_quat_rotate(void);
void bk_qofx_fx_quat_rotate(void)
{
    int i;
    const qo_quat_q30 *a = g_qa[g_set];
    for (i = 0; i < BK_N; i++) g_vo[i] = qo_quat_rotate_q30(a[i], g_v[i]);
}

void bk_qofx_fx_to_euler_ZYX(void);
void bk_qofx_fx_to_euler_ZYX(void)
{
    int i;
    const qo_quat_q30 *a = g_qa[g_set];
    for (i = 0; i < BK_N; i++) (void)qo_euler_from_quat_q30(a[i], QO_EULER_ZYX, &g_e[i], NULL);
}

void bk_qofx_fx_slerp(void);
void bk_qofx_fx_slerp(void)
{
    int i;
    const qo_quat_q30 *a = g_qa[g_set], *b = g_qb[g_set];
    for (i = 0; i < BK_N; i++) (void)qo_interp_slerp_q30(a[i], b[i], g_t[i], &g_q[i]);
}

const bk_kernel bk_qofx_kernels[] = {
    { "qorient", "fx_sqrt", bk_qofx_fx_sqrt, fetch },
    { "qorient", "fx_sin", bk_qofx_fx_sin, fetch },
    { "qorient", "fx_cos", bk_qofx_fx_cos, fetch },
    { "qorient", "fx_atan2", bk_qofx_fx_atan2, fetch },
    { "qorient", "fx_quat_mul", bk_qofx_fx_quat_mul, fetch },
    { "qorient", "fx_quat_normalize", bk_qofx_fx_quat_normalize, fetch },
    { "qorient", "fx_quat_rotate", bk_qofx_fx_quat_rotate, fetch },
    { "qorient", "fx_to_euler_ZYX", bk_qofx_fx_to_euler_ZYX, fetch },
    { "qorient", "fx_slerp", bk_qofx_fx_slerp, fetch },
    { 0, 0, 0, 0 }
};
