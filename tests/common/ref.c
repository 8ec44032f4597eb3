/* Double-precision reference math for tests and bench programs. See ref.h. */
#include "common/ref.h"

#include <math.h>

ref_quat ref_quat_from_f32(qo_quat_f32 q)
{
    ref_quat r;
    r.w = q.w; r.x = q.x; r.y = q.y; r.z = q.z;
    return r;
}

qo_quat_f32 ref_quat_to_f32(ref_quat q)
{
    qo_quat_f32 r;
    r.w = (float)q.w; r.x = (float)q.x; r.y = (float)q.y; r.z = (float)q.z;
    return r;
}

ref_vec3 ref_vec3_from_f32(qo_vec3_f32 v)
{
    ref_vec3 r;
    r.x = v.x; r.y = v.y; r.z = v.z;
    return r;
}

qo_vec3_f32 ref_vec3_to_f32(ref_vec3 v)
{
    qo_vec3_f32 r;
    r.x = (float)v.x; r.y = (float)v.y; r.z = (float)v.z;
    return r;
}

ref_mat3 ref_mat3_from_f32(const qo_mat3_f32 *m)
{
    ref_mat3 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i][j] = m->m[i][j];
    return r;
}

qo_mat3_f32 ref_mat3_to_f32(const ref_mat3 *m)
{
    qo_mat3_f32 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i][j] = (float)m->m[i][j];
    return r;
}

ref_quat ref_quat_mul(ref_quat a, ref_quat b)
{
    ref_quat r;
    r.w = a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z;
    r.x = a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y;
    r.y = a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x;
    r.z = a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w;
    return r;
}

double ref_quat_norm(ref_quat q)
{
    /* hypot chain: no overflow for float-range inputs, which is all the tests feed. */
    return hypot(hypot(q.w, q.x), hypot(q.y, q.z));
}

ref_quat ref_quat_normalize(ref_quat q)
{
    double n = ref_quat_norm(q);
    ref_quat r = { 1.0, 0.0, 0.0, 0.0 };
    if (n == 0.0) return r;
    r.w = q.w / n; r.x = q.x / n; r.y = q.y / n; r.z = q.z / n;
    return r;
}

ref_quat ref_quat_canonical(ref_quat q)
{
    int flip;
    if (q.w != 0.0) flip = q.w < 0.0;
    else if (q.x != 0.0) flip = q.x < 0.0;
    else if (q.y != 0.0) flip = q.y < 0.0;
    else flip = q.z < 0.0;
    if (flip) { q.w = -q.w; q.x = -q.x; q.y = -q.y; q.z = -q.z; }
    return q;
}

ref_vec3 ref_quat_rotate(ref_quat q, ref_vec3 v)
{
    ref_quat p = { 0.0, v.x, v.y, v.z };
    ref_quat c = { q.w, -q.x, -q.y, -q.z };
    double n2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
    ref_quat r = ref_quat_mul(ref_quat_mul(q, p), c);
    ref_vec3 o;
    o.x = r.x / n2; o.y = r.y / n2; o.z = r.z / n2;
    return o;
}

ref_mat3 ref_quat_to_mat3(ref_quat q)
{
    /* Column j is the image of basis vector e_j: built from ref_quat_rotate rather than the
     * closed form, so it shares no formula with the code under test. */
    ref_mat3 m;
    int i, j;
    for (j = 0; j < 3; j++) {
        ref_vec3 e = { j == 0, j == 1, j == 2 };
        ref_vec3 c = ref_quat_rotate(q, e);
        double col[3];
        col[0] = c.x; col[1] = c.y; col[2] = c.z;
        for (i = 0; i < 3; i++) m.m[i][j] = col[i];
    }
    return m;
}

ref_quat ref_mat3_to_quat(const ref_mat3 *mm)
{
    /* 4w^2 = 1 + t, 4x^2 = 1 + m00 - m11 - m22, ...: take the largest as the pivot. */
    const double (*m)[3] = mm->m;
    double d[4];
    ref_quat q;
    int k = 0, i;
    d[0] = 1.0 + m[0][0] + m[1][1] + m[2][2];
    d[1] = 1.0 + m[0][0] - m[1][1] - m[2][2];
    d[2] = 1.0 - m[0][0] + m[1][1] - m[2][2];
    d[3] = 1.0 - m[0][0] - m[1][1] + m[2][2];
    for (i = 1; i < 4; i++)
        if (d[i] > d[k]) k = i;
    {
        double r = sqrt(d[k]), s = 0.5 / r;
        double wx = (m[2][1] - m[1][2]) * s, wy = (m[0][2] - m[2][0]) * s,
               wz = (m[1][0] - m[0][1]) * s;
        double xy = (m[0][1] + m[1][0]) * s, xz = (m[0][2] + m[2][0]) * s,
               yz = (m[1][2] + m[2][1]) * s;
        switch (k) {
        case 0: q.w = 0.5 * r; q.x = wx; q.y = wy; q.z = wz; break;
        case 1: q.w = wx; q.x = 0.5 * r; q.y = xy; q.z = xz; break;
        case 2: q.w = wy; q.x = xy; q.y = 0.5 * r; q.z = yz; break;
        default: q.w = wz; q.x = xz; q.y = yz; q.z = 0.5 * r; break;
        }
    }
    return ref_quat_canonical(ref_quat_normalize(q));
}

ref_quat ref_quat_from_axis_angle(ref_vec3 a, double angle)
{
    double n = sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    double s = sin(0.5 * angle) / n;
    ref_quat q;
    q.w = cos(0.5 * angle); q.x = s * a.x; q.y = s * a.y; q.z = s * a.z;
    return q;
}

double ref_quat_angle_between(ref_quat a, ref_quat b)
{
    ref_quat c, d;
    a = ref_quat_normalize(a);
    b = ref_quat_normalize(b);
    c.w = a.w; c.x = -a.x; c.y = -a.y; c.z = -a.z;
    d = ref_quat_mul(c, b);
    return 2.0 * atan2(sqrt(d.x * d.x + d.y * d.y + d.z * d.z), fabs(d.w));
}

double ref_mat3_rotation_distance(const ref_mat3 *a, const ref_mat3 *b)
{
    ref_mat3 e;
    double sx, sy, sz, c;
    int i, j, k;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            e.m[i][j] = 0.0;
            for (k = 0; k < 3; k++) e.m[i][j] += a->m[k][i] * b->m[k][j];
        }
    /* For E = rotation by t about n: E - E^T = 2 sin(t) [n]x, trace E = 1 + 2 cos t. */
    sx = 0.5 * (e.m[2][1] - e.m[1][2]);
    sy = 0.5 * (e.m[0][2] - e.m[2][0]);
    sz = 0.5 * (e.m[1][0] - e.m[0][1]);
    c = 0.5 * (e.m[0][0] + e.m[1][1] + e.m[2][2] - 1.0);
    return atan2(sqrt(sx * sx + sy * sy + sz * sz), c);
}

ref_mat3 ref_mat3_mul(const ref_mat3 *a, const ref_mat3 *b)
{
    ref_mat3 r;
    int i, j, k;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            r.m[i][j] = 0.0;
            for (k = 0; k < 3; k++) r.m[i][j] += a->m[i][k] * b->m[k][j];
        }
    return r;
}

double ref_mat3_det(const ref_mat3 *m)
{
    const double (*a)[3] = m->m;
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
         - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
         + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

/* Cyclic Jacobi eigen-decomposition of a symmetric 3x3 matrix: a = v diag(l) v^T. */
static void jacobi_sym3(ref_mat3 a, double l[3], ref_mat3 *v)
{
    int sweep, p, q, k;
    for (p = 0; p < 3; p++)
        for (q = 0; q < 3; q++) v->m[p][q] = (p == q);
    for (sweep = 0; sweep < 50; sweep++) {
        double off = a.m[0][1] * a.m[0][1] + a.m[0][2] * a.m[0][2] + a.m[1][2] * a.m[1][2];
        double diag = a.m[0][0] * a.m[0][0] + a.m[1][1] * a.m[1][1] + a.m[2][2] * a.m[2][2];
        if (off <= 1e-40 * diag) break;
        for (p = 0; p < 2; p++) {
            for (q = p + 1; q < 3; q++) {
                double apq = a.m[p][q], theta, t, c, s;
                if (apq == 0.0) continue;
                theta = (a.m[q][q] - a.m[p][p]) / (2.0 * apq);
                t = (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                c = 1.0 / sqrt(t * t + 1.0);
                s = t * c;
                /* a <- J^T a J, v <- v J with the Givens rotation J in the (p, q) plane. */
                for (k = 0; k < 3; k++) {
                    double akp = a.m[k][p], akq = a.m[k][q];
                    a.m[k][p] = c * akp - s * akq;
                    a.m[k][q] = s * akp + c * akq;
                }
                for (k = 0; k < 3; k++) {
                    double apk = a.m[p][k], aqk = a.m[q][k];
                    a.m[p][k] = c * apk - s * aqk;
                    a.m[q][k] = s * apk + c * aqk;
                }
                for (k = 0; k < 3; k++) {
                    double vkp = v->m[k][p], vkq = v->m[k][q];
                    v->m[k][p] = c * vkp - s * vkq;
                    v->m[k][q] = s * vkp + c * vkq;
                }
            }
        }
    }
    for (k = 0; k < 3; k++) l[k] = a.m[k][k];
}

ref_mat3 ref_mat3_nearest_rotation(const ref_mat3 *m)
{
    ref_mat3 mtm, v, sinv, r;
    double l[3];
    int i, j, k;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            mtm.m[i][j] = 0.0;
            for (k = 0; k < 3; k++) mtm.m[i][j] += m->m[k][i] * m->m[k][j];
        }
    jacobi_sym3(mtm, l, &v);
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            sinv.m[i][j] = 0.0;
            for (k = 0; k < 3; k++) sinv.m[i][j] += v.m[i][k] * v.m[j][k] / sqrt(l[k]);
        }
    r = ref_mat3_mul(m, &sinv);
    return r;
}

uint64_t ref_splitmix64(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

uint64_t ref_rng_next(ref_rng *r) { return ref_splitmix64(&r->s); }

double ref_unit_from_bits(uint64_t bits) { return (double)(bits >> 11) * (1.0 / 9007199254740992.0); }

double ref_rng_unit(ref_rng *r) { return ref_unit_from_bits(ref_rng_next(r)); }

double ref_rng_range(ref_rng *r, double lo, double hi)
{
    return lo + (hi - lo) * ref_rng_unit(r);
}

ref_quat ref_rng_quat(ref_rng *r)
{
    double u1 = ref_rng_unit(r), u2 = ref_rng_unit(r), u3 = ref_rng_unit(r);
    double a = sqrt(1.0 - u1), b = sqrt(u1);
    ref_quat q;
    q.w = a * sin(2.0 * REF_PI * u2);
    q.x = a * cos(2.0 * REF_PI * u2);
    q.y = b * sin(2.0 * REF_PI * u3);
    q.z = b * cos(2.0 * REF_PI * u3);
    return q;
}

ref_quat ref_quat_axis(char axis, double angle)
{
    ref_quat q = { 0.0, 0.0, 0.0, 0.0 };
    double s = sin(angle / 2);
    q.w = cos(angle / 2);
    if (axis == 'x' || axis == 'X') q.x = s;
    else if (axis == 'y' || axis == 'Y') q.y = s;
    else q.z = s;
    return q;
}

ref_quat ref_quat_from_euler(const char *n, double a1, double a2, double a3)
{
    ref_quat q1 = ref_quat_axis(n[0], a1), q2 = ref_quat_axis(n[1], a2), q3 = ref_quat_axis(n[2], a3);
    if (n[0] >= 'X' && n[0] <= 'Z') return ref_quat_mul(ref_quat_mul(q1, q2), q3);
    return ref_quat_mul(q3, ref_quat_mul(q2, q1));
}

const char *const ref_euler_names[REF_EULER_SEQS] = {
    "xyz", "xzy", "yxz", "yzx", "zxy", "zyx", "xyx", "xzx", "yxy", "yzy", "zxz", "zyz",
    "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ",
};

int ref_euler_proper(int seq) { return ref_euler_names[seq][0] == ref_euler_names[seq][2]; }

ref_quat ref_quat_from_q30(qo_quat_q30 q)
{
    ref_quat r;
    r.w = q.w / REF_Q30; r.x = q.x / REF_Q30; r.y = q.y / REF_Q30; r.z = q.z / REF_Q30;
    return r;
}

int32_t ref_to_fixed(double v, double scale)
{
    double r = floor(v * scale + 0.5);
    if (r > 2147483647.0) r = 2147483647.0;
    if (r < -2147483648.0) r = -2147483648.0;
    return (int32_t)r;
}

qo_quat_q30 ref_quat_to_q30(ref_quat q)
{
    qo_quat_q30 r;
    r.w = ref_to_fixed(q.w, REF_Q30); r.x = ref_to_fixed(q.x, REF_Q30);
    r.y = ref_to_fixed(q.y, REF_Q30); r.z = ref_to_fixed(q.z, REF_Q30);
    return r;
}

double ref_quat_err_lsb_q30(qo_quat_q30 got, ref_quat want)
{
    double e = fabs(got.w - want.w * REF_Q30), t;
    t = fabs(got.x - want.x * REF_Q30); if (t > e) e = t;
    t = fabs(got.y - want.y * REF_Q30); if (t > e) e = t;
    t = fabs(got.z - want.z * REF_Q30); if (t > e) e = t;
    return e;
}
