/*
 * ports/linux/regmap.h - the Modbus register map of a drive bank, read from an INI file.
 *
 * Index:
 *   qo_regmap, qo_regmap_joint, qo_regmap_slave, qo_regmap_write
 *                            the parsed map (fixed capacity)
 *   qo_regmap_load()         parse a file (inih)
 *   qo_regmap_parse()        parse text in memory (same rules; for tests and embedded maps)
 *   qo_regmap_find_slave()   the settings of one slave id
 *   qo_regmap_parse_writes() parse "ADDR=VALUE, ..." (also used by the CLI)
 *
 * File format (the .ini files in examples/maps are worked examples):
 *
 *   # comment lines start with '#' or ';'; ';' also starts an inline comment
 *   [slave.1]                 ; optional: slave id 1..255 (255 = Modbus TCP default unit id)
 *   max_registers = 123       ; 1..123, registers per FC16 write (Delta ASDA: 10)
 *   gap_us = 0                ; 0..1000000, silence kept after every request to this slave
 *   init = 0x6200=1, 0x0405=1 ; FC06 writes sent in this order after every (re)connection
 *   disable = 0x6002=0x40     ; FC06 writes sent by the sink's "disable" failure action
 *   constant = 0x6203=600     ; registers rewritten with the targets in every tick; merged into
 *                             ; the same FC16 when contiguous (Leadshine PR block: speed, trigger)
 *
 *   [joint.shoulder]          ; one section per joint, in file order = the sink's joint order
 *   slave = 1                 ; required, 1..255
 *   address = 0x6201          ; required, 0-based PDU address, decimal or 0x hex (not 4xxxx)
 *   type = int32              ; required: int16 uint16 int32 uint32 float32
 *   order = hi-first          ; hi-first (ABCD, default) | lo-first (CDAB); 32-bit types only
 *   scale = 1591.549          ; register units per joint unit, finite, non-zero (default 1)
 *   offset = 0                ; raw register value at joint position 0 (default 0)
 *   invert = no               ; yes/no, true/false, 1/0 (default no)
 *   min = -3.14               ; joint limits in joint units (default: none, only the type range)
 *   max = 3.14
 *   max_step = 0.01           ; largest change per tick in joint units, > 0 (default: unlimited)
 *   feedback = 0x602A         ; optional address of the actual position, same type/order/scale
 *
 * Lines are at most 198 characters (inih's buffer); a longer write list continues on
 * indented lines, which append to it (comment lines may sit between them):
 *   constant = 0x6200=1, 0x6203=600,
 *              0x6207=0x10
 * Values: integers are decimal or 0x hex (a leading 0 is decimal, not octal); register values
 * in write lists are 0..65535 or -32768..-1 (two's complement). Unknown sections or keys,
 * duplicate sections or keys, bad values, registers of one slave that overlap (targets,
 * constants, feedback) and a map with no joint are errors. The error text is
 * "FILE:LINE: reason" (LINE 0 when the problem is not on one line). Section headers are seen
 * by our line reader (inih's handler gets no line number in Debian's build), so an empty
 * [joint.X] is reported too. Slaves used by joints but without a section get the defaults.
 *
 * Input is text: a NUL byte anywhere is an error (never the end of a line), a UTF-8
 * byte-order mark at the start is skipped, and reading stops with QO_E_CAPACITY after
 * QO_REGMAP_MAX_BYTES bytes or QO_REGMAP_MAX_LINES lines (so /dev/zero or a FIFO cannot
 * hang the reader).
 *
 * Capacity is fixed (no heap): QO_REGMAP_MAX_JOINTS joints, QO_REGMAP_MAX_SLAVES slaves,
 * QO_REGMAP_MAX_WRITES entries per write list. A qo_regmap is about 20 KiB.
 */
#ifndef QORIENT_REGMAP_H
#define QORIENT_REGMAP_H

#include <stddef.h>
#include <stdint.h>

#include "qorient/status.h"
#include "linux/modbus_reg.h"

#define QO_REGMAP_MAX_JOINTS 64
#define QO_REGMAP_MAX_SLAVES 16
#define QO_REGMAP_MAX_WRITES 16
#define QO_REGMAP_NAME_MAX 32      /* joint name, including the terminating NUL */
#define QO_REGMAP_MAX_REGISTERS 123 /* MODBUS_MAX_WRITE_REGISTERS */
#define QO_REGMAP_MAX_BYTES (1024 * 1024) /* a map file is read up to this size ... */
#define QO_REGMAP_MAX_LINES 20000         /* ... and this many lines, then refused */

typedef struct qo_regmap_write {
    uint16_t address;
    uint16_t value;
} qo_regmap_write;

typedef struct qo_regmap_joint {
    char name[QO_REGMAP_NAME_MAX];
    unsigned slave;          /* 1..255 */
    uint16_t address;        /* first target register */
    qo_modbus_reg_format fmt;
    double min, max;         /* joint units; -INFINITY / INFINITY when unset */
    double max_step;         /* joint units per tick; 0 = unlimited */
    int has_feedback;
    uint16_t feedback;       /* first feedback register when has_feedback */
    int line;                /* line of the [joint.NAME] header */
} qo_regmap_joint;

typedef struct qo_regmap_slave {
    unsigned id;             /* 1..255 */
    unsigned max_registers;  /* 1..123 */
    unsigned gap_us;         /* 0..1000000 */
    qo_regmap_write init[QO_REGMAP_MAX_WRITES];
    size_t n_init;
    qo_regmap_write disable[QO_REGMAP_MAX_WRITES];
    size_t n_disable;
    qo_regmap_write constant[QO_REGMAP_MAX_WRITES];
    size_t n_constant;
    int line;                /* line of [slave.ID], 0 for a slave without a section */
} qo_regmap_slave;

typedef struct qo_regmap {
    qo_regmap_joint joints[QO_REGMAP_MAX_JOINTS];
    size_t n_joints;
    qo_regmap_slave slaves[QO_REGMAP_MAX_SLAVES];
    size_t n_slaves;         /* every slave a joint uses, plus every [slave.*] section */
} qo_regmap;

/* Parses the INI file at `path` into *map. On error writes "FILE:LINE: reason" to err
 * (err_len > 0; truncated to fit; may be NULL) and leaves *map empty (n_joints = n_slaves = 0).
 * Returns QO_OK; QO_E_NULL (path or map NULL); QO_E_IO (cannot open/read the file);
 * QO_E_CONFIG (any content error, a NUL byte); QO_E_CAPACITY (more joints/slaves/writes
 * than the fixed capacity, or more than QO_REGMAP_MAX_BYTES / QO_REGMAP_MAX_LINES of input). err is "" on success. */
qo_status qo_regmap_load(const char *path, qo_regmap *map, char *err, size_t err_len);

/* As qo_regmap_load, for NUL-terminated `text`; `name` (may be NULL: "<string>") is the file
 * name used in error messages. */
qo_status qo_regmap_parse(const char *text, const char *name, qo_regmap *map, char *err,
                          size_t err_len);

/* The slave with this id, or NULL (also for a NULL map). */
const qo_regmap_slave *qo_regmap_find_slave(const qo_regmap *map, unsigned id);

/* Parses "ADDR=VALUE, ADDR=VALUE ..." (commas and/or blanks between entries) into
 * out[0..max-1], *n entries. Returns QO_OK; QO_E_NULL; QO_E_CONFIG for a malformed entry or
 * value out of range; QO_E_CAPACITY for more than max entries. *n is 0 on error. */
qo_status qo_regmap_parse_writes(const char *text, qo_regmap_write *out, size_t max, size_t *n);

#endif /* QORIENT_REGMAP_H */
