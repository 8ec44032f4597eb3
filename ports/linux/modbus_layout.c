/* Map -> the requests of one tick. Contract: modbus_layout.h. */
#include "linux/modbus_layout.h"

#include <stdlib.h>
#include <string.h>

struct cell {
    unsigned slave, address, width;
    int joint;      /* joint index, or -1 for a constant */
    uint16_t value; /* a constant's value */
};

static int cmp_cell(const void *a, const void *b)
{
    const struct cell *x = a, *y = b;
    if (x->slave != y->slave) return x->slave < y->slave ? -1 : 1;
    if (x->address != y->address) return x->address < y->address ? -1 : 1;
    return 0;
}

qo_status qo_modbus_layout_build(const qo_regmap *map, qo_modbus_layout *out)
{
    struct cell cells[QO_MODBUS_LAYOUT_MAX];
    size_t nc = 0, i, k;
    qo_modbus_layout_request *r = NULL;
    if (out == NULL) return QO_E_NULL;
    out->n_requests = 0;
    out->n_items = 0;
    if (map == NULL) return QO_E_NULL;
    if (map->n_joints == 0 || map->n_joints > QO_REGMAP_MAX_JOINTS ||
        map->n_slaves > QO_REGMAP_MAX_SLAVES)
        return QO_E_CONFIG;
    for (i = 0; i < map->n_joints; i++) {
        const qo_regmap_joint *j = &map->joints[i];
        const qo_regmap_slave *sl = qo_regmap_find_slave(map, j->slave);
        unsigned w = (unsigned)qo_modbus_reg_type_width(j->fmt.type);
        unsigned maxr = sl != NULL ? sl->max_registers : QO_REGMAP_MAX_REGISTERS;
        if (w == 0 || (unsigned)j->address + w > 65536u || w > maxr) return QO_E_CONFIG;
        cells[nc].slave = j->slave;
        cells[nc].address = j->address;
        cells[nc].width = w;
        cells[nc].joint = (int)i;
        cells[nc].value = 0;
        nc++;
    }
    for (i = 0; i < map->n_slaves; i++) {
        const qo_regmap_slave *sl = &map->slaves[i];
        if (sl->n_constant > QO_REGMAP_MAX_WRITES) return QO_E_CONFIG;
        for (k = 0; k < sl->n_constant; k++) {
            cells[nc].slave = sl->id;
            cells[nc].address = sl->constant[k].address;
            cells[nc].width = 1;
            cells[nc].joint = -1;
            cells[nc].value = sl->constant[k].value;
            nc++;
        }
    }
    qsort(cells, nc, sizeof cells[0], cmp_cell);
    for (i = 0; i < nc; i++) {
        const qo_regmap_slave *sl = qo_regmap_find_slave(map, cells[i].slave);
        unsigned maxr = sl != NULL ? sl->max_registers : QO_REGMAP_MAX_REGISTERS;
        if (maxr < 1 || maxr > QO_REGMAP_MAX_REGISTERS) maxr = QO_REGMAP_MAX_REGISTERS;
        if (r == NULL || r->slave != cells[i].slave || r->start + r->count != cells[i].address ||
            r->count + cells[i].width > maxr) {
            r = &out->req[out->n_requests++];
            memset(r, 0, sizeof *r);
            r->slave = cells[i].slave;
            r->gap_us = sl != NULL ? sl->gap_us : 0;
            r->start = (uint16_t)cells[i].address;
            r->first_item = out->n_items;
        }
        if (cells[i].joint >= 0) {
            out->item[out->n_items].joint = (size_t)cells[i].joint;
            out->item[out->n_items].offset = r->count;
            out->n_items++;
            r->n_items++;
        } else {
            r->regs[r->count] = cells[i].value;
        }
        r->count += cells[i].width;
    }
    return QO_OK;
}
