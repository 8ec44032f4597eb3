/*
 * fuzz/fuzz_common.h - shared helpers of the libFuzzer targets in fuzz/fuzz_*.c.
 *
 * Index:
 *   QO_FUZZ_FAIL(...)        report a property violation (default: message + abort(), which
 *                            libFuzzer records as a crash; tests/fuzz/test_fuzz_regress.c maps it to
 *                            a cmocka failure)
 *   QO_FUZZ_ENTRY            name of the target's entry point (default LLVMFuzzerTestOneInput;
 *                            the regress test renames it per target)
 *   qo_fz                    a cursor over the fuzzer's bytes
 *   qo_fz_u8 / _u32          raw bytes (0 when the input is exhausted)
 *   qo_fz_f32                a float: either raw bits or one of the edge values (NaN, +-Inf,
 *                            +-0, denormals, FLT_MIN/MAX, 1, pi, pi/2 ...), picked by a tag byte
 *   qo_fz_i32                an int32: raw bits or an edge value (INT32_MIN/MAX, 0, +-1, Q ONEs)
 *   qo_fz_quat / _vec3 / _mat3   structs of qo_fz_f32
 *   qo_fz_status_ok          1 when a value is one of the qo_status codes
 *   qo_fz_finite_quat ...    all components finite
 *   qo_fz_unit_quat          | |q| - 1 | <= tol
 *
 * Everything is `static inline` so the regress test can include several targets in one
 * translation unit without unused-function warnings.
 */
#ifndef QORIENT_FUZZ_COMMON_H
#define QORIENT_FUZZ_COMMON_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "qorient/status.h"
#include "qorient/types.h"

#ifndef QO_FUZZ_FAIL
#define QO_FUZZ_FAIL(...) do { \
        fprintf(stderr, "fuzz property violated at %s:%d: ", __FILE__, __LINE__); \
        fprintf(stderr, __VA_ARGS__); \
        fputc('\n', stderr); \
        abort(); \
    } while (0)
#endif

#define QO_FUZZ_CHECK(cond, ...) do { if (!(cond)) QO_FUZZ_FAIL(__VA_ARGS__); } while (0)

/* A cursor over the input bytes; reads past the end give zeros, so every input is valid. */
typedef struct qo_fz {
    const uint8_t *p;
    size_t n;
} qo_fz;

static inline qo_fz qo_fz_init(const uint8_t *data, size_t size)
{
    qo_fz f;
    f.p = data;
    f.n = size;
    return f;
}

static inline uint8_t qo_fz_u8(qo_fz *f)
{
    uint8_t v = 0;
    if (f->n > 0) {
        v = f->p[0];
        f->p++;
        f->n--;
    }
    return v;
}

static inline uint32_t qo_fz_u32(qo_fz *f)
{
    uint32_t v = 0;
    int i;
    for (i = 0; i < 4; i++) v |= (uint32_t)qo_fz_u8(f) << (8 * i);
    return v;
}

static inline float qo_fz_bits_f32(uint32_t u)
{
    float v;
    memcpy(&v, &u, sizeof v);
    return v;
}

/* Tag byte: < 0x80 raw 4 bytes follow; otherwise an edge value from the table (sign from bit 6
 * of the tag), so short inputs reach every edge and long ones reach every bit pattern. */
static inline float qo_fz_f32(qo_fz *f)
{
    uint8_t tag = qo_fz_u8(f);
    float v;
    if (tag < 0x80u) return qo_fz_bits_f32(qo_fz_u32(f));
    switch (tag & 0x1fu) {
    case 0: v = 0.0f; break;
    case 1: v = 1.0f; break;
    case 2: v = NAN; break;
    case 3: v = INFINITY; break;
    case 4: v = FLT_MAX; break;
    case 5: v = FLT_MIN; break;
    case 6: v = qo_fz_bits_f32(1u); break;              /* smallest denormal */
    case 7: v = qo_fz_bits_f32(0x007fffffu); break;     /* largest denormal */
    case 8: v = 3.14159274f; break;                     /* float nearest pi */
    case 9: v = 1.57079637f; break;                     /* float nearest pi/2 */
    case 10: v = 0.707106769f; break;                   /* 1/sqrt(2) */
    case 11: v = 0.5f; break;
    case 12: v = 1e-7f; break;
    case 13: v = 1.00000012f; break;                    /* 1 + 1 ulp */
    case 14: v = 0.99999994f; break;                    /* 1 - 1 ulp */
    case 15: v = 2.0f; break;
    case 16: v = 1e30f; break;
    case 17: v = 1e-30f; break;
    case 18: v = 6.28318548f; break;                    /* 2 pi */
    case 19: v = 1e-3f; break;
    case 20: v = 2e-6f; break;                          /* the default Euler lock band */
    case 21: v = 0.333333343f; break;
    case 22: v = 1.9999999f; break;                     /* top of Q1.30 */
    case 23: v = 7.99999952f; break;                    /* top of Q3.28 */
    case 24: v = 32767.998f; break;                     /* top of Q16.16 */
    case 25: v = 100.0f; break;
    case 26: v = 0.1f; break;
    case 27: v = 1e-4f; break;
    default: v = (float)(tag & 0x1fu) - 20.0f; break;   /* small integers 8..11 */
    }
    return (tag & 0x40u) ? -v : v;
}

static inline int32_t qo_fz_i32(qo_fz *f)
{
    uint8_t tag = qo_fz_u8(f);
    int32_t v;
    if (tag < 0x80u) {
        uint32_t u = qo_fz_u32(f);
        memcpy(&v, &u, sizeof v);
        return v;
    }
    switch (tag & 0x0fu) {
    case 0: return INT32_MIN;
    case 1: return INT32_MAX;
    case 2: v = 0; break;
    case 3: v = 1; break;
    case 4: v = 0x40000000; break;   /* 1.0 in Q1.30 */
    case 5: v = 0x10000000; break;   /* 1.0 in Q3.28 */
    case 6: v = 0x00010000; break;   /* 1.0 in Q16.16 */
    case 7: v = 843314857; break;    /* pi in Q3.28 */
    case 8: v = 421657428; break;    /* pi/2 in Q3.28 */
    case 9: v = 1686629713; break;   /* 2 pi in Q3.28 */
    case 10: v = 759250125; break;   /* 1/sqrt(2) in Q1.30 */
    case 11: v = 0x20000000; break;  /* 0.5 in Q1.30 */
    case 12: v = 0x7fff0000; break;
    case 13: v = 0x3fffffff; break;
    default: v = (int32_t)(tag & 0x3fu); break;
    }
    return (tag & 0x40u) ? -v : v;
}

static inline qo_quat_f32 qo_fz_quat(qo_fz *f)
{
    qo_quat_f32 q;
    q.w = qo_fz_f32(f); q.x = qo_fz_f32(f); q.y = qo_fz_f32(f); q.z = qo_fz_f32(f);
    return q;
}

static inline qo_vec3_f32 qo_fz_vec3(qo_fz *f)
{
    qo_vec3_f32 v;
    v.x = qo_fz_f32(f); v.y = qo_fz_f32(f); v.z = qo_fz_f32(f);
    return v;
}

static inline qo_mat3_f32 qo_fz_mat3(qo_fz *f)
{
    qo_mat3_f32 m;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) m.m[i][j] = qo_fz_f32(f);
    return m;
}

static inline int qo_fz_status_ok(qo_status st)
{
    return (int)st >= 0 && (int)st < (int)QO_STATUS_COUNT_;
}

static inline int qo_fz_finite_quat(qo_quat_f32 q)
{
    return isfinite(q.w) && isfinite(q.x) && isfinite(q.y) && isfinite(q.z);
}

static inline int qo_fz_finite_vec3(qo_vec3_f32 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static inline int qo_fz_finite_mat3(const qo_mat3_f32 *m)
{
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            if (!isfinite(m->m[i][j])) return 0;
    return 1;
}

static inline double qo_fz_norm_quat(qo_quat_f32 q)
{
    return sqrt((double)q.w * q.w + (double)q.x * q.x + (double)q.y * q.y + (double)q.z * q.z);
}

static inline int qo_fz_unit_quat(qo_quat_f32 q, double tol)
{
    return qo_fz_finite_quat(q) && fabs(qo_fz_norm_quat(q) - 1.0) <= tol;
}

static inline int qo_fz_same_quat(qo_quat_f32 a, qo_quat_f32 b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static inline int qo_fz_is_identity(qo_quat_f32 q)
{
    return q.w == 1.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f;
}

static inline int qo_fz_is_identity_mat3(const qo_mat3_f32 *m)
{
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            if (m->m[i][j] != (i == j ? 1.0f : 0.0f)) return 0;
    return 1;
}

/* Unit length tolerance used where a header promises a unit result ("unit to float rounding";
 * interp.h says 1e-6 measured). 1e-5 is ~80 ulp of 1: a real failure is far bigger. */
#define QO_FZ_UNIT_TOL 1e-5

#define QO_FZ_QFMT "(%.9g %.9g %.9g %.9g)"
#define QO_FZ_QARG(q) (double)(q).w, (double)(q).x, (double)(q).y, (double)(q).z

#endif /* QORIENT_FUZZ_COMMON_H */
