/* bench/compare/k_fixmath.c - libfixmath (Debian libfixmath-dev, Q16.16, liblibfixmath.a)
 * kernels of the comparison (see bench.h).
 *
 * Primitives: fix16_sqrt, fix16_sin, fix16_cos, fix16_atan2 as shipped (Debian's build keeps
 * the sin and atan memo caches; the driver cycles BK_FX_SETS distinct input sets so the
 * timings are those of new inputs, as sensor data are). Composed operations: libfixmath has
 * no quaternions (libfixmatrix's qf16 is not packaged), so they are written here the
 * textbook way from its primitives, as a user of libfixmath would: fix16_mul for every
 * product, plain integer adds, fix16_sqrt + fix16_div to normalise, fix16_atan2/fix16_asin
 * for Euler angles, fix16_acos/fix16_sin/fix16_div for slerp. */
#include <math.h>

#include <libfixmath/fix16.h>

#include "bench.h"

typedef struct fq { fix16_t w, x, y, z; } fq;

static fix16_t g_x[BK_FX_SETS][BK_N], g_ang[BK_FX_SETS][BK_N], g_ay[BK_FX_SETS][BK_N],
    g_ax[BK_FX_SETS][BK_N];
static fq g_qa[BK_FX_SETS][BK_N], g_qb[BK_FX_SETS][BK_N], g_qn[BK_FX_SETS][BK_N];
static fix16_t g_v[BK_N][3], g_t[BK_N];
static int g_set;
/* outputs */
static fix16_t g_s[BK_N];
static fq g_q[BK_N];
static fix16_t g_vo[BK_N][3], g_e[BK_N][3];
static int g_kind; /* 0 sqrt, 1 sin/cos (angle input), 2 atan2 (inputs y, x) */

static fix16_t q16(double v) { return fix16_from_dbl(v); }
static double dbl(fix16_t v) { return fix16_to_dbl(v); }

static fq to_fq(qo_quat_f32 q, double k, int s)
{
    fq r;
    /* normalised in double first, as qorient's Q1.30 inputs (k_qofx.c) */
    k /= sqrt((double)q.w * q.w + (double)q.x * q.x + (double)q.y * q.y + (double)q.z * q.z);
    /* set s > 0 moves w by s LSB: distinct inputs for the caches, used for timing only */
    r.w = q16(q.w * k) + s; r.x = q16(q.x * k); r.y = q16(q.y * k); r.z = q16(q.z * k);
    return r;
}

void bk_fixmath_load(const bk_input *in)
{
    int s, i;
    for (s = 0; s < BK_FX_SETS; s++) {
        for (i = 0; i < BK_N; i++) {
            g_x[s][i] = q16(in->fx_unit[s][i]);
            g_ang[s][i] = q16(in->fx_ang[s][i]);
            g_ay[s][i] = q16(in->fx_y[s][i]);
            g_ax[s][i] = q16(in->fx_x[s][i]);
            g_qa[s][i] = to_fq(in->qa[i], 1.0, s);
            g_qb[s][i] = to_fq(in->qb[i], 1.0, s);
            /* halved so that qorient's Q1.30 (range [-2, 2)) holds it too; normalising is
             * scale-invariant, the reference is the same */
            g_qn[s][i] = to_fq(in->qn[i], 0.5, s);
        }
    }
    for (i = 0; i < BK_N; i++) {
        g_v[i][0] = q16(in->v[i].x); g_v[i][1] = q16(in->v[i].y); g_v[i][2] = q16(in->v[i].z);
        g_t[i] = q16(in->t[i]);
    }
}

void bk_fixmath_set(int set) { g_set = set; }

static void put_q(double d[4], fq q)
{
    d[0] = dbl(q.w); d[1] = dbl(q.x); d[2] = dbl(q.y); d[3] = dbl(q.z);
}

static void fetch(bk_output *o)
{
    int i;
    o->fx_set = g_set;
    for (i = 0; i < BK_N; i++) {
        o->s[i] = dbl(g_s[i]);
        if (g_kind == 0) { o->s_in[i][0] = dbl(g_x[g_set][i]); o->s_in[i][1] = 0; }
        else if (g_kind == 1) { o->s_in[i][0] = dbl(g_ang[g_set][i]); o->s_in[i][1] = 0; }
        else { o->s_in[i][0] = dbl(g_ax[g_set][i]); o->s_in[i][1] = dbl(g_ay[g_set][i]); }
        o->qd[i][0] = dbl(g_q[i].w); o->qd[i][1] = dbl(g_q[i].x);
        o->qd[i][2] = dbl(g_q[i].y); o->qd[i][3] = dbl(g_q[i].z);
        put_q(o->qin[0][i], g_qa[g_set][i]);
        put_q(o->qin[1][i], g_qb[g_set][i]);
        put_q(o->qin[2][i], g_qn[g_set][i]);
        o->vin[i][0] = dbl(g_v[i][0]); o->vin[i][1] = dbl(g_v[i][1]); o->vin[i][2] = dbl(g_v[i][2]);
        o->vd[i][0] = dbl(g_vo[i][0]); o->vd[i][1] = dbl(g_vo[i][1]); o->vd[i][2] = dbl(g_vo[i][2]);
        o->e[i][0] = dbl(g_e[i][0]); o->e[i][1] = dbl(g_e[i][1]); o->e[i][2] = dbl(g_e[i][2]);
    }
}

void bk_fixmath_fx_sqrt(void);
void bk_fixmath_fx_sqrt(void)
{
    int i;
    const fix16_t *x = g_x[g_set];
    g_kind = 0;
    for (i = 0; i < BK_N; i++) g_s[i] = fix16_sqrt(x[i]);
}

void bk_fixmath_fx_sin(void);
void bk_fixmath_fx_sin(void)
{
    int i;
    const fix16_t *a = g_ang[g_set];
    g_kind = 1;
    for (i = 0; i < BK_N; i++) g_s[i] = fix16_sin(a[i]);
}

void bk_fixmath_fx_cos(void);
void bk_fixmath_fx_cos(void)
{
    int i;
    const fix16_t *a = g_ang[g_set];
    g_kind = 1;
    for (i = 0; i < BK_N; i++) g_s[i] = fix16_cos(a[i]);
}

void bk_fixmath_fx_atan2(void);
void bk_fixmath_fx_atan2(void)
{
    int i;
    const fix16_t *y = g_ay[g_set], *x = g_ax[g_set];
    g_kind = 2;
    for (i = 0; i < BK_N; i++) g_s[i] = fix16_atan2(y[i], x[i]);
}

static fq fq_mul(fq a, fq b)
{
    fq r;
    r.w = fix16_mul(a.w, b.w) - fix16_mul(a.x, b.x) - fix16_mul(a.y, b.y) - fix16_mul(a.z, b.z);
    r.x = fix16_mul(a.w, b.x) + fix16_mul(a.x, b.w) + fix16_mul(a.y, b.z) - fix16_mul(a.z, b.y);
    r.y = fix16_mul(a.w, b.y) - fix16_mul(a.x, b.z) + fix16_mul(a.y, b.w) + fix16_mul(a.z, b.x);
    r.z = fix16_mul(a.w, b.z) + fix16_mul(a.x, b.y) - fix16_mul(a.y, b.x) + fix16_mul(a.z, b.w);
    return r;
}

static fq fq_normalize(fq q)
{
    fix16_t n = fix16_sqrt(fix16_mul(q.w, q.w) + fix16_mul(q.x, q.x) + fix16_mul(q.y, q.y) +
                           fix16_mul(q.z, q.z));
    fq r;
    r.w = fix16_div(q.w, n); r.x = fix16_div(q.x, n); r.y = fix16_div(q.y, n); r.z = fix16_div(q.z, n);
    return r;
}

void bk_fixmath_fx_quat_mul(void);
void bk_fixmath_fx_quat_mul(void)
{
    int i;
    const fq *a = g_qa[g_set], *b = g_qb[g_set];
    for (i = 0; i < BK_N; i++) g_q[i] = fq_mul(a[i], b[i]);
}

void bk_fixmath_fx_quat_normalize(void);
void bk_fixmath_fx_quat_normalize(void)
{
    int i;
    const fq *a = g_qn[g_set];
    for (i = 0; i < BK_N; i++) g_q[i] = fq_normalize(a[i]);
}

void bk_fixmath_fx_quat_rotate(void);
void bk_fixmath_fx_quat_rotate(void)
{
    int i;
    const fq *a = g_qa[g_set];
    for (i = 0; i < BK_N; i++) {
        fq q = a[i];
        const fix16_t *v = g_v[i];
        fix16_t tx = 2 * (fix16_mul(q.y, v[2]) - fix16_mul(q.z, v[1]));
        fix16_t ty = 2 * (fix16_mul(q.z, v[0]) - fix16_mul(q.x, v[2]));
        fix16_t tz = 2 * (fix16_mul(q.x, v[1]) - fix16_mul(q.y, v[0]));
        g_vo[i][0] = v[0] + fix16_mul(q.w, tx) + fix16_mul(q.y, tz) - fix16_mul(q.z, ty);
        g_vo[i][1] = v[1] + fix16_mul(q.w, ty) + fix16_mul(q.z, tx) - fix16_mul(q.x, tz);
        g_vo[i][2] = v[2] + fix16_mul(q.w, tz) + fix16_mul(q.x, ty) - fix16_mul(q.y, tx);
    }
}

/* Intrinsic ZYX (yaw, pitch, roll) of a unit quaternion, the usual closed form. */
void bk_fixmath_fx_to_euler_ZYX(void);
void bk_fixmath_fx_to_euler_ZYX(void)
{
    int i;
    const fq *a = g_qa[g_set];
    for (i = 0; i < BK_N; i++) {
        fq q = a[i];
        fix16_t sp = 2 * (fix16_mul(q.w, q.y) - fix16_mul(q.z, q.x));
        if (sp > fix16_one) sp = fix16_one;
        if (sp < -fix16_one) sp = -fix16_one;
        g_e[i][0] = fix16_atan2(2 * (fix16_mul(q.w, q.z) + fix16_mul(q.x, q.y)),
                                fix16_one - 2 * (fix16_mul(q.y, q.y) + fix16_mul(q.z, q.z)));
        g_e[i][1] = fix16_asin(sp);
        g_e[i][2] = fix16_atan2(2 * (fix16_mul(q.w, q.x) + fix16_mul(q.y, q.z)),
                                fix16_one - 2 * (fix16_mul(q.x, q.x) + fix16_mul(q.y, q.y)));
    }
}

void bk_fixmath_fx_slerp(void);
void bk_fixmath_fx_slerp(void)
{
    int i;
    const fq *qa = g_qa[g_set], *qb = g_qb[g_set];
    for (i = 0; i < BK_N; i++) {
        fq a = qa[i], b = qb[i], r;
        fix16_t t = g_t[i], th, s, wa, wb;
        fix16_t d = fix16_mul(a.w, b.w) + fix16_mul(a.x, b.x) + fix16_mul(a.y, b.y) + fix16_mul(a.z, b.z);
        if (d < 0) { d = -d; b.w = -b.w; b.x = -b.x; b.y = -b.y; b.z = -b.z; }
        if (d > fix16_one) d = fix16_one;
        th = fix16_acos(d);
        s = fix16_sin(th);
        if (s < 66) { /* < 0.001: linear weights */
            wa = fix16_one - t; wb = t;
        } else {
            wa = fix16_div(fix16_sin(fix16_mul(fix16_one - t, th)), s);
            wb = fix16_div(fix16_sin(fix16_mul(t, th)), s);
        }
        r.w = fix16_mul(wa, a.w) + fix16_mul(wb, b.w);
        r.x = fix16_mul(wa, a.x) + fix16_mul(wb, b.x);
        r.y = fix16_mul(wa, a.y) + fix16_mul(wb, b.y);
        r.z = fix16_mul(wa, a.z) + fix16_mul(wb, b.z);
        g_q[i] = r;
    }
}

const bk_kernel bk_fixmath_kernels[] = {
    { "libfixmath", "fx_sqrt", bk_fixmath_fx_sqrt, fetch },
    { "libfixmath", "fx_sin", bk_fixmath_fx_sin, fetch },
    { "libfixmath", "fx_cos", bk_fixmath_fx_cos, fetch },
    { "libfixmath", "fx_atan2", bk_fixmath_fx_atan2, fetch },
    { "libfixmath", "fx_quat_mul", bk_fixmath_fx_quat_mul, fetch },
    { "libfixmath", "fx_quat_normalize", bk_fixmath_fx_quat_normalize, fetch },
    { "libfixmath", "fx_quat_rotate", bk_fixmath_fx_quat_rotate, fetch },
    { "libfixmath", "fx_to_euler_ZYX", bk_fixmath_fx_to_euler_ZYX, fetch },
    { "libfixmath", "fx_slerp", bk_fixmath_fx_slerp, fetch },
    { 0, 0, 0, 0 }
};
