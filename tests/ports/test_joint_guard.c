/* The joint guard alone (no bus): for random ranges [lo, hi] the drive may hold and random
 * targets (fixed seed), every value sent is within max_step of every value in the range,
 * checked in double on the decoded registers; it is the target itself when that is inside
 * the window and the limits; the window's edge otherwise; blocked only when no register
 * value fits. Edges: NaN-free infinities of min/max, saturation, an empty window, float32
 * rounding, and the answered / refused / unknown bookkeeping. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <string.h>
#include <cmocka.h>

#include "linux/joint_guard.h"
#include "common/ref.h"

static uint64_t rng = 0x5EEDu;

static double urand(double a, double b)
{
    return a + (b - a) * ref_unit_from_bits(ref_splitmix64(&rng)); /* tests/common/ref.c */
}

static qo_regmap_joint joint(qo_modbus_reg_type type, double scale, double max_step)
{
    qo_regmap_joint j;
    memset(&j, 0, sizeof j);
    j.fmt.type = type;
    j.fmt.order = QO_MODBUS_REG_HI_FIRST;
    j.fmt.scale = scale;
    j.min = -INFINITY;
    j.max = INFINITY;
    j.max_step = max_step;
    return j;
}

static void test_window_random(void **state)
{
    static const qo_modbus_reg_type types[] = { QO_MODBUS_REG_INT16, QO_MODBUS_REG_INT32, QO_MODBUS_REG_UINT16, QO_MODBUS_REG_FLOAT32 };
    unsigned t, k, sent = 0, blocked = 0;
    (void)state;
    for (t = 0; t < 4; t++) {
        qo_regmap_joint j =
            joint(types[t], types[t] == QO_MODBUS_REG_UINT16 ? 100.0 : 1000.0, 0.05);
        for (k = 0; k < 20000; k++) {
            qo_joint_guard g;
            uint16_t regs[2];
            unsigned changed;
            double base = types[t] == QO_MODBUS_REG_UINT16 ? urand(1000, 5000) : urand(-5000, 5000);
            double width = urand(0, 1) < 0.7 ? 0.0 : urand(0, 120); /* raw; step is 50 raw */
            double target = base / j.fmt.scale + urand(-1, 1), raw_sent, a, b;
            qo_status st;
            qo_joint_guard_init(&g, &j);
            if (types[t] != QO_MODBUS_REG_FLOAT32) base = floor(base), width = floor(width);
            qo_joint_guard_known(&g, base);
            g.hi = base + width;
            st = qo_joint_guard_limit(&g, &j, target, regs, &changed);
            a = g.hi - g.step;
            b = g.lo + g.step;
            if (st != QO_OK) {
                if (st != QO_E_INFEASIBLE ||
                    a <= b - (types[t] == QO_MODBUS_REG_FLOAT32 ? 0.01 : 1.0))
                    fail_msg("type %u case %u: %s with window [%g, %g]", t, k, qo_status_str(st), a, b);
                assert_true(g.uncertain);
                blocked++;
                continue;
            }
            sent++;
            assert_int_equal(qo_modbus_reg_unpack_raw(j.fmt.type, j.fmt.order, regs, &raw_sent),
                             QO_OK);
            if (raw_sent != g.cmd) fail_msg("type %u case %u: packed %.9g, cmd %.9g", t, k, raw_sent, g.cmd);
            /* the independent check: within max_step of both ends of what the drive may hold */
            if (fabs(raw_sent - g.lo) > g.step + 1e-9 || fabs(raw_sent - g.hi) > g.step + 1e-9)
                fail_msg("type %u case %u: sent %.9g, range [%.9g, %.9g], step %.9g", t, k, raw_sent, g.lo, g.hi, g.step);
            if (!(changed & QO_JOINT_GUARD_RATE_LIMITED) && fabs(raw_sent - target * j.fmt.scale) > (types[t] == QO_MODBUS_REG_FLOAT32 ? 1e-3 : 0.5 + 1e-9))
                fail_msg("type %u case %u: unlimited target %.9g sent as %.9g", t, k, target * j.fmt.scale, raw_sent);
        }
    }
    assert_true(sent > 70000);
    assert_true(blocked > 0); /* ranges wider than 2 x step occur and are refused */
}

static void test_edges(void **state)
{
    qo_regmap_joint j = joint(QO_MODBUS_REG_INT16, 1000.0, 0.0);
    qo_joint_guard g;
    uint16_t regs[2];
    unsigned changed;
    (void)state;
    /* no max_step, nothing known: the target as is; clamp and saturation reported */
    qo_joint_guard_init(&g, &j);
    assert_int_equal(qo_joint_guard_limit(&g, &j, 1.5, regs, &changed), QO_OK);
    assert_true(g.cmd == 1500.0 && changed == 0);
    assert_int_equal(qo_joint_guard_limit(&g, &j, 1e39, regs, &changed), QO_OK);
    assert_true(g.cmd == 32767.0 && changed == QO_JOINT_GUARD_SATURATED);
    j.max = 2.0;
    assert_int_equal(qo_joint_guard_limit(&g, &j, 3.0, regs, &changed), QO_OK);
    assert_true(g.cmd == 2000.0 && changed == QO_JOINT_GUARD_CLAMPED);
    assert_true(qo_joint_guard_goal(&g, &j, 3.0) == 2000.0);
    assert_true(qo_joint_guard_goal(&g, &j, -1e39) == -32768.0);
    /* the goal is held only when known exactly, with nothing outstanding */
    assert_false(qo_joint_guard_holds(&g, 2000.0));
    qo_joint_guard_known(&g, 2000.0);
    assert_true(qo_joint_guard_holds(&g, 2000.0));
    /* a write outstanding, then refused: the old value again */
    j = joint(QO_MODBUS_REG_INT16, 1000.0, 0.05);
    qo_joint_guard_init(&g, &j);
    qo_joint_guard_known(&g, 0.0);
    assert_int_equal(qo_joint_guard_limit(&g, &j, 1.0, regs, &changed), QO_OK);
    assert_true(g.cmd == 50.0 && changed == QO_JOINT_GUARD_RATE_LIMITED);
    qo_joint_guard_sent(&g);
    qo_joint_guard_unknown(&g);
    assert_true(g.lo == 0.0 && g.hi == 50.0 && !qo_joint_guard_holds(&g, 50.0));
    /* while unknown, the next value is within max_step of both: 50 at most */
    assert_int_equal(qo_joint_guard_limit(&g, &j, 1.0, regs, &changed), QO_OK);
    assert_true(g.cmd == 50.0);
    qo_joint_guard_answered(&g, 0);
    assert_true(g.lo == 0.0 && g.hi == 0.0 && !g.pend);
    /* sent and applied */
    g.cmd = 50.0;
    qo_joint_guard_sent(&g);
    qo_joint_guard_answered(&g, 1);
    assert_true(qo_joint_guard_holds(&g, 50.0));
    qo_joint_guard_answered(&g, 0); /* nothing outstanding: no change */
    assert_true(qo_joint_guard_holds(&g, 50.0));
    /* a range wider than 2 x max_step: nothing may be sent */
    g.lo = 0.0;
    g.hi = 101.0;
    assert_int_equal(qo_joint_guard_limit(&g, &j, 0.05, regs, &changed), QO_E_INFEASIBLE);
    assert_true(g.uncertain);
    /* float32: rounding never steps past max_step */
    j = joint(QO_MODBUS_REG_FLOAT32, 1.0, 3e-7); /* float(1 + 3e-7) rounds up past the window */
    qo_joint_guard_init(&g, &j);
    qo_joint_guard_known(&g, 1.0);
    assert_int_equal(qo_joint_guard_limit(&g, &j, 2.0, regs, &changed), QO_OK);
    assert_true(g.cmd > 1.0 && g.cmd - 1.0 <= 3e-7);
    j.max_step = 1e-7; /* below half an ulp of 1.0: only 1.0 itself fits */
    qo_joint_guard_init(&g, &j);
    qo_joint_guard_known(&g, 1.0);
    assert_int_equal(qo_joint_guard_limit(&g, &j, 2.0, regs, &changed), QO_OK);
    assert_true(g.cmd == 1.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_window_random),
        cmocka_unit_test(test_edges),
    };
    return cmocka_run_group_tests_name("joint_guard", tests, NULL, NULL);
}
