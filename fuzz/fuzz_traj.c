/*
 * fuzz/fuzz_traj.c - qorient/traj.h: a keyframe trajectory (every spline profile, end
 * condition, key_cols 1..3, limits, wrap, and bad enum values) or a target queue (both motion
 * profiles, every sync, fuzzed limits, timing rules) over 1..4 joints and a capacity of 1..6,
 * with fuzzed storage sizes (targets with room for velocities and accelerations, or not),
 * then a fuzzed sequence of push (target states too), prepare, set_timing, set_joint_sync, sample,
 * end_time, done and joints calls at fuzzed int64 times (near zero, near +-QO_TRAJ_TIME_MAX,
 * beyond it), and qo_traj_ns_from_s and qo_traj_store_len on fuzzed values.
 * Properties from the header: documented statuses; a failed init leaves kind NONE and every
 * later call QO_E_STATE (done 1, joints 0, end 0); qo_traj_store_len is 0 exactly for the
 * documented bad arguments and init refuses less storage with QO_E_CAPACITY; a failed push
 * stores nothing (the trajectory is bit-identical); sample always writes its outputs, which
 * are finite whenever the status gives a defined motion (QO_OK, QO_E_RANGE, QO_E_ORDER, and
 * the braking of a refused target); KEYS clamped flags in {-1, 0, 1}, TARGETS 0; end_time
 * writes 0 on error; ns_from_s rounds to nearest and writes 0 on error.
 */
#include "fuzz_common.h"
#include "qorient/traj.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define FUZZ_TR_MAXN 4
#define FUZZ_TR_MAXC 6
#define FUZZ_TR_STORE (FUZZ_TR_MAXC + FUZZ_TR_MAXC * FUZZ_TR_MAXN * 3 + 1024)

/* A time: small offsets around a base (ns), the edges of the supported range, or raw bits. */
static qo_traj_ns fuzz_traj_time(qo_fz *f, qo_traj_ns *base)
{
    uint8_t tag = qo_fz_u8(f);
    int64_t raw;
    switch (tag & 7u) {
    case 0: *base += (qo_traj_ns)(qo_fz_u8(f)) * 10000000; return *base;          /* +0..2.55 s */
    case 1: *base += (qo_traj_ns)qo_fz_u32(f); return *base;                        /* +0..4.3 s */
    case 2: return *base - (qo_traj_ns)qo_fz_u8(f);                                 /* back a bit */
    case 3: return QO_TRAJ_TIME_MAX - (qo_traj_ns)qo_fz_u8(f);
    case 4: return (tag & 8u) ? QO_TRAJ_TIME_MAX + 1 : -QO_TRAJ_TIME_MAX - 1;
    case 5: return -QO_TRAJ_TIME_MAX + (qo_traj_ns)qo_fz_u8(f);
    case 6: return *base;
    default:
        raw = (int64_t)((uint64_t)qo_fz_u32(f) | (uint64_t)qo_fz_u32(f) << 32);
        return raw;
    }
}

static int fuzz_traj_finite(const float *v, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    qo_fz f = qo_fz_init(data, size);
    uint8_t h0 = qo_fz_u8(&f), h1 = qo_fz_u8(&f);
    size_t n = 1u + (h0 & 3u), cap = 1u + (size_t)((h0 >> 2) % FUZZ_TR_MAXC), need, store_len, j;
    qo_traj_kind kind = (h0 & 0x20u) ? QO_TRAJ_TARGETS : QO_TRAJ_KEYS;
    unsigned key_cols = (h1 & 3u) == 3u ? 0u : 1u + (h1 & 3u); /* 0: a bad value */
    qo_traj tr, before;
    qo_traj_ns t_ns[FUZZ_TR_MAXC], base = 0, t, end;
    float store[FUZZ_TR_STORE];
    qo_motion_joint_f32 joints[FUZZ_TR_MAXN];
    qo_motion_limits_f32 lim[FUZZ_TR_MAXN];
    qo_motion_settings_f32 mset;
    qo_spline_settings_f32 sset = qo_spline_settings_default;
    float pmin[FUZZ_TR_MAXN], pmax[FUZZ_TR_MAXN], endv[2 * FUZZ_TR_MAXN];
    unsigned char wrap[FUZZ_TR_MAXN];
    float pos[FUZZ_TR_MAXN], vel[FUZZ_TR_MAXN], acc[FUZZ_TR_MAXN];
    int8_t cl[FUZZ_TR_MAXN];
    qo_status st;
    int ops, inited;

    /* qo_traj_store_len: 0 exactly for the documented bad arguments */
    need = qo_traj_store_len(kind, n, cap, key_cols == 0 ? 1u : key_cols);
    QO_FUZZ_CHECK((need > 0) == (kind == QO_TRAJ_TARGETS || cap >= 2), "store_len(%d, %zu, %zu) = %zu", (int)kind, n, cap, need);
    QO_FUZZ_CHECK(qo_traj_store_len(QO_TRAJ_NONE, n, cap, 1) == 0 && qo_traj_store_len(kind, 0, cap, 1) == 0
                  && qo_traj_store_len(kind, n, 0, 1) == 0 && qo_traj_store_len(QO_TRAJ_KEYS, n, cap, 4) == 0
                  && qo_traj_store_len(QO_TRAJ_KEYS, (size_t)-1, (size_t)-1, 3) == 0, "store_len bad arguments");
    store_len = (h1 & 4u) && need > 0 ? need - 1u : need; /* one float short: QO_E_CAPACITY */
    if (need == 0) store_len = FUZZ_TR_STORE;
    if (store_len > FUZZ_TR_STORE) store_len = FUZZ_TR_STORE;

    if (kind == QO_TRAJ_KEYS) {
        sset.profile = (qo_spline_profile)((h1 >> 3) % 6u);
        sset.end = (qo_spline_end)((h1 >> 6) % 3u);
        sset.derivs = (qo_spline_derivs)(qo_fz_u8(&f) % 3u);
        if (h0 & 0x40u) {
            for (j = 0; j < n; j++) { pmin[j] = qo_fz_f32(&f); pmax[j] = qo_fz_f32(&f); }
            sset.pos_min = pmin; sset.pos_max = pmax;
        }
        if (h0 & 0x80u) {
            for (j = 0; j < n; j++) wrap[j] = qo_fz_u8(&f) & 1u;
            sset.wrap = wrap;
            sset.wrap_period = qo_fz_f32(&f);
        }
        if (qo_fz_u8(&f) & 1u) {
            for (j = 0; j < 2 * n; j++) endv[j] = qo_fz_f32(&f);
            sset.end_vel = endv;
        }
        st = qo_traj_init_keys(&tr, n, &sset, key_cols, t_ns, cap, store, store_len);
        QO_FUZZ_CHECK(st == QO_OK || st == QO_E_TOO_FEW || st == QO_E_ARG || st == QO_E_CAPACITY,
                      "init_keys status %d", (int)st);
        if (st == QO_OK) QO_FUZZ_CHECK(cap >= 2 && key_cols >= 1 && store_len >= need, "init_keys accepted cap %zu cols %u store %zu/%zu",
                                       cap, key_cols, store_len, need);
        if (store_len < need && cap >= 2 && key_cols >= 1) QO_FUZZ_CHECK(st != QO_OK, "init_keys took too little storage");
    } else {
        uint8_t how = qo_fz_u8(&f);
        mset.profile = (qo_motion_profile)((h1 >> 3) % 3u);
        mset.sync = (qo_motion_sync)((h1 >> 5) % 5u);
        for (j = 0; j < n; j++) {
            lim[j] = qo_motion_limits_default;
            if (how & 1u) { lim[j].vmax = qo_fz_f32(&f); lim[j].amax = qo_fz_f32(&f); lim[j].jmax = qo_fz_f32(&f); }
            else {
                lim[j].vmax = 1.0f + (float)(qo_fz_u8(&f) % 20u);
                lim[j].amax = 1.0f + (float)(qo_fz_u8(&f) % 40u);
                lim[j].jmax = 5.0f + (float)(qo_fz_u8(&f) % 200u);
            }
            if (how & 2u) { lim[j].pmin = qo_fz_f32(&f); lim[j].pmax = qo_fz_f32(&f); }
            if (how & 4u) lim[j].wrap = (how & 8u) ? qo_fz_f32(&f) : 6.28318548f;
        }
        st = qo_traj_init_targets(&tr, n, lim, &mset, joints, t_ns, cap, store, store_len);
        QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG || st == QO_E_LIMIT || st == QO_E_CAPACITY,
                      "init_targets status %d", (int)st);
        /* positions need C*N floats; room for velocities (accelerations) decides target_cols */
        QO_FUZZ_CHECK((st == QO_E_CAPACITY) == (store_len < qo_traj_store_len(kind, n, cap, 1)) || st == QO_E_ARG || st == QO_E_LIMIT,
                      "init_targets status %d with %zu floats", (int)st, store_len);
        if (st == QO_OK) {
            unsigned want = store_len >= qo_traj_store_len(kind, n, cap, 3) ? 3u : store_len >= qo_traj_store_len(kind, n, cap, 2) ? 2u : 1u;
            QO_FUZZ_CHECK(tr.target_cols == want, "target_cols %u with %zu floats, want %u", tr.target_cols, store_len, want);
        }
    }
    inited = st == QO_OK;
    if (!inited) {
        QO_FUZZ_CHECK(tr.kind == QO_TRAJ_NONE, "failed init left kind %d", (int)tr.kind);
        QO_FUZZ_CHECK(qo_traj_push(&tr, 0, pos, NULL, NULL) == QO_E_STATE && qo_traj_prepare(&tr) == QO_E_STATE
                      && qo_traj_set_timing(&tr, 0.0f, 0.0f) == QO_E_STATE && qo_traj_joints(&tr) == 0
                      && qo_traj_done(&tr, 0) == 1, "calls after a failed init");
        end = 1;
        QO_FUZZ_CHECK(qo_traj_end_time(&tr, &end) == QO_E_STATE && end == 0, "end_time after a failed init");
        pos[0] = 1.0f;
        st = qo_traj_sample(&tr, 0, pos, vel, acc, cl);
        QO_FUZZ_CHECK(st == QO_E_STATE, "sample after a failed init: %d", (int)st);
        return 0;
    }
    QO_FUZZ_CHECK(qo_traj_joints(&tr) == n, "joints %zu, want %zu", qo_traj_joints(&tr), n);

    for (ops = 0; ops < 24 && f.n > 0; ops++) {
        uint8_t op = qo_fz_u8(&f);
        t = fuzz_traj_time(&f, &base);
        switch (op % 6u) {
        case 0:
        case 1: { /* push */
            float p[FUZZ_TR_MAXN], v[FUZZ_TR_MAXN], a[FUZZ_TR_MAXN];
            int drop = (op >> 3) & 3;
            for (j = 0; j < n; j++) {
                p[j] = (op & 0x80u) ? qo_fz_f32(&f) : (float)((int)qo_fz_u8(&f) - 128) * 0.05f;
                v[j] = (op & 0x40u) ? qo_fz_f32(&f) : (float)((int)qo_fz_u8(&f) - 128) * 0.01f;
                a[j] = (op & 0x20u) ? qo_fz_f32(&f) : 0.0f;
            }
            before = tr;
            st = qo_traj_push(&tr, t, p, drop == 1 ? NULL : v, drop == 2 ? NULL : a);
            QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NULL || st == QO_E_RANGE || st == QO_E_NONFINITE || st == QO_E_ORDER
                          || st == QO_E_CAPACITY || st == QO_E_LIMIT || (st == QO_E_ARG && kind == QO_TRAJ_TARGETS),
                          "push status %d", (int)st);
            if (kind == QO_TRAJ_TARGETS && st == QO_OK)
                QO_FUZZ_CHECK((drop == 1 || tr.target_cols >= 2) && (drop == 2 || tr.target_cols >= 3),
                              "push took velocities/accelerations without storage (cols %u)", tr.target_cols);
            if (st != QO_OK) QO_FUZZ_CHECK(memcmp(&tr, &before, sizeof tr) == 0, "push error %d changed the trajectory", (int)st);
            if (st == QO_E_NULL) QO_FUZZ_CHECK(kind == QO_TRAJ_KEYS && ((drop == 1 && key_cols >= 2) || (drop == 2 && key_cols >= 3)),
                                               "push QO_E_NULL with every array given");
            break;
        }
        case 2:
            st = qo_traj_prepare(&tr);
            QO_FUZZ_CHECK(st == QO_OK || st == QO_E_TOO_FEW || st == QO_E_RANGE || st == QO_E_NONFINITE || st == QO_E_ORDER
                          || st == QO_E_LIMIT || st == QO_E_NULL || st == QO_E_ARG, "prepare status %d", (int)st);
            break;
        case 3: {
            float md = qo_fz_f32(&f), per = qo_fz_f32(&f);
            if (op & 0x80u) { /* per-joint sync instead */
                size_t ji = qo_fz_u8(&f) % (n + 1u);
                qo_motion_sync sy = (qo_motion_sync)(qo_fz_u8(&f) % 5u);
                before = tr;
                st = qo_traj_set_joint_sync(&tr, ji, sy);
                QO_FUZZ_CHECK(kind == QO_TRAJ_KEYS ? st == QO_E_STATE
                              : st == (ji >= n ? QO_E_RANGE : (unsigned)sy > 3u ? QO_E_ARG : QO_OK),
                              "set_joint_sync(%zu, %d) status %d", ji, (int)sy, (int)st);
                if (st != QO_OK) QO_FUZZ_CHECK(memcmp(&tr, &before, sizeof tr) == 0, "set_joint_sync error changed the trajectory");
                break;
            }
            before = tr;
            st = qo_traj_set_timing(&tr, md, per);
            QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG || st == QO_E_STATE, "set_timing status %d", (int)st);
            QO_FUZZ_CHECK((st == QO_E_STATE) == (kind == QO_TRAJ_KEYS), "set_timing status %d on kind %d", (int)st, (int)kind);
            if (st != QO_OK) QO_FUZZ_CHECK(memcmp(&tr, &before, sizeof tr) == 0, "set_timing error changed the trajectory");
            break;
        }
        case 4: {
            int k = qo_traj_done(&tr, t);
            QO_FUZZ_CHECK(k == 0 || k == 1, "done %d", k);
            end = 12345;
            st = qo_traj_end_time(&tr, &end);
            QO_FUZZ_CHECK(st == QO_OK || st == QO_E_TOO_FEW, "end_time status %d", (int)st);
            if (st != QO_OK) QO_FUZZ_CHECK(end == 0 && k == 1, "end_time error wrote %lld, done %d", (long long)end, k);
            QO_FUZZ_CHECK(qo_traj_end_time(&tr, NULL) == QO_E_NULL, "end_time NULL");
            break;
        }
        default: { /* sample, sometimes with NULL optional outputs */
            int nulls = (op >> 3) & 3;
            for (j = 0; j < n; j++) { pos[j] = vel[j] = acc[j] = NAN; cl[j] = 99; }
            st = qo_traj_sample(&tr, t, pos, nulls == 1 ? NULL : vel, nulls == 2 ? NULL : acc, nulls == 3 ? NULL : cl);
            QO_FUZZ_CHECK(st == QO_OK || st == QO_E_TOO_FEW || st == QO_E_RANGE || st == QO_E_ORDER || st == QO_E_NONFINITE
                          || st == QO_E_LIMIT || st == QO_E_ARG || st == QO_E_NULL, "sample status %d", (int)st);
            QO_FUZZ_CHECK(fuzz_traj_finite(pos, n) && (nulls == 1 || fuzz_traj_finite(vel, n))
                          && (nulls == 2 || fuzz_traj_finite(acc, n)), "sample kind %d t %lld status %d: outputs not written or not finite:"
                          " last joint %g %g %g (nulls %d), n %zu, profile %d, keys %zu", (int)kind, (long long)t, (int)st, (double)pos[n - 1], (double)vel[n - 1],
                          (double)acc[n - 1], nulls, n, (int)sset.profile, tr.n_keys);
            if (nulls != 3)
                for (j = 0; j < n; j++)
                    QO_FUZZ_CHECK(cl[j] == -1 || cl[j] == 0 || cl[j] == 1, "clamped[%zu] = %d", j, (int)cl[j]);
            if (kind == QO_TRAJ_TARGETS && nulls != 3)
                for (j = 0; j < n; j++) QO_FUZZ_CHECK(cl[j] == 0, "TARGETS clamped[%zu] = %d", j, (int)cl[j]);
            st = qo_traj_sample(&tr, t, NULL, vel, acc, cl);
            QO_FUZZ_CHECK(st == QO_E_NULL, "sample pos NULL: %d", (int)st);
            break;
        }
        }
    }

    /* seconds -> ns: nearest, 0 on error */
    {
        double s = (double)qo_fz_f32(&f) * ((qo_fz_u8(&f) & 1u) ? 1e9 : 1.0);
        qo_traj_ns tn = 7;
        st = qo_traj_ns_from_s(s, &tn);
        QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_RANGE, "ns_from_s status %d", (int)st);
        if (st != QO_OK) QO_FUZZ_CHECK(tn == 0, "ns_from_s(%g) error wrote %lld", s, (long long)tn);
        else QO_FUZZ_CHECK(fabs((double)tn - s * 1e9) <= 0.5 + fabs(s * 1e9) * 2.3e-16 && tn >= -QO_TRAJ_TIME_MAX
                           && tn <= QO_TRAJ_TIME_MAX, "ns_from_s(%.17g) = %lld", s, (long long)tn);
        QO_FUZZ_CHECK(qo_traj_ns_from_s(s, NULL) == QO_E_NULL, "ns_from_s NULL");
    }
    return 0;
}
