/*
 * qorient/types.h - the small value types shared by every module, float32 and fixed point.
 *
 * Conventions, stated once for the whole library:
 *   - Quaternions are scalar-first (w, x, y, z), Hamilton algebra (i*j = k), and describe
 *     ACTIVE rotations of vectors in a right-handed frame: v' = q v q*. A unit quaternion q and
 *     -q are the same rotation; functions that return a quaternion say which sign they pick.
 *   - Matrices are 3x3, row-major: m[row][col], and rotate column vectors: v' = M v.
 *     A quaternion q and the matrix built from it rotate a vector the same way.
 *   - Angles are radians unless a function says otherwise.
 *   - Values are passed and returned by value; nothing here owns memory.
 *
 * Fixed-point formats (the `_q30` / `_q28` / `_q16` suffix names the format):
 *   - Q1.30  (int32_t, value = raw / 2^30, range [-2, 2)):  unit quaternion, unit vector and
 *            rotation-matrix components, interpolation parameter t. LSB = 9.3e-10.
 *   - Q3.28  (int32_t, value = raw / 2^28, range [-8, 8)):  angles in radians (+-pi fits with
 *            headroom for sums of two angles). LSB = 3.7e-9 rad.
 *   - Q16.16 (int32_t, value = raw / 2^16, range [-32768, 32768)): user units - joint positions,
 *            times in seconds, rates. LSB = 1.5e-5.
 */
#ifndef QORIENT_TYPES_H
#define QORIENT_TYPES_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- float32 ------------------------------------------------------------------------- */

/* Quaternion w + x i + y j + z k, scalar first. Unit length when it represents a rotation. */
typedef struct qo_quat_f32 { float w, x, y, z; } qo_quat_f32;

/* 3-vector in a right-handed frame. */
typedef struct qo_vec3_f32 { float x, y, z; } qo_vec3_f32;

/* 3x3 matrix, row-major m[row][col], acting on column vectors. */
typedef struct qo_mat3_f32 { float m[3][3]; } qo_mat3_f32;

/* ---- fixed point --------------------------------------------------------------------- */

/* Q1.30 raw value (see the format table above). */
typedef int32_t qo_q30;
/* Q3.28 raw value, radians. */
typedef int32_t qo_q28;
/* Q16.16 raw value, user units. */
typedef int32_t qo_q16;

#define QO_Q30_ONE ((qo_q30)0x40000000)   /* 1.0 in Q1.30 */
#define QO_Q28_ONE ((qo_q28)0x10000000)   /* 1.0 in Q3.28 */
#define QO_Q16_ONE ((qo_q16)0x00010000)   /* 1.0 in Q16.16 */

/* pi, pi/2 and 2pi in Q3.28, each rounded to nearest (so 2*HALF_PI == PI - 1 LSB, and
 * TWO_PI == 2*PI - 1 LSB: use the constant you mean). */
#define QO_Q28_PI      ((qo_q28)843314857)   /* 3.14159265 */
#define QO_Q28_HALF_PI ((qo_q28)421657428)   /* 1.57079633 */
#define QO_Q28_TWO_PI  ((qo_q28)1686629713)  /* 6.28318531 */

/* Quaternion with Q1.30 components, scalar first; same conventions as qo_quat_f32. */
typedef struct qo_quat_q30 { qo_q30 w, x, y, z; } qo_quat_q30;

/* 3-vector with Q1.30 components (unit and sub-unit vectors: directions, rotated directions). */
typedef struct qo_vec3_q30 { qo_q30 x, y, z; } qo_vec3_q30;

/* 3-vector with Q3.28 components (rotation vectors in radians, angular rates times dt). */
typedef struct qo_vec3_q28 { qo_q28 x, y, z; } qo_vec3_q28;

/* 3x3 matrix with Q1.30 components, row-major, acting on column vectors. */
typedef struct qo_mat3_q30 { qo_q30 m[3][3]; } qo_mat3_q30;

/* 3-vector with Q16.16 components (rates in user units per second, e.g. rad/s: range
 * [-32768, 32768), LSB 1.5e-5). */
typedef struct qo_vec3_q16 { qo_q16 x, y, z; } qo_vec3_q16;

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_TYPES_H */
