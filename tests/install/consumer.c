/*
 * tests/install/consumer.c - a program outside the tree, built by `make install-check` against
 * the INSTALLED headers and library through pkg-config (qorient.pc), once statically and once
 * against libqorient.so. It uses the float32 and the fixed-point core and checks the results
 * against double-precision math of its own, so a broken or mismatched installed library fails.
 * Prints one line and exits 0 when everything holds, else names the failed check and exits 1.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "qorient/qorient.h"
#include "qorient/euler_fx.h"
#include "qorient/spline.h"
#include "qorient/spline_fx.h"

static int failures;

static void check(int ok, const char *what, double got, double want)
{
    if (!ok) {
        printf("consumer: FAIL: %s: got %.9g, want %.9g\n", what, got, want);
        failures++;
    }
}

int main(void)
{
    /* ZYX (yaw, pitch, roll) = (0.3, -0.2, 0.1) rad: q = qz(0.3) qy(-0.2) qx(0.1) in double. */
    const double y = 0.3, p = -0.2, r = 0.1;
    const double cy = cos(y / 2), sy = sin(y / 2), cp = cos(p / 2), sp = sin(p / 2);
    const double cr = cos(r / 2), sr = sin(r / 2);
    const double qw = cy * cp * cr + sy * sp * sr, qx = cy * cp * sr - sy * sp * cr;
    const double qy = cy * sp * cr + sy * cp * sr, qz = sy * cp * cr - cy * sp * sr;
    qo_euler_f32 e = { 0.3f, -0.2f, 0.1f }, back;
    qo_quat_f32 q;
    qo_quat_q30 qf;
    qo_euler_q28 ef;
    qo_euler_info_q28 info;
    double err;

    check(strcmp(QO_VERSION_STRING, "0.0.0") != 0, "version string", 0, 0);
    check(strcmp(qo_status_str(QO_OK), "ok") == 0, "qo_status_str(QO_OK) is \"ok\"", 0, 0);

    /* float32 core: angles -> quaternion against the double product, and back. */
    check(qo_euler_to_quat_f32(QO_EULER_ZYX, e, &q) == QO_OK, "qo_euler_to_quat_f32", 0, 0);
    err = fabs(q.w - qw) + fabs(q.x - qx) + fabs(q.y - qy) + fabs(q.z - qz);
    check(err < 1e-6, "quaternion from ZYX (0.3, -0.2, 0.1) vs double", err, 0);
    check(qo_euler_from_quat_f32(q, QO_EULER_ZYX, &back, NULL) == QO_OK, "to_euler_f32", 0, 0);
    check(fabs(back.a1 - y) < 1e-6, "yaw back", back.a1, y);
    check(fabs(back.a2 - p) < 1e-6, "pitch back", back.a2, p);
    check(fabs(back.a3 - r) < 1e-6, "roll back", back.a3, r);

    /* fixed-point core: the double quaternion in Q1.30 -> Q3.28 angles. */
    qf.w = (qo_q30)lround(qw * 1073741824.0); qf.x = (qo_q30)lround(qx * 1073741824.0);
    qf.y = (qo_q30)lround(qy * 1073741824.0); qf.z = (qo_q30)lround(qz * 1073741824.0);
    check(qo_euler_from_quat_q30(qf, QO_EULER_ZYX, &ef, &info) == QO_OK, "to_euler_q30", 0, 0);
    check(fabs(ef.a1 / 268435456.0 - y) < 1e-7, "fixed yaw", ef.a1 / 268435456.0, y);
    check(fabs(ef.a2 / 268435456.0 - p) < 1e-7, "fixed pitch", ef.a2 / 268435456.0, p);
    check(fabs(ef.a3 / 268435456.0 - r) < 1e-7, "fixed roll", ef.a3 / 268435456.0, r);
    check(info.locked == 0, "not locked at pitch -0.2", info.locked, 0);

    /* keyframe spline, float32 plan -> Q16.16 table -> fixed sample at the keys. */
    {
        const float t[3] = { 0.0f, 1.0f, 2.5f }, pk[6] = { 0.0f, 1.0f, 2.0f, -1.0f, 0.5f, 0.25f };
        float coef[64], pos[2];
        int32_t table[96];
        qo_q16 pq[2];
        qo_spline_f32 s;
        qo_spline_table_q16 sq;
        check(qo_spline_coef_len(2, 3) <= 64 && qo_spline_q16_len(2, 3) <= 96, "storage", 0, 0);
        check(qo_spline_init_f32(2, 3, t, pk, &qo_spline_settings_default, coef, 64, &s) == QO_OK,
              "qo_spline_init_f32 status", 0, 0);
        check(qo_spline_sample_f32(&s, 1.0f, pos, NULL, NULL, NULL) == QO_OK, "sample", 0, 0);
        check(fabs(pos[0] - 2.0) < 1e-6 && fabs(pos[1] + 1.0) < 1e-6, "float sample at key 1",
              pos[0], 2.0);
        check(qo_spline_export_q16(&s, &sq, table, 96) == QO_OK, "qo_spline_export_q16", 0, 0);
        check(qo_spline_sample_q16(&sq, 5 * QO_Q16_ONE / 2, pq, NULL, NULL, NULL) == QO_OK,
              "qo_spline_sample_q16 status", 0, 0);
        check(pq[0] == QO_Q16_ONE / 2 && pq[1] == QO_Q16_ONE / 4, "fixed sample at the last key",
              pq[0] / 65536.0, 0.5);
    }

    if (failures) {
        printf("consumer: %d check(s) failed\n", failures);
        return 1;
    }
    printf("consumer: qorient %s: float32 and fixed-point Euler, spline and Q16.16 table: ok\n",
           QO_VERSION_STRING);
    return 0;
}
