/*
 * accuracy_convert: worst and mean rotation error, in radians, of every float32 conversion of
 * qorient/convert.h in both directions, over fixed-seed uniformly random rotations plus an edge
 * table (identity, 180 degrees about axes and diagonals, each Shepperd pivot, tiny angles).
 *
 * The error of a result is the angle of the rotation between it and a double-precision
 * reference computed from the SAME float32 input (tests/common/ref.c), measured in double, so
 * only the conversion's own error is counted, not the rounding of the input.
 *
 * Run: make figures   (or ./build/bench/accuracy_convert [N])
 * Exit status 1 if any worst error exceeds 1e-6 rad (float32 round-off is ~1e-7 rad).
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "qorient/convert.h"
#include "qorient/quat.h"

/* the double reference, linked from tests/common/ref.c */
#include "common/ref.h"

#define LIMIT_RAD 1e-6

enum {
    C_Q2M, C_M2Q, C_M2Q_TRUSTED, C_M2Q_DRIFT, C_M2Q_ORTHO_EXACT, C_M2Q_ORTHO_NOISY, C_ORTHO_NOISY, C_AA2Q, C_Q2AA,
    C_RV2Q, C_Q2RV, C_Q2M2Q, C_COUNT
};
static const char *const names[C_COUNT] = {
    "mat3_from_quat", "mat3_to_quat", "mat3_to_quat_trusted", "mat3_to_quat (drift 1e-5)",
    "mat3_to_quat_ortho (rotation)",
    "mat3_to_quat_ortho (noise 1e-2)", "mat3_orthonormalize (noise 1e-2)",
    "axis_angle_to_quat", "axis_angle_from_quat", "rotvec_to_quat", "rotvec_from_quat",
    "quat -> mat3 -> quat",
};

struct stat { double worst, sum; long n, failed; };
static struct stat st[C_COUNT];

static void record(int c, double err, qo_status s)
{
    if (s != QO_OK) {
        st[c].failed++;
        return;
    }
    if (!(err <= st[c].worst)) st[c].worst = err; /* NaN counts as worst */
    st[c].sum += err;
    st[c].n++;
}

/* Every conversion on one rotation q (any sign, unit in double). */
static void measure(ref_quat rq, ref_rng *rng)
{
    qo_quat_f32 q = ref_quat_to_f32(rq), q2;
    ref_quat qd = ref_quat_from_f32(q);
    ref_mat3 rm = ref_quat_to_mat3(qd), rmd, near;
    qo_mat3_f32 m, mf, mn;
    qo_vec3_f32 ax, rv;
    float ang;
    qo_status s;
    int i, j;

    /* quat -> mat3: vs the double matrix of the same float q. */
    s = qo_mat3_from_quat_f32(q, &m);
    rmd = ref_mat3_from_f32(&m);
    record(C_Q2M, ref_mat3_rotation_distance(&rm, &rmd), s);

    /* mat3 -> quat: the input is the double matrix rounded to float; reference is the nearest
     * rotation of that float matrix. */
    mf = ref_mat3_to_f32(&rm);
    rmd = ref_mat3_from_f32(&mf);
    near = ref_mat3_nearest_rotation(&rmd);
    s = qo_mat3_to_quat_f32(&mf, &q2);
    record(C_M2Q, ref_quat_angle_between(ref_quat_from_f32(q2), ref_mat3_to_quat(&near)), s);
    s = qo_mat3_to_quat_trusted_f32(&mf, &q2);
    record(C_M2Q_TRUSTED, ref_quat_angle_between(ref_quat_from_f32(q2), ref_mat3_to_quat(&near)), s);
    s = qo_mat3_to_quat_ortho_f32(&mf, &q2);
    record(C_M2Q_ORTHO_EXACT, ref_quat_angle_between(ref_quat_from_f32(q2), ref_mat3_to_quat(&near)), s);

    /* Slightly drifted matrix (accepted by the strict path): vs its nearest rotation. */
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) mn.m[i][j] = mf.m[i][j] + (float)ref_rng_range(rng, -1e-5, 1e-5);
    rmd = ref_mat3_from_f32(&mn);
    near = ref_mat3_nearest_rotation(&rmd);
    s = qo_mat3_to_quat_f32(&mn, &q2);
    record(C_M2Q_DRIFT, ref_quat_angle_between(ref_quat_from_f32(q2), ref_mat3_to_quat(&near)), s);

    /* Drifted matrix: uniform noise of 1e-2 on every entry, repaired by the ortho path. */
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) mn.m[i][j] = mf.m[i][j] + (float)ref_rng_range(rng, -1e-2, 1e-2);
    rmd = ref_mat3_from_f32(&mn);
    near = ref_mat3_nearest_rotation(&rmd);
    s = qo_mat3_to_quat_ortho_f32(&mn, &q2);
    record(C_M2Q_ORTHO_NOISY, ref_quat_angle_between(ref_quat_from_f32(q2), ref_mat3_to_quat(&near)), s);
    s = qo_mat3_orthonormalize_f32(&mn, &m);
    rmd = ref_mat3_from_f32(&m);
    record(C_ORTHO_NOISY, ref_mat3_rotation_distance(&near, &rmd), s);

    /* quat -> axis-angle and quat -> rotvec: the rotation the float result describes, built
     * in double, vs the input. */
    s = qo_axis_angle_from_quat_f32(q, &ax, &ang);
    record(C_Q2AA, ref_quat_angle_between(ref_quat_from_axis_angle(ref_vec3_from_f32(ax), ang), qd), s);
    s = qo_rotvec_from_quat_f32(q, &rv);
    {
        ref_vec3 r = ref_vec3_from_f32(rv);
        double th = sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
        ref_quat back = { 1.0, 0.0, 0.0, 0.0 };
        if (th > 0.0) back = ref_quat_from_axis_angle(r, th);
        record(C_Q2RV, ref_quat_angle_between(back, qd), s);
    }

    /* axis-angle -> quat with a non-unit axis of random length and angle in [-2pi, 2pi]. */
    {
        double len = pow(10.0, ref_rng_range(rng, -3.0, 3.0));
        ref_vec3 a;
        /* one draw per statement: the order of an initializer list's calls is unspecified */
        a.x = ref_rng_range(rng, -1, 1) * len;
        a.y = ref_rng_range(rng, -1, 1) * len;
        a.z = ref_rng_range(rng, -1, 1) * len;
        qo_vec3_f32 af = ref_vec3_to_f32(a);
        float an = (float)ref_rng_range(rng, -2.0 * REF_PI, 2.0 * REF_PI);
        s = qo_axis_angle_to_quat_f32(af, an, &q2);
        record(C_AA2Q, ref_quat_angle_between(ref_quat_from_f32(q2),
                                              ref_quat_from_axis_angle(ref_vec3_from_f32(af), an)), s);
    }
    /* rotvec -> quat: the rotation vector of q (|rv| <= pi), and a log-uniform tiny one. */
    {
        ref_vec3 r = ref_vec3_from_f32(rv);
        double th = sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
        ref_quat e = { 1.0, 0.0, 0.0, 0.0 };
        if (th > 0.0) e = ref_quat_from_axis_angle(r, th);
        s = qo_rotvec_to_quat_f32(rv, &q2);
        record(C_RV2Q, ref_quat_angle_between(ref_quat_from_f32(q2), e), s);
        th = pow(10.0, ref_rng_range(rng, -12.0, -1.0));
        r.x *= th; r.y *= th; r.z *= th;
        rv = ref_vec3_to_f32(r);
        r = ref_vec3_from_f32(rv);
        th = sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
        if (th > 0.0) e = ref_quat_from_axis_angle(r, th);
        s = qo_rotvec_to_quat_f32(rv, &q2);
        record(C_RV2Q, ref_quat_angle_between(ref_quat_from_f32(q2), e), s);
    }

    /* Round trip through the matrix. */
    s = qo_mat3_from_quat_f32(q, &m);
    if (s == QO_OK) s = qo_mat3_to_quat_f32(&m, &q2);
    record(C_Q2M2Q, ref_quat_angle_between(ref_quat_from_f32(q2), qd), s);
}

/* Edge table: (axis, degrees). */
static const double edges[][4] = {
    { 1, 0, 0, 0 }, { 1, 0, 0, 180 }, { 0, 1, 0, 180 }, { 0, 0, 1, 180 }, { -1, 0, 0, 180 },
    { 1, 1, 0, 180 }, { 1, 0, 1, 180 }, { 0, 1, 1, 180 }, { 1, -1, 0, 180 }, { 1, 1, 1, 180 },
    { 1, -1, 1, 180 }, { 1, 1, 1, 179.999 }, { 1, 2, 3, 180.001 }, { 1, 1, 1, 120 },
    { 1, 2, 3, 10 }, { 1, 0.1, 0.1, 170 }, { 0.1, 1, 0.1, 170 }, { 0.1, 0.1, 1, 170 },
    { 0, 0, 1, 90 }, { 3, -1, 2, 5.7e-5 }, { 0, 1, 0, 1e-30 }, { 1, 2, 3, 359.9 },
};

int main(int argc, char **argv)
{
    long n_random = 100000, k;
    ref_rng rng = { 20261126u };
    size_t e;
    int c, bad = 0;
    if (argc > 1) n_random = strtol(argv[1], NULL, 10);
    if (n_random < 1) n_random = 1;
    for (e = 0; e < sizeof edges / sizeof edges[0]; e++) {
        ref_vec3 a = { edges[e][0], edges[e][1], edges[e][2] };
        ref_quat q = ref_quat_from_axis_angle(a, edges[e][3] * REF_PI / 180.0);
        ref_quat nq = { -q.w, -q.x, -q.y, -q.z };
        measure(q, &rng);
        measure(nq, &rng);
    }
    for (k = 0; k < n_random; k++) measure(ref_rng_quat(&rng), &rng);

    printf("accuracy_convert: %ld random rotations (splitmix64 seed 20261126) + %d edge cases,\n"
           "rotation error in radians vs a double reference of the same float32 input\n\n",
           n_random, (int)(2 * (sizeof edges / sizeof edges[0])));
    printf("%-36s %12s %12s %8s %7s\n", "conversion", "worst_rad", "mean_rad", "n", "failed");
    for (c = 0; c < C_COUNT; c++) {
        double mean = st[c].n ? st[c].sum / (double)st[c].n : 0.0;
        int over = !(st[c].worst <= LIMIT_RAD) || st[c].failed != 0;
        printf("%-36s %12.3e %12.3e %8ld %7ld%s\n", names[c], st[c].worst, mean, st[c].n,
               st[c].failed, over ? "  OVER LIMIT" : "");
        bad |= over;
    }
    printf("\nlimit %.0e rad: %s\n", LIMIT_RAD, bad ? "EXCEEDED" : "all within");
    return bad ? 1 : 0;
}
