#include "linux/regmap.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ini.h>

enum sect_kind { SECT_NONE, SECT_JOINT, SECT_SLAVE };

/* Keys of a joint and of a slave, as bits of the "seen" mask (duplicate detection). */
enum {
    JK_SLAVE = 1 << 0, JK_ADDRESS = 1 << 1, JK_TYPE = 1 << 2, JK_ORDER = 1 << 3,
    JK_SCALE = 1 << 4, JK_OFFSET = 1 << 5, JK_INVERT = 1 << 6, JK_MIN = 1 << 7,
    JK_MAX = 1 << 8, JK_MAX_STEP = 1 << 9, JK_FEEDBACK = 1 << 10,
    SK_MAX_REGISTERS = 1 << 0, SK_GAP_US = 1 << 1, SK_INIT = 1 << 2, SK_DISABLE = 1 << 3,
    SK_CONSTANT = 1 << 4
};

struct parser {
    qo_regmap *map;
    const char *name;   /* file name for messages */
    char *err;
    size_t err_len;
    qo_status st;       /* first error */
    int line;           /* line being parsed */
    int at_line_start;
    int cont;           /* the line being parsed is an indented continuation line */
    int too_long;       /* swallowing the rest of an over-long line */
    int eof;            /* the input ended */
    size_t bytes;       /* bytes read so far (bounded by QO_REGMAP_MAX_BYTES) */
    char last_key[32];  /* key of the previous key line, for continuations */
    enum sect_kind kind;
    size_t cur;         /* index of the current joint or slave */
    unsigned seen;      /* keys seen in the current section */
    unsigned jseen[QO_REGMAP_MAX_JOINTS]; /* keys seen per joint, for "missing key" checks */
    /* input: exactly one of fp / text */
    FILE *fp;
    const char *text;
};

static void fail(struct parser *p, qo_status st, int line, const char *fmt, ...)
{
    va_list ap;
    int k;
    if (p->st != QO_OK) return; /* keep the first error: later ones often follow from it */
    p->st = st;
    if (p->err == NULL || p->err_len == 0) return;
    k = snprintf(p->err, p->err_len, "%s:%d: ", p->name, line);
    if (k < 0 || (size_t)k >= p->err_len) return;
    va_start(ap, fmt);
    vsnprintf(p->err + k, p->err_len - (size_t)k, fmt, ap);
    va_end(ap);
}

/* Integer in decimal or 0x hex; the whole string must be the number. */
static int parse_long(const char *s, long lo, long hi, long *out)
{
    char *end;
    long v;
    int base = 10;
    const char *q = s;
    if (*q == '-' || *q == '+') q++;
    if (q[0] == '0' && (q[1] == 'x' || q[1] == 'X')) base = 16;
    if (!isdigit((unsigned char)*q)) return -1;
    errno = 0;
    v = strtol(s, &end, base);
    if (errno != 0 || end == s || *end != '\0' || v < lo || v > hi) return -1;
    *out = v;
    return 0;
}

static int parse_double(const char *s, double *out)
{
    char *end;
    double v;
    errno = 0;
    v = strtod(s, &end);
    if (end == s || *end != '\0' || !isfinite(v)) return -1;
    *out = v;
    return 0;
}

static int parse_bool(const char *s, int *out)
{
    if (!strcmp(s, "1") || !strcmp(s, "yes") || !strcmp(s, "true") || !strcmp(s, "on")) {
        *out = 1;
        return 0;
    }
    if (!strcmp(s, "0") || !strcmp(s, "no") || !strcmp(s, "false") || !strcmp(s, "off")) {
        *out = 0;
        return 0;
    }
    return -1;
}

qo_status qo_regmap_parse_writes(const char *text, qo_regmap_write *out, size_t max, size_t *n)
{
    const char *p = text;
    size_t k = 0;
    if (n == NULL) return QO_E_NULL;
    *n = 0;
    if (text == NULL || (out == NULL && max > 0)) return QO_E_NULL;
    for (;;) {
        char buf[64];
        size_t len = 0;
        char *eq;
        long a, v;
        while (*p == ' ' || *p == '\t' || *p == ',') p++;
        if (*p == '\0') break;
        while (p[len] != '\0' && p[len] != ',' && p[len] != ' ' && p[len] != '\t') len++;
        if (len >= sizeof buf) return QO_E_CONFIG;
        memcpy(buf, p, len);
        buf[len] = '\0';
        p += len;
        eq = strchr(buf, '=');
        if (eq == NULL) return QO_E_CONFIG;
        *eq = '\0';
        if (parse_long(buf, 0, 65535, &a) != 0 || parse_long(eq + 1, -32768, 65535, &v) != 0)
            return QO_E_CONFIG;
        if (k >= max) return QO_E_CAPACITY;
        out[k].address = (uint16_t)a;
        out[k].value = (uint16_t)(v < 0 ? v + 65536 : v);
        k++;
    }
    *n = k;
    return QO_OK;
}

static qo_regmap_slave *find_slave(qo_regmap *map, unsigned id)
{
    size_t i;
    for (i = 0; i < map->n_slaves; i++)
        if (map->slaves[i].id == id) return &map->slaves[i];
    return NULL;
}

const qo_regmap_slave *qo_regmap_find_slave(const qo_regmap *map, unsigned id)
{
    size_t i;
    if (map == NULL) return NULL;
    for (i = 0; i < map->n_slaves; i++)
        if (map->slaves[i].id == id) return &map->slaves[i];
    return NULL;
}

static qo_regmap_slave *add_slave(struct parser *p, unsigned id, int line)
{
    qo_regmap_slave *s;
    if (p->map->n_slaves >= QO_REGMAP_MAX_SLAVES) {
        fail(p, QO_E_CAPACITY, line, "more than %d slaves", QO_REGMAP_MAX_SLAVES);
        return NULL;
    }
    s = &p->map->slaves[p->map->n_slaves++];
    memset(s, 0, sizeof *s);
    s->id = id;
    s->max_registers = QO_REGMAP_MAX_REGISTERS;
    s->line = line;
    return s;
}

static void begin_section(struct parser *p, const char *sect)
{
    p->kind = SECT_NONE;
    p->seen = 0;
    if (strncmp(sect, "joint.", 6) == 0) {
        const char *nm = sect + 6;
        size_t i;
        qo_regmap_joint *j;
        if (*nm == '\0' || strlen(nm) >= QO_REGMAP_NAME_MAX) {
            fail(p, QO_E_CONFIG, p->line, "joint name must be 1..%d characters",
                 QO_REGMAP_NAME_MAX - 1);
            return;
        }
        for (i = 0; i < p->map->n_joints; i++) {
            if (strcmp(p->map->joints[i].name, nm) == 0) {
                fail(p, QO_E_CONFIG, p->line, "duplicate section [%s] (first on line %d)", sect,
                     p->map->joints[i].line);
                return;
            }
        }
        if (p->map->n_joints >= QO_REGMAP_MAX_JOINTS) {
            fail(p, QO_E_CAPACITY, p->line, "more than %d joints", QO_REGMAP_MAX_JOINTS);
            return;
        }
        j = &p->map->joints[p->map->n_joints];
        memset(j, 0, sizeof *j);
        memcpy(j->name, nm, strlen(nm) + 1);
        j->fmt.type = QO_MODBUS_REG_TYPE_COUNT_; /* "unset" until type = ... */
        j->fmt.order = QO_MODBUS_REG_HI_FIRST;
        j->fmt.scale = 1.0;
        j->min = -INFINITY;
        j->max = INFINITY;
        j->line = p->line;
        p->cur = p->map->n_joints++;
        p->kind = SECT_JOINT;
    } else if (strncmp(sect, "slave.", 6) == 0) {
        long id;
        qo_regmap_slave *s;
        if (parse_long(sect + 6, 1, 255, &id) != 0) {
            fail(p, QO_E_CONFIG, p->line, "bad slave id in [%s] (1..255)", sect);
            return;
        }
        s = find_slave(p->map, (unsigned)id);
        if (s != NULL) {
            fail(p, QO_E_CONFIG, p->line, "duplicate section [%s] (first on line %d)", sect,
                 s->line);
            return;
        }
        s = add_slave(p, (unsigned)id, p->line);
        if (s == NULL) return;
        p->cur = (size_t)(s - p->map->slaves);
        p->kind = SECT_SLAVE;
    } else {
        fail(p, QO_E_CONFIG, p->line, "unknown section [%s] (expected [joint.NAME] or [slave.ID])",
             sect);
    }
}

static int mark(struct parser *p, unsigned bit, const char *key)
{
    if (p->seen & bit) {
        fail(p, QO_E_CONFIG, p->line, "duplicate key '%s'", key);
        return -1;
    }
    p->seen |= bit;
    if (p->kind == SECT_JOINT) p->jseen[p->cur] = p->seen;
    return 0;
}

static void joint_key(struct parser *p, const char *key, const char *val)
{
    qo_regmap_joint *j = &p->map->joints[p->cur];
    long l;
    double d;
    int b;
#define BAD(what) fail(p, QO_E_CONFIG, p->line, "joint '%s': bad %s '%s'", j->name, what, val)
    if (!strcmp(key, "slave")) {
        if (mark(p, JK_SLAVE, key)) return;
        if (parse_long(val, 1, 255, &l)) BAD("slave (1..255)"); else j->slave = (unsigned)l;
    } else if (!strcmp(key, "address")) {
        if (mark(p, JK_ADDRESS, key)) return;
        if (parse_long(val, 0, 65535, &l)) BAD("address (0..65535)"); else j->address = (uint16_t)l;
    } else if (!strcmp(key, "type")) {
        if (mark(p, JK_TYPE, key)) return;
        if (!strcmp(val, "int16")) j->fmt.type = QO_MODBUS_REG_INT16;
        else if (!strcmp(val, "uint16")) j->fmt.type = QO_MODBUS_REG_UINT16;
        else if (!strcmp(val, "int32")) j->fmt.type = QO_MODBUS_REG_INT32;
        else if (!strcmp(val, "uint32")) j->fmt.type = QO_MODBUS_REG_UINT32;
        else if (!strcmp(val, "float32")) j->fmt.type = QO_MODBUS_REG_FLOAT32;
        else BAD("type (int16 uint16 int32 uint32 float32)");
    } else if (!strcmp(key, "order")) {
        if (mark(p, JK_ORDER, key)) return;
        if (!strcmp(val, "hi-first")) j->fmt.order = QO_MODBUS_REG_HI_FIRST;
        else if (!strcmp(val, "lo-first")) j->fmt.order = QO_MODBUS_REG_LO_FIRST;
        else BAD("order (hi-first or lo-first)");
    } else if (!strcmp(key, "scale")) {
        if (mark(p, JK_SCALE, key)) return;
        if (parse_double(val, &d) || d == 0.0) BAD("scale (finite, non-zero)"); else j->fmt.scale = d;
    } else if (!strcmp(key, "offset")) {
        if (mark(p, JK_OFFSET, key)) return;
        if (parse_double(val, &d)) BAD("offset"); else j->fmt.offset = d;
    } else if (!strcmp(key, "invert")) {
        if (mark(p, JK_INVERT, key)) return;
        if (parse_bool(val, &b)) BAD("invert (yes/no)"); else j->fmt.invert = b;
    } else if (!strcmp(key, "min")) {
        if (mark(p, JK_MIN, key)) return;
        if (parse_double(val, &d)) BAD("min"); else j->min = d;
    } else if (!strcmp(key, "max")) {
        if (mark(p, JK_MAX, key)) return;
        if (parse_double(val, &d)) BAD("max"); else j->max = d;
    } else if (!strcmp(key, "max_step")) {
        if (mark(p, JK_MAX_STEP, key)) return;
        if (parse_double(val, &d) || d <= 0.0) BAD("max_step (> 0)"); else j->max_step = d;
    } else if (!strcmp(key, "feedback")) {
        if (mark(p, JK_FEEDBACK, key)) return;
        if (parse_long(val, 0, 65535, &l)) BAD("feedback address (0..65535)");
        else {
            j->feedback = (uint16_t)l;
            j->has_feedback = 1;
        }
    } else {
        fail(p, QO_E_CONFIG, p->line, "unknown key '%s' in [joint.%s]", key, j->name);
    }
#undef BAD
}

/* Parses a write list; a continuation line appends to the entries already read. */
static void write_list(struct parser *p, const char *key, const char *val, qo_regmap_write *out,
                       size_t *n)
{
    size_t have = p->cont ? *n : 0, got = 0;
    qo_status st = qo_regmap_parse_writes(val, out + have, QO_REGMAP_MAX_WRITES - have, &got);
    *n = have + got;
    if (st == QO_E_CAPACITY)
        fail(p, st, p->line, "'%s' has more than %d entries", key, QO_REGMAP_MAX_WRITES);
    else if (st != QO_OK)
        fail(p, QO_E_CONFIG, p->line, "bad '%s' list '%s' (expected ADDR=VALUE, ...)", key, val);
}

static void slave_key(struct parser *p, const char *key, const char *val)
{
    qo_regmap_slave *s = &p->map->slaves[p->cur];
    long l;
    if (!strcmp(key, "max_registers")) {
        if (mark(p, SK_MAX_REGISTERS, key)) return;
        if (parse_long(val, 1, QO_REGMAP_MAX_REGISTERS, &l))
            fail(p, QO_E_CONFIG, p->line, "bad max_registers '%s' (1..%d)", val,
                 QO_REGMAP_MAX_REGISTERS);
        else s->max_registers = (unsigned)l;
    } else if (!strcmp(key, "gap_us")) {
        if (mark(p, SK_GAP_US, key)) return;
        if (parse_long(val, 0, 1000000, &l))
            fail(p, QO_E_CONFIG, p->line, "bad gap_us '%s' (0..1000000)", val);
        else s->gap_us = (unsigned)l;
    } else if (!strcmp(key, "init")) {
        if (!p->cont && mark(p, SK_INIT, key)) return;
        write_list(p, key, val, s->init, &s->n_init);
    } else if (!strcmp(key, "disable")) {
        if (!p->cont && mark(p, SK_DISABLE, key)) return;
        write_list(p, key, val, s->disable, &s->n_disable);
    } else if (!strcmp(key, "constant")) {
        if (!p->cont && mark(p, SK_CONSTANT, key)) return;
        write_list(p, key, val, s->constant, &s->n_constant);
    } else {
        fail(p, QO_E_CONFIG, p->line, "unknown key '%s' in [slave.%u]", key, s->id);
    }
}

static int handler(void *user, const char *section, const char *name, const char *value)
{
    struct parser *p = user;
    (void)section; /* the current section is tracked by the reader, which knows its line */
    if (p->cont && !(p->kind == SECT_SLAVE && (!strcmp(name, "init") || !strcmp(name, "disable") ||
                                               !strcmp(name, "constant")))) {
        fail(p, QO_E_CONFIG, p->line, "indented line continues '%s', which takes one value", name);
        return 1;
    }
    switch (p->kind) {
    case SECT_JOINT: joint_key(p, name, value); break;
    case SECT_SLAVE: slave_key(p, name, value); break;
    default:
        if (section[0] == '\0') fail(p, QO_E_CONFIG, p->line, "key '%s' outside a section", name);
        break; /* keys of a rejected section: its error is already recorded */
    }
    return 1;
}

/* One byte of the input, or -1 at its end. Counts what was read so that an endless input
 * (/dev/zero, a FIFO) stops at QO_REGMAP_MAX_BYTES instead of being read for ever. */
static int next_byte(struct parser *p)
{
    int c;
    if (p->fp != NULL) {
        c = getc(p->fp);
        if (c == EOF) return -1;
    } else {
        if (*p->text == '\0') return -1;
        c = (unsigned char)*p->text++;
    }
    p->bytes++;
    return c;
}

/* inih calls this fgets-like reader once per line. It reads the bytes itself (not fgets):
 * fgets cannot say how many bytes it stored when one is NUL, and a NUL would end the line
 * for strlen, so what follows it (after a comment, say) would be read as a key. Counting
 * lines and spotting section headers here gives every message its line number. Bounded:
 * at most QO_REGMAP_MAX_BYTES bytes and QO_REGMAP_MAX_LINES lines are read. */
static char *reader(char *str, int num, void *stream)
{
    struct parser *p = stream;
    size_t len = 0;
    int c = 0, nul = 0;
    if (p->st != QO_OK || p->eof || num < 3) return NULL; /* first error ends the parse */
    while (len < (size_t)num - 1) {
        c = next_byte(p);
        if (c < 0) {
            p->eof = 1;
            break;
        }
        if (c == 0) nul = 1;
        str[len++] = (char)c;
        if (c == '\n') break;
    }
    str[len] = '\0';
    if (len == 0) return NULL;
    if (p->line == 0 && p->at_line_start && len >= 3 && (unsigned char)str[0] == 0xEF &&
        (unsigned char)str[1] == 0xBB && (unsigned char)str[2] == 0xBF) {
        /* A UTF-8 byte-order mark (written by some Windows editors) is not content. */
        memmove(str, str + 3, len - 2);
        len -= 3;
        if (len == 0) return NULL; /* the file is the mark alone */
    }
    if (p->bytes > QO_REGMAP_MAX_BYTES || (p->at_line_start && p->line >= QO_REGMAP_MAX_LINES)) {
        fail(p, QO_E_CAPACITY, p->line, "more than %d bytes or %d lines: not a register map",
             QO_REGMAP_MAX_BYTES, QO_REGMAP_MAX_LINES);
        return NULL;
    }
    if (nul) {
        fail(p, QO_E_CONFIG, p->line + (p->at_line_start ? 1 : 0),
             "NUL byte (not a text file?)");
        return NULL;
    }
    if (p->too_long) {
        /* rest of an over-long line: hand inih a blank line instead */
        p->too_long = !(str[len - 1] == '\n');
        p->at_line_start = !p->too_long;
        str[0] = '\n';
        str[1] = '\0';
        return str;
    }
    if (str[len - 1] != '\n' && len == (size_t)num - 1) {
        /* inih would split the line and read its tail as a new key: report it instead */
        p->line++;
        fail(p, QO_E_CONFIG, p->line,
             "line longer than %d characters (continue a long list on indented lines)", num - 2);
        p->too_long = 1;
        p->at_line_start = 0;
        str[0] = '\n';
        str[1] = '\0';
        return str;
    }
    if (p->at_line_start) {
        const char *q = str;
        p->line++;
        while (*q == ' ' || *q == '\t') q++;
        /* inih's rule: an indented, non-comment line continues the previous key's value */
        p->cont = q > str && *q != '\0' && *q != '\n' && *q != '\r' && *q != ';' && *q != '#';
        if (*q == '[') {
            const char *e = strchr(q, ']');
            if (e != NULL && (size_t)(e - q) < 80) {
                char sect[80];
                memcpy(sect, q + 1, (size_t)(e - q - 1));
                sect[e - q - 1] = '\0';
                begin_section(p, sect);
            }
        }
    }
    p->at_line_start = str[len - 1] == '\n';
    return str;
}

static int ranges_overlap(unsigned a, unsigned na, unsigned b, unsigned nb)
{
    return a < b + nb && b < a + na;
}

struct span {
    unsigned slave, addr, n, line;
    const char *what;
    char label[48];
};

static void validate(struct parser *p)
{
    qo_regmap *map = p->map;
    size_t i, k, ns = 0;
    static const size_t max_spans = QO_REGMAP_MAX_JOINTS * 2 +
                                    QO_REGMAP_MAX_SLAVES * QO_REGMAP_MAX_WRITES;
    struct span *sp;
    if (p->st != QO_OK) return;
    if (map->n_joints == 0) {
        fail(p, QO_E_CONFIG, 0, "no [joint.NAME] section");
        return;
    }
    for (i = 0; i < map->n_joints; i++) {
        qo_regmap_joint *j = &map->joints[i];
        unsigned seen = p->jseen[i];
        const char *missing = !(seen & JK_SLAVE) ? "slave" : !(seen & JK_ADDRESS) ? "address"
                            : !(seen & JK_TYPE) ? "type" : NULL;
        size_t w;
        if (missing != NULL) {
            fail(p, QO_E_CONFIG, j->line, "joint '%s' has no '%s'", j->name, missing);
            return;
        }
        w = qo_modbus_reg_type_width(j->fmt.type);
        if ((unsigned)j->address + w - 1 > 65535u ||
            (j->has_feedback && (unsigned)j->feedback + w - 1 > 65535u)) {
            fail(p, QO_E_CONFIG, j->line, "joint '%s': registers run past 65535", j->name);
            return;
        }
        if (j->min > j->max) {
            fail(p, QO_E_CONFIG, j->line, "joint '%s': min > max", j->name);
            return;
        }
        if (find_slave(map, j->slave) == NULL && add_slave(p, j->slave, 0) == NULL) return;
    }
    sp = calloc(max_spans, sizeof *sp);
    if (sp == NULL) {
        fail(p, QO_E_CAPACITY, 0, "out of memory");
        return;
    }
    for (i = 0; i < map->n_joints; i++) {
        const qo_regmap_joint *j = &map->joints[i];
        unsigned w = (unsigned)qo_modbus_reg_type_width(j->fmt.type);
        sp[ns].slave = j->slave; sp[ns].addr = j->address; sp[ns].n = w;
        sp[ns].line = (unsigned)j->line;
        snprintf(sp[ns].label, sizeof sp[ns].label, "joint '%s' target", j->name);
        ns++;
        if (j->has_feedback) {
            sp[ns] = sp[ns - 1];
            sp[ns].addr = j->feedback;
            snprintf(sp[ns].label, sizeof sp[ns].label, "joint '%s' feedback", j->name);
            ns++;
        }
    }
    for (i = 0; i < map->n_slaves; i++) {
        const qo_regmap_slave *s = &map->slaves[i];
        for (k = 0; k < s->n_constant; k++) {
            sp[ns].slave = s->id; sp[ns].addr = s->constant[k].address; sp[ns].n = 1;
            sp[ns].line = (unsigned)s->line;
            snprintf(sp[ns].label, sizeof sp[ns].label, "slave %u constant 0x%04X", s->id,
                     s->constant[k].address);
            ns++;
        }
    }
    for (i = 0; i < ns && p->st == QO_OK; i++) {
        for (k = 0; k < i; k++) {
            if (sp[i].slave == sp[k].slave &&
                ranges_overlap(sp[i].addr, sp[i].n, sp[k].addr, sp[k].n)) {
                /* Two feedback views of one register are fine (a joint may read what another
                 * reads); anything written must be written by one owner only. */
                if (strstr(sp[i].label, "feedback") && strstr(sp[k].label, "feedback")) continue;
                fail(p, QO_E_CONFIG, (int)sp[i].line, "%s (0x%04X) overlaps %s (0x%04X) on slave %u",
                     sp[i].label, sp[i].addr, sp[k].label, sp[k].addr, sp[i].slave);
                break;
            }
        }
    }
    free(sp);
}

static qo_status run(struct parser *p)
{
    int rc = ini_parse_stream(reader, p, handler, p);
    if (p->fp != NULL && ferror(p->fp) && p->st == QO_OK) fail(p, QO_E_IO, 0, "cannot read");
    if (rc == -1 && p->st == QO_OK) fail(p, QO_E_IO, 0, "cannot read");
    else if (rc == -2 && p->st == QO_OK) fail(p, QO_E_CAPACITY, 0, "out of memory");
    else if (rc > 0 && p->st == QO_OK)
        fail(p, QO_E_CONFIG, rc, "syntax error (expected KEY = VALUE or [SECTION])");
    validate(p);
    if (p->st != QO_OK) {
        p->map->n_joints = 0;
        p->map->n_slaves = 0;
    }
    return p->st;
}

static void init_parser(struct parser *p, qo_regmap *map, const char *name, char *err,
                        size_t err_len)
{
    memset(p, 0, sizeof *p);
    p->map = map;
    p->name = name;
    p->err = err;
    p->err_len = err_len;
    p->at_line_start = 1;
    if (err != NULL && err_len > 0) err[0] = '\0';
    memset(map, 0, sizeof *map);
}

qo_status qo_regmap_load(const char *path, qo_regmap *map, char *err, size_t err_len)
{
    struct parser p;
    qo_status st;
    if (err != NULL && err_len > 0) err[0] = '\0';
    if (map == NULL) return QO_E_NULL;
    memset(map, 0, sizeof *map);
    if (path == NULL) return QO_E_NULL;
    init_parser(&p, map, path, err, err_len);
    p.fp = fopen(path, "r");
    if (p.fp == NULL) {
        fail(&p, QO_E_IO, 0, "cannot open: %s", strerror(errno));
        return p.st;
    }
    st = run(&p);
    fclose(p.fp);
    return st;
}

qo_status qo_regmap_parse(const char *text, const char *name, qo_regmap *map, char *err,
                          size_t err_len)
{
    struct parser p;
    if (err != NULL && err_len > 0) err[0] = '\0';
    if (map == NULL) return QO_E_NULL;
    memset(map, 0, sizeof *map);
    if (text == NULL) return QO_E_NULL;
    init_parser(&p, map, name != NULL ? name : "<string>", err, err_len);
    p.text = text;
    return run(&p);
}
