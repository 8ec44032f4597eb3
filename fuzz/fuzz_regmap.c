/*
 * fuzz/fuzz_regmap.c - the register-map INI parser (ports/linux/regmap.h) fed raw text:
 * qo_regmap_parse on the whole input, qo_regmap_parse_writes on it too, with an error buffer
 * whose size (1..200) comes from the input length so truncation is exercised.
 * Properties from the header: status QO_OK, QO_E_CONFIG or QO_E_CAPACITY; on error the map is
 * empty and err is "NAME:LINE: reason" (or its truncation), NUL-terminated inside err_len; on
 * QO_OK err is "" and every field is inside its documented range: 1..64 joints, slave ids
 * 1..255, a known type and word order, finite non-zero scale, finite offset, min <= max,
 * max_step >= 0, target registers inside the 16-bit address space and not overlapping
 * another joint's on the same slave, every joint's slave present, slave settings in range.
 */
#include "fuzz_common.h"
#include "linux/regmap.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

static void fuzz_regmap_check_map(const qo_regmap *m)
{
    size_t i, j;
    QO_FUZZ_CHECK(m->n_joints >= 1 && m->n_joints <= QO_REGMAP_MAX_JOINTS, "n_joints %zu", m->n_joints);
    QO_FUZZ_CHECK(m->n_slaves >= 1 && m->n_slaves <= QO_REGMAP_MAX_SLAVES, "n_slaves %zu", m->n_slaves);
    for (i = 0; i < m->n_joints; i++) {
        const qo_regmap_joint *jt = &m->joints[i];
        size_t w = qo_modbus_reg_type_width(jt->fmt.type);
        QO_FUZZ_CHECK(memchr(jt->name, '\0', sizeof jt->name) != NULL, "joint %zu name not terminated", i);
        QO_FUZZ_CHECK(jt->slave >= 1 && jt->slave <= 255, "joint %zu slave %u", i, jt->slave);
        QO_FUZZ_CHECK(w == 1 || w == 2, "joint %zu type %d", i, (int)jt->fmt.type);
        QO_FUZZ_CHECK(jt->fmt.order == QO_MODBUS_REG_HI_FIRST || jt->fmt.order == QO_MODBUS_REG_LO_FIRST, "joint %zu order", i);
        QO_FUZZ_CHECK(isfinite(jt->fmt.scale) && jt->fmt.scale != 0.0 && isfinite(jt->fmt.offset),
                      "joint %zu scale %g offset %g", i, jt->fmt.scale, jt->fmt.offset);
        QO_FUZZ_CHECK(!isnan(jt->min) && !isnan(jt->max) && jt->min <= jt->max, "joint %zu limits [%g, %g]", i,
                      jt->min, jt->max);
        QO_FUZZ_CHECK(isfinite(jt->max_step) && jt->max_step >= 0.0, "joint %zu max_step %g", i, jt->max_step);
        QO_FUZZ_CHECK((unsigned long)jt->address + w - 1 <= 0xFFFFul, "joint %zu address 0x%X width %zu", i,
                      (unsigned)jt->address, w);
        if (jt->has_feedback)
            QO_FUZZ_CHECK((unsigned long)jt->feedback + w - 1 <= 0xFFFFul, "joint %zu feedback 0x%X", i,
                          (unsigned)jt->feedback);
        QO_FUZZ_CHECK(qo_regmap_find_slave(m, jt->slave) != NULL, "joint %zu slave %u has no entry", i, jt->slave);
        for (j = 0; j < i; j++) {
            const qo_regmap_joint *o = &m->joints[j];
            size_t wo = qo_modbus_reg_type_width(o->fmt.type);
            if (o->slave != jt->slave) continue;
            QO_FUZZ_CHECK((unsigned long)jt->address + w <= o->address || (unsigned long)o->address + wo <= jt->address,
                          "joints %zu and %zu overlap on slave %u", j, i, jt->slave);
            QO_FUZZ_CHECK(strcmp(o->name, jt->name) != 0, "duplicate joint name '%s'", jt->name);
        }
    }
    for (i = 0; i < m->n_slaves; i++) {
        const qo_regmap_slave *s = &m->slaves[i];
        QO_FUZZ_CHECK(s->id >= 1 && s->id <= 255, "slave %zu id %u", i, s->id);
        QO_FUZZ_CHECK(s->max_registers >= 1 && s->max_registers <= QO_REGMAP_MAX_REGISTERS, "slave %u max_registers %u",
                      s->id, s->max_registers);
        QO_FUZZ_CHECK(s->gap_us <= 1000000u, "slave %u gap_us %u", s->id, s->gap_us);
        QO_FUZZ_CHECK(s->n_init <= QO_REGMAP_MAX_WRITES && s->n_disable <= QO_REGMAP_MAX_WRITES
                      && s->n_constant <= QO_REGMAP_MAX_WRITES, "slave %u write list sizes", s->id);
        for (j = 0; j < i; j++) QO_FUZZ_CHECK(m->slaves[j].id != s->id, "slave %u listed twice", s->id);
    }
}

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    static qo_regmap map;   /* ~20 KiB: kept off the stack; rewritten by every call */
    char err[200];
    size_t err_len = 1 + size % sizeof err, n, i;
    char *text = malloc(size + 1);
    qo_regmap_write w[QO_REGMAP_MAX_WRITES];
    qo_status st;

    if (text == NULL) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    memset(err, 'X', sizeof err);

    st = qo_regmap_parse(text, "fz.ini", &map, err, err_len);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_CONFIG || st == QO_E_CAPACITY, "regmap_parse status %d", (int)st);
    QO_FUZZ_CHECK(memchr(err, '\0', err_len) != NULL, "err not terminated inside err_len %zu", err_len);
    if (st == QO_OK) {
        QO_FUZZ_CHECK(err[0] == '\0', "err '%s' on success", err);
        fuzz_regmap_check_map(&map);
    } else {
        QO_FUZZ_CHECK(map.n_joints == 0 && map.n_slaves == 0, "map not empty on error %d", (int)st);
        QO_FUZZ_CHECK(err_len < 8 || strncmp(err, "fz.ini:", 7) == 0, "err '%s' does not name the file", err);
    }

    /* write lists: "ADDR=VALUE, ..." */
    n = 99;
    st = qo_regmap_parse_writes(text, w, (size_t)(size % (QO_REGMAP_MAX_WRITES + 1)), &n);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_CONFIG || st == QO_E_CAPACITY, "parse_writes status %d", (int)st);
    if (st == QO_OK) QO_FUZZ_CHECK(n <= size % (QO_REGMAP_MAX_WRITES + 1), "parse_writes n %zu", n);
    else QO_FUZZ_CHECK(n == 0, "parse_writes n %zu on error", n);
    for (i = 0; i < n; i++) (void)w[i].value;
    free(text);
    return 0;
}
