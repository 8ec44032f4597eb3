/* The layout of one tick (map -> FC16 requests) against an independent check: for random
 * maps (fixed seed) every written register of every slave (joint targets and constants) is
 * covered by exactly one request, a request is strictly contiguous, within max_registers,
 * never cuts a 32-bit value, carries the constants' values, and two neighbouring requests
 * of one slave could not have been merged. Plus the case of issue 13: a slave with only
 * constants is written (and counted by the wire budget). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "linux/modbus_layout.h"
#include "linux/wire_budget.h"
#include "common/ref.h"

static qo_regmap map;
static qo_modbus_layout lay;
static qo_wire_budget wb;

static uint64_t rng = 0x13u;

static unsigned rnd(unsigned n) { return (unsigned)(ref_splitmix64(&rng) % n); } /* tests/common/ref.c */

/* owner[slave][address]: 0 free, 1 + joint index (first register), 1000 + joint (second
 * register of a 32-bit value), 2000 + value-less constant marker; value[] for constants. */
static int owner[4][256];
static unsigned cval[4][256];

static void random_map(unsigned seed_case)
{
    size_t nj = 0, s;
    unsigned a;
    (void)seed_case;
    memset(&map, 0, sizeof map);
    memset(owner, 0, sizeof owner);
    map.n_slaves = 3;
    for (s = 0; s < 3; s++) {
        map.slaves[s].id = (unsigned)s + 1;
        map.slaves[s].max_registers = 1 + rnd(8);
        map.slaves[s].gap_us = rnd(3) * 100;
    }
    for (s = 0; s < 3; s++) {
        for (a = 0; a < 40;) {
            unsigned kind = rnd(6);
            qo_regmap_slave *sl = &map.slaves[s];
            if (kind < 2 && nj < 12) { /* a joint, 1 or 2 registers */
                qo_regmap_joint *j = &map.joints[nj];
                unsigned w = kind == 0 ? 2 : 1;
                if (w > sl->max_registers) w = 1;
                j->slave = sl->id;
                j->address = (uint16_t)a;
                j->fmt.type = w == 2 ? QO_MODBUS_REG_INT32 : QO_MODBUS_REG_INT16;
                j->fmt.scale = 1.0;
                owner[s][a] = 1 + (int)nj;
                if (w == 2) owner[s][a + 1] = 1000 + (int)nj;
                nj++;
                a += w;
            } else if (kind == 2 && sl->n_constant < QO_REGMAP_MAX_WRITES) {
                sl->constant[sl->n_constant].address = (uint16_t)a;
                sl->constant[sl->n_constant].value = (uint16_t)(a * 7 + s);
                sl->n_constant++;
                owner[s][a] = 2000;
                cval[s][a] = a * 7 + (unsigned)s;
                a++;
            } else {
                a += 1 + rnd(2); /* a gap */
            }
        }
    }
    if (nj == 0) { /* at least one joint */
        map.joints[0].slave = 1;
        map.joints[0].address = 200;
        map.joints[0].fmt.type = QO_MODBUS_REG_INT16;
        map.joints[0].fmt.scale = 1.0;
        owner[0][200] = 1;
        nj = 1;
    }
    map.n_joints = nj;
}

static void check_layout(unsigned c)
{
    static int seen[4][256];
    size_t r, i;
    unsigned s, a;
    memset(seen, 0, sizeof seen);
    assert_int_equal(qo_modbus_layout_build(&map, &lay), QO_OK);
    for (r = 0; r < lay.n_requests; r++) {
        const qo_modbus_layout_request *q = &lay.req[r];
        const qo_regmap_slave *sl = qo_regmap_find_slave(&map, q->slave);
        assert_non_null(sl);
        if (q->count < 1 || q->count > sl->max_registers)
            fail_msg("case %u request %u: %u registers, max %u", c, (unsigned)r, q->count, sl->max_registers);
        if (owner[q->slave - 1][q->start] >= 1000 && owner[q->slave - 1][q->start] < 2000)
            fail_msg("case %u: request %u starts inside a 32-bit value", c, (unsigned)r);
        for (a = q->start; a < (unsigned)q->start + q->count; a++) {
            int o = owner[q->slave - 1][a];
            if (o == 0) fail_msg("case %u: request %u covers unused register %u", c, (unsigned)r, a);
            if (seen[q->slave - 1][a]++) fail_msg("case %u: register %u sent twice", c, a);
            if (o == 2000 && q->regs[a - q->start] != cval[q->slave - 1][a])
                fail_msg("case %u: constant at %u is %u", c, a, q->regs[a - q->start]);
        }
        if (a < 256 && owner[q->slave - 1][a] >= 1000 && owner[q->slave - 1][a] < 2000)
            fail_msg("case %u: request %u cuts a 32-bit value", c, (unsigned)r);
        for (i = 0; i < q->n_items; i++) {
            const qo_modbus_layout_item *it = &lay.item[q->first_item + i];
            const qo_regmap_joint *j = &map.joints[it->joint];
            if (j->slave != q->slave || j->address != q->start + it->offset)
                fail_msg("case %u: joint %u at offset %u of request %u", c, (unsigned)it->joint, it->offset, (unsigned)r);
        }
        if (r > 0) {
            const qo_modbus_layout_request *p = &lay.req[r - 1];
            if (p->slave > q->slave || (p->slave == q->slave && p->start >= q->start))
                fail_msg("case %u: requests out of order", c);
            if (p->slave == q->slave && (unsigned)p->start + p->count == q->start) {
                /* contiguous: only split because the next cell would not fit */
                unsigned w = owner[q->slave - 1][q->start] < 1000 && q->count >= 2 &&
                             owner[q->slave - 1][q->start + 1] >= 1000 && owner[q->slave - 1][q->start + 1] < 2000 ? 2 : 1;
                if (p->count + w <= sl->max_registers)
                    fail_msg("case %u: requests %u and %u could be one", c, (unsigned)r - 1, (unsigned)r);
            }
        }
    }
    for (s = 0; s < 3; s++)
        for (a = 0; a < 256; a++)
            if (owner[s][a] != 0 && !seen[s][a])
                fail_msg("case %u: slave %u register %u never sent", c, s + 1, a);
    assert_int_equal(lay.n_items, map.n_joints);
}

static void test_random_maps(void **state)
{
    unsigned c;
    (void)state;
    for (c = 0; c < 500; c++) {
        random_map(c);
        check_layout(c);
    }
}

/* Issue 13: a [slave.2] with only constants is one more request per tick, sent by the sink
 * and counted by the wire budget (which --dry-run prints). */
static void test_constant_only_slave(void **state)
{
    char err[256];
    qo_modbus_link_spec spec;
    (void)state;
    assert_int_equal(qo_regmap_parse("[slave.2]\nconstant = 0x10=5, 0x11=6\n"
                                     "[joint.a]\nslave = 1\naddress = 0\ntype = int32\n",
                                     "c.ini", &map, err, sizeof err), QO_OK);
    assert_int_equal(qo_modbus_layout_build(&map, &lay), QO_OK);
    assert_int_equal(lay.n_requests, 2);
    assert_int_equal(lay.req[1].slave, 2);
    assert_int_equal(lay.req[1].start, 0x10);
    assert_int_equal(lay.req[1].count, 2);
    assert_int_equal(lay.req[1].n_items, 0);
    assert_int_equal(lay.req[1].regs[0], 5);
    assert_int_equal(lay.req[1].regs[1], 6);
    assert_int_equal(qo_modbus_link_parse_spec("rtu:/dev/null,115200,8N1", &spec), QO_OK);
    assert_int_equal(qo_wire_budget_compute(&map, &spec, 0.0, &wb), QO_OK);
    assert_int_equal(wb.n_requests, 2);
    assert_int_equal(wb.req[1].slave, 2);
    assert_int_equal(wb.req[1].registers, 2);
}

static void test_bad_maps(void **state)
{
    (void)state;
    memset(&map, 0, sizeof map);
    assert_int_equal(qo_modbus_layout_build(NULL, &lay), QO_E_NULL);
    assert_int_equal(qo_modbus_layout_build(&map, NULL), QO_E_NULL);
    assert_int_equal(qo_modbus_layout_build(&map, &lay), QO_E_CONFIG); /* no joint */
    map.n_joints = 1;
    map.joints[0].slave = 1;
    map.joints[0].address = 65535;
    map.joints[0].fmt.type = QO_MODBUS_REG_INT32; /* runs past 65535 */
    assert_int_equal(qo_modbus_layout_build(&map, &lay), QO_E_CONFIG);
    assert_int_equal(lay.n_requests, 0);
    map.joints[0].address = 0;
    map.joints[0].fmt.type = QO_MODBUS_REG_TYPE_COUNT_;
    assert_int_equal(qo_modbus_layout_build(&map, &lay), QO_E_CONFIG);
    map.joints[0].fmt.type = QO_MODBUS_REG_INT32;
    map.n_slaves = 1;
    map.slaves[0].id = 1;
    map.slaves[0].max_registers = 1; /* a 32-bit value cannot fit */
    assert_int_equal(qo_modbus_layout_build(&map, &lay), QO_E_CONFIG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_maps),
        cmocka_unit_test(test_constant_only_slave),
        cmocka_unit_test(test_bad_maps),
    };
    return cmocka_run_group_tests_name("modbus_layout", tests, NULL, NULL);
}
