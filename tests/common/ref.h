/*
 * tests/common/ref.h - double-precision reference math and a deterministic PRNG for tests and
 * bench programs. Written independently of the library (no qorient function is called), so a
 * test compares the float32 code against something it did not compute itself.
 *
 * Conventions are the library's (qorient/types.h): quaternions scalar-first, Hamilton, active
 * rotations v' = q v q*, matrices row-major acting on column vectors, radians.
 *
 * Index:
 *   ref_quat, ref_vec3, ref_mat3          double twins of the float32 types
 *   ref_quat_from_f32 / ref_quat_to_f32   (and vec3, mat3) type conversions
 *   ref_quat_mul                          Hamilton product
 *   ref_quat_norm / ref_quat_normalize    length / unit quaternion (zero -> identity)
 *   ref_quat_canonical                    sign with w >= 0 (ties: first non-zero of x, y, z > 0)
 *   ref_quat_rotate                       q v q* by explicit quaternion products
 *   ref_quat_to_mat3                      rotation matrix of a (normalised) quaternion
 *   ref_mat3_to_quat                      canonical quaternion of a rotation matrix
 *   ref_quat_from_axis_angle              (cos a/2, sin a/2 * axis/|axis|)
 *   ref_quat_angle_between                rotation angle between two orientations, [0, pi]
 *   ref_mat3_rotation_distance            rotation angle of A^T B for two (near-)rotation matrices
 *   ref_mat3_mul, ref_mat3_det            matrix product, determinant
 *   ref_mat3_nearest_rotation             polar factor M (M^T M)^-1/2 via a Jacobi eigensolver
 *   ref_quat_axis                         elementary rotation about x, y or z
 *   ref_quat_from_euler                   Euler angles by products of elementary rotations
 *   ref_euler_names, ref_euler_proper     the 24 conventions by name (qo_euler_seq order), and
 *                                         whether one is proper (first axis = last axis)
 *   ref_quat_from_q30 / ref_quat_to_q30   exact value of a Q1.30 quaternion / rounded to Q1.30
 *   REF_Q30, REF_Q28, REF_Q16             one in Q1.30, Q3.28, Q16.16 (2^30, 2^28, 2^16)
 *   ref_to_fixed                          a double rounded to a fixed-point format, saturating
 *   ref_quat_err_lsb_q30                  largest component error of a Q1.30 result, in LSB
 *   ref_rng / ref_rng_next / ref_rng_unit / ref_rng_range   splitmix64 PRNG
 *   ref_splitmix64 / ref_unit_from_bits    the same on a bare uint64_t state
 *   ref_rng_quat                          uniform random unit quaternion (Shoemake)
 */
#ifndef QORIENT_TESTS_REF_H
#define QORIENT_TESTS_REF_H

#include <stdint.h>

#include "qorient/types.h"

typedef struct ref_quat { double w, x, y, z; } ref_quat;
typedef struct ref_vec3 { double x, y, z; } ref_vec3;
typedef struct ref_mat3 { double m[3][3]; } ref_mat3;

#define REF_PI 3.14159265358979323846
/* The scale of a fixed-point format: one in Q1.30 (unit values), Q3.28 (angles, rad),
 * Q16.16 (durations, s). */
#define REF_Q30 1073741824.0
#define REF_Q28 268435456.0
#define REF_Q16 65536.0

ref_quat ref_quat_from_f32(qo_quat_f32 q);
qo_quat_f32 ref_quat_to_f32(ref_quat q);
ref_vec3 ref_vec3_from_f32(qo_vec3_f32 v);
qo_vec3_f32 ref_vec3_to_f32(ref_vec3 v);
ref_mat3 ref_mat3_from_f32(const qo_mat3_f32 *m);
qo_mat3_f32 ref_mat3_to_f32(const ref_mat3 *m);

ref_quat ref_quat_mul(ref_quat a, ref_quat b);
double ref_quat_norm(ref_quat q);
/* Unit quaternion; the zero quaternion gives the identity. */
ref_quat ref_quat_normalize(ref_quat q);
ref_quat ref_quat_canonical(ref_quat q);
/* q (0, v) conj(q) / |q|^2 (so q need not be unit). */
ref_vec3 ref_quat_rotate(ref_quat q, ref_vec3 v);
/* Matrix of q/|q|. */
ref_mat3 ref_quat_to_mat3(ref_quat q);
/* Canonical unit quaternion of an (assumed) rotation matrix: Shepperd pivot in double. */
ref_quat ref_mat3_to_quat(const ref_mat3 *m);
ref_quat ref_quat_from_axis_angle(ref_vec3 axis, double angle);
/* Angle in [0, pi] of the rotation taking a to b (both normalised first; sign-insensitive). */
double ref_quat_angle_between(ref_quat a, ref_quat b);
/* Angle in [0, pi] of the rotation A^T B, as atan2(|skew part|, (trace - 1)/2): accurate for
 * tiny angles; residual non-orthogonality of A or B shows up as a (small) angle. */
double ref_mat3_rotation_distance(const ref_mat3 *a, const ref_mat3 *b);
ref_mat3 ref_mat3_mul(const ref_mat3 *a, const ref_mat3 *b);
double ref_mat3_det(const ref_mat3 *m);
/* Orthogonal polar factor of m (nearest orthogonal matrix in the Frobenius norm), computed as
 * M V diag(1/sqrt(l)) V^T from the Jacobi eigen-decomposition M^T M = V diag(l) V^T: an
 * algorithm independent of the library's Newton iteration. m must be non-singular. */
ref_mat3 ref_mat3_nearest_rotation(const ref_mat3 *m);

/* Rotation by angle (rad) about the axis named by a letter: 'x'/'X', 'y'/'Y', anything else z. */
ref_quat ref_quat_axis(char axis, double angle);
/* Rotation of the Euler angles (rad) a1, a2, a3 of the convention named by three letters, the
 * library's names (qorient/euler.h): lower case extrinsic "abc", R = R_c(a3) R_b(a2) R_a(a1);
 * upper case intrinsic "ABC", R = R_A(a1) R_B(a2) R_C(a3). Built from the letters, so it shares
 * no table with the code under test. */
ref_quat ref_quat_from_euler(const char *seq, double a1, double a2, double a3);
/* The 24 conventions by the library's names, indexed by qo_euler_seq (the enum order is ABI):
 * a copy kept here, with the axes derived from the letters, so that a reference built from it
 * shares no table with the code under test. */
#define REF_EULER_SEQS 24
extern const char *const ref_euler_names[REF_EULER_SEQS];
/* 1 if convention seq (0 ... 23) is proper (its first and last axes are the same: zxz, XYX,
 * ...), 0 if it is Tait-Bryan (xyz, ZYX, ...). */
int ref_euler_proper(int seq);
/* Exact value of a Q1.30 quaternion (not normalised). */
ref_quat ref_quat_from_q30(qo_quat_q30 q);
/* v * scale rounded half up, saturated to int32 (scale 2^30 gives Q1.30, 2^28 Q3.28). */
int32_t ref_to_fixed(double v, double scale);
/* Each component through ref_to_fixed(., 2^30). */
qo_quat_q30 ref_quat_to_q30(ref_quat q);
/* Largest |got - want| over the four components, in LSB of Q1.30. */
double ref_quat_err_lsb_q30(qo_quat_q30 got, ref_quat want);

/* splitmix64 (Vigna): a 64-bit state, every seed is fine, identical on every platform. */
typedef struct ref_rng { uint64_t s; } ref_rng;
uint64_t ref_rng_next(ref_rng *r);
/* The same step on a bare state word (for files that keep their state as a uint64_t). */
uint64_t ref_splitmix64(uint64_t *state);
/* The top 53 bits of a 64-bit draw as a uniform double in [0, 1). */
double ref_unit_from_bits(uint64_t bits);
/* Uniform double in [0, 1) with 53 random bits. */
double ref_rng_unit(ref_rng *r);
/* Uniform double in [lo, hi). */
double ref_rng_range(ref_rng *r, double lo, double hi);
/* Uniform random unit quaternion on S^3 (Shoemake's subgroup algorithm), any sign. */
ref_quat ref_rng_quat(ref_rng *r);

#endif /* QORIENT_TESTS_REF_H */
