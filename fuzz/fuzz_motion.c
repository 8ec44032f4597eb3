/*
 * fuzz/fuzz_motion.c - limited moves (qorient/motion.h, motion_fx.h): 1..4 joints with fuzzed
 * limits (vmax/amax/jmax/range/wrap and the asymmetric vmin/amin, also zero, positive,
 * negative, NaN, Inf, denormal), both profiles and every sync (and one bad value of each), then
 * a fuzzed sequence of set_target, set_target_state (fuzzed velocities and accelerations),
 * set_velocity, set_limits, set_joint_sync, brake, set_timing (fuzzed minimum duration and
 * period) and sample calls at fuzzed times, and the Q16.16 export and sampler.
 * Properties from the header: documented statuses; a failed init leaves n = 0 (every later
 * call QO_E_STATE); *clamped is 0 on error; every sample with QO_OK (or QO_E_RANGE, which
 * also gives the state at t0) is finite; while no limit was changed and no brake or NaN
 * target happened, vel in [vmin, vmax] and acc in [amin, amax] (1e-3 relative slack), also
 * after the end of a plan to a moving target state; a refused target state (QO_E_LIMIT,
 * QO_E_ARG) leaves the planner and its joints bit-for-bit unchanged; the export and its
 * sampler return documented statuses; set_timing accepts only values in its documented range
 * and never re-plans by itself.
 */
#include "fuzz_common.h"
#include "qorient/motion.h"
#include "qorient/motion_fx.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define FUZZ_MO_MAXN 4

static qo_motion_limits_f32 fuzz_motion_limits(qo_fz *f, uint8_t how)
{
    qo_motion_limits_f32 l = qo_motion_limits_default;
    if (how & 1u) { l.vmax = qo_fz_f32(f); l.amax = qo_fz_f32(f); l.jmax = qo_fz_f32(f); }
    else { l.vmax = 1.0f + (float)(qo_fz_u8(f) % 50u); l.amax = 1.0f + (float)(qo_fz_u8(f) % 50u); l.jmax = 5.0f + (float)(qo_fz_u8(f) % 200u); }
    if (how & 2u) { l.pmin = qo_fz_f32(f); l.pmax = qo_fz_f32(f); }
    if (how & 4u) l.wrap = (how & 8u) ? qo_fz_f32(f) : 6.28318548f;
    if (how & 16u) { l.vmin = qo_fz_f32(f); l.amin = qo_fz_f32(f); }
    else if (how & 32u) { l.vmin = -1.0f - (float)(qo_fz_u8(f) % 50u); l.amin = -1.0f - (float)(qo_fz_u8(f) % 50u); }
    return l;
}

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    qo_fz f = qo_fz_init(data, size);
    uint8_t h0 = qo_fz_u8(&f);
    size_t n = 1u + (h0 & 3u), i;
    qo_motion_joint_f32 joints[FUZZ_MO_MAXN];
    qo_motion_limits_f32 lim[FUZZ_MO_MAXN];
    qo_motion_settings_f32 set;
    qo_motion_planner_f32 pl;
    float start[FUZZ_MO_MAXN], tg[FUZZ_MO_MAXN], pos[FUZZ_MO_MAXN], vel[FUZZ_MO_MAXN], acc[FUZZ_MO_MAXN];
    float t0 = (h0 & 0x80u) ? qo_fz_f32(&f) : 0.0f;
    qo_motion_seg_q16 segs[FUZZ_MO_MAXN * QO_MOTION_Q16_SEGS];
    qo_motion_table_q16 table;
    qo_status st;
    uint32_t cl;
    int ops, steady = 1;

    set.profile = (qo_motion_profile)((h0 >> 2) % 3u);
    set.sync = (qo_motion_sync)((h0 >> 4) % 5u);
    for (i = 0; i < n; i++) {
        lim[i] = fuzz_motion_limits(&f, qo_fz_u8(&f));
        start[i] = qo_fz_f32(&f);
    }
    st = qo_motion_init_f32(&pl, joints, n, lim, start, t0, &set);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG || st == QO_E_LIMIT || st == QO_E_NONFINITE || st == QO_E_RANGE, "motion_init status %d", (int)st);
    if (st != QO_OK) {
        QO_FUZZ_CHECK(pl.n == 0, "motion_init error left n = %zu", pl.n);
        QO_FUZZ_CHECK(qo_motion_sample_f32(&pl, 0.0f, pos, vel, acc) == QO_E_STATE, "sample after failed init");
        cl = 99u;
        QO_FUZZ_CHECK(qo_motion_set_target_f32(&pl, 0.0f, start, &cl) == QO_E_STATE && cl == 0u, "set_target after failed init");
        return 0;
    }

    for (ops = 0; ops < 12 && f.n > 0; ops++) {
        uint8_t op = qo_fz_u8(&f);
        float t = ((op & 0x30u) == 0x30u) ? qo_fz_f32(&f) : pl.t0 + (float)(qo_fz_u8(&f)) * 0.05f;
        switch (op & 3u) {
        case 0:
            if (op & 0x80u) {
                /* velocity interface: fuzzed velocities (NaN brakes, beyond vmax is refused) */
                for (i = 0; i < n; i++) tg[i] = (op & 0x40u) ? qo_fz_f32(&f) : (float)((int)qo_fz_u8(&f) - 128) * 0.01f;
                st = qo_motion_set_velocity_f32(&pl, t, tg);
                QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_ORDER || st == QO_E_RANGE,
                              "set_velocity status %d", (int)st);
                if (st == QO_OK) QO_FUZZ_CHECK(pl.vel_mode == 1, "set_velocity OK without velocity mode");
                if (st == QO_E_NONFINITE) steady = 0;
                break;
            }
            for (i = 0; i < n; i++) {
                tg[i] = (op & 0x40u) ? qo_fz_f32(&f) : start[i] + (float)((int)qo_fz_u8(&f) - 128) * 0.1f;
            }
            cl = 99u;
            if (op & 0x08u) {
                /* full target states: velocities and accelerations small (mostly accepted) or
                 * fuzzed floats (mostly refused: nothing may change then) */
                float tv[FUZZ_MO_MAXN], ta[FUZZ_MO_MAXN];
                qo_motion_planner_f32 before;
                qo_motion_joint_f32 jb[FUZZ_MO_MAXN];
                memcpy(&before, &pl, sizeof pl);
                memcpy(jb, joints, sizeof joints);
                for (i = 0; i < n; i++) {
                    tv[i] = (op & 0x04u) ? qo_fz_f32(&f) : (float)((int)qo_fz_u8(&f) - 128) * 0.005f;
                    ta[i] = (op & 0x04u) ? qo_fz_f32(&f) : (float)((int)qo_fz_u8(&f) - 128) * 0.005f;
                }
                st = qo_motion_set_target_state_f32(&pl, t, tg, tv, (op & 0x40u) ? NULL : ta, &cl);
                QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_ORDER || st == QO_E_RANGE ||
                                  st == QO_E_LIMIT || st == QO_E_ARG, "set_target_state status %d", (int)st);
                if (st == QO_E_LIMIT || st == QO_E_ARG || st == QO_E_ORDER)
                    QO_FUZZ_CHECK(memcmp(&before, &pl, sizeof pl) == 0 && memcmp(jb, joints, sizeof joints) == 0,
                                  "set_target_state refused (%d) but changed the planner", (int)st);
            } else {
                st = qo_motion_set_target_f32(&pl, t, tg, &cl);
                QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_ORDER || st == QO_E_RANGE, "set_target status %d", (int)st);
            }
            if (st != QO_OK) QO_FUZZ_CHECK(cl == 0u, "set_target error %d with clamped %u", (int)st, (unsigned)cl);
            if (st == QO_E_NONFINITE || st == QO_E_RANGE) steady = 0;   /* brakes: no sync, may exceed nothing, but re-plans */
            break;
        case 1:
            i = qo_fz_u8(&f) % (n + 1u);   /* n is out of range */
            lim[0] = fuzz_motion_limits(&f, qo_fz_u8(&f));
            st = qo_motion_set_limits_f32(&pl, t, i, &lim[0]);
            QO_FUZZ_CHECK(st == QO_OK || st == QO_E_RANGE || st == QO_E_NONFINITE || st == QO_E_ORDER || st == QO_E_LIMIT,
                          "set_limits status %d", (int)st);
            if (st == QO_OK || st == QO_E_LIMIT || st == QO_E_RANGE) steady = 0;
            break;
        case 2:
            if ((op & 0xC0u) == 0x40u) {
                /* per-joint sync: any index (n is out of range), any value (5.. are bad) */
                qo_motion_sync sy = (qo_motion_sync)(qo_fz_u8(&f) % 7u);
                int old;
                i = qo_fz_u8(&f) % (n + 1u);
                old = i < n ? joints[i].sync : 0;
                st = qo_motion_set_joint_sync_f32(&pl, i, sy);
                QO_FUZZ_CHECK(st == QO_OK || st == QO_E_RANGE || st == QO_E_ARG, "set_joint_sync status %d", (int)st);
                QO_FUZZ_CHECK((st == QO_OK) == (i < n && (unsigned)sy <= 3u), "set_joint_sync(%zu, %d) status %d", i,
                              (int)sy, (int)st);
                if (st != QO_OK && i < n) QO_FUZZ_CHECK(joints[i].sync == old, "set_joint_sync refused but changed");
                break;
            }
            if (op & 0x80u) {
                /* duration rules: accepted only in range, never re-plan by themselves */
                float md = qo_fz_f32(&f), per = qo_fz_f32(&f), d0 = qo_motion_duration_f32(&pl);
                st = qo_motion_set_timing_f32(&pl, md, per);
                QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG, "set_timing status %d", (int)st);
                if (st == QO_OK)
                    QO_FUZZ_CHECK(pl.min_duration == md && pl.period == per && md >= 0.0f && per >= 0.0f &&
                                      md <= QO_MOTION_DURATION_MAX && per <= QO_MOTION_DURATION_MAX,
                                  "set_timing accepted %g %g", (double)md, (double)per);
                QO_FUZZ_CHECK(qo_motion_duration_f32(&pl) == d0, "set_timing re-planned");
                break;
            }
            st = qo_motion_brake_f32(&pl, t);
            QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_ORDER || st == QO_E_RANGE, "brake status %d", (int)st);
            if (st == QO_OK || st == QO_E_RANGE) steady = 0;
            break;
        default:
            st = qo_motion_sample_f32(&pl, t, pos, vel, acc);
            QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_RANGE, "sample status %d", (int)st);
            for (i = 0; i < n; i++) {
                const qo_motion_limits_f32 *l = &pl.joints[i].lim;
                QO_FUZZ_CHECK(isfinite(pos[i]) && isfinite(vel[i]) && isfinite(acc[i]),
                              "sample joint %zu at %.9g: pos %g vel %g acc %g (vmax %g amax %g jmax %g)", i, (double)t,
                              (double)pos[i], (double)vel[i], (double)acc[i], (double)l->vmax, (double)l->amax,
                              (double)l->jmax);
                if (steady && st == QO_OK) {
                    float vlo = l->vmin != 0.0f ? -l->vmin : l->vmax, alo = l->amin != 0.0f ? -l->amin : l->amax;
                    QO_FUZZ_CHECK(vel[i] <= l->vmax * 1.001f + 1e-6f && -vel[i] <= vlo * 1.001f + 1e-6f &&
                                      acc[i] <= l->amax * 1.001f + 1e-6f && -acc[i] <= alo * 1.001f + 1e-6f,
                                  "sample joint %zu at %.9g: vel %g acc %g over [%g, %g] [%g, %g]", i, (double)t,
                                  (double)vel[i], (double)acc[i], (double)-vlo, (double)l->vmax, (double)-alo,
                                  (double)l->amax);
                }
            }
            break;
        }
        QO_FUZZ_CHECK(isfinite(qo_motion_duration_f32(&pl)) && qo_motion_duration_f32(&pl) >= 0.0f,
                      "duration %g after op %u (status %d) at t %.9g; joint 0: vmax %g amax %g jmax %g range [%g, %g]"
                      " wrap %g goal %g final %g", (double)qo_motion_duration_f32(&pl), (unsigned)(op & 3u), (int)st,
                      (double)t, (double)pl.joints[0].lim.vmax, (double)pl.joints[0].lim.amax,
                      (double)pl.joints[0].lim.jmax, (double)pl.joints[0].lim.pmin, (double)pl.joints[0].lim.pmax,
                      (double)pl.joints[0].lim.wrap, (double)pl.joints[0].goal, (double)pl.joints[0].final);
    }

    st = qo_motion_export_q16(&pl, &table, segs, (h0 & 0x40u) ? n * QO_MOTION_Q16_SEGS : n * QO_MOTION_Q16_SEGS - 1u);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_OVERFLOW || st == QO_E_CAPACITY, "export_q16 status %d", (int)st);
    if (st == QO_E_CAPACITY) {
        QO_FUZZ_CHECK(table.n == 0, "export_q16 capacity error left n = %zu", (size_t)table.n);
    } else {
        qo_q16 qp[FUZZ_MO_MAXN], qv[FUZZ_MO_MAXN], qa[FUZZ_MO_MAXN];
        int r;
        for (r = 0; r < 6; r++) {
            st = qo_motion_sample_q16(&table, qo_fz_i32(&f), qp, qv, qa);
            QO_FUZZ_CHECK(st == QO_OK || st == QO_E_RANGE || st == QO_E_OVERFLOW, "sample_q16 status %d", (int)st);
        }
    }
    return 0;
}
