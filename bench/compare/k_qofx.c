/* bench/compare/k_qofx.c - qorient fixed-point kernels of the comparison (see bench.h):
 * the primitives of qorient/fxmath.h (Q1.30 values, Q3.28 angles) on the same real inputs
 * as libfixmath's Q16.16 kernels, cycled over the same BK_FX_SETS input sets. */
#include "bench.h"
#include "qorient/fxmath.h"

static qo_q30 g_x[BK_FX_SETS][BK_N], g_ay[BK_FX_SETS][BK_N], g_ax[BK_FX_SETS][BK_N];
static qo_q28 g_ang[BK_FX_SETS][BK_N];
static int g_set, g_kind;
static int32_t g_s[BK_N];

static int32_t fx(double v, double one)
{
    double t = v * one;
    return (int32_t)(t < 0 ? t - 0.5 : t + 0.5);
}

#define Q30 1073741824.0
#define Q28 268435456.0

void bk_qofx_load(const bk_input *in)
{
    int s, i;
    for (s = 0; s < BK_FX_SETS; s++) {
        for (i = 0; i < BK_N; i++) {
            g_x[s][i] = fx(in->fx_unit[s][i], Q30);
            g_ang[s][i] = fx(in->fx_ang[s][i], Q28);
            g_ay[s][i] = fx(in->fx_y[s][i], Q30);
            g_ax[s][i] = fx(in->fx_x[s][i], Q30);
        }
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

const bk_kernel bk_qofx_kernels[] = {
    { "qorient", "fx_sqrt", bk_qofx_fx_sqrt, fetch },
    { "qorient", "fx_sin", bk_qofx_fx_sin, fetch },
    { "qorient", "fx_cos", bk_qofx_fx_cos, fetch },
    { "qorient", "fx_atan2", bk_qofx_fx_atan2, fetch },
    { 0, 0, 0, 0 }
};
