/*
 * The `qorient` command: one entry point per subcommand plus shared text helpers.
 * Every subcommand follows the same habits: getopt_long options, `--help`, one record per
 * line in and out, `error: REASON` in place of a record that fails, a message naming the
 * line on standard error, exit status 0 (all good), 1 (some record failed) or 2 (usage).
 */
#ifndef QORIENT_CLI_H
#define QORIENT_CLI_H

#include <stddef.h>
#include <stdio.h>

#include "qorient/euler.h"
#include "qorient/motion.h"
#include "qorient/spline.h"
#include "qorient/status.h"
#include "qorient/traj.h"

/* Subcommands: argv[0] is the subcommand name. Return the process exit status. */
int qo_cli_version(int argc, char **argv);
int qo_cli_convert(int argc, char **argv);
int qo_cli_slerp(int argc, char **argv);
int qo_cli_gimbal(int argc, char **argv);
int qo_cli_sim(int argc, char **argv);
/* `qorient plan`: keyframes (spline profiles) or targets (trapezoid|scurve), plan.c. */
int qo_cli_plan(int argc, char **argv);
int qo_cli_stream(int argc, char **argv);

/* ---- one number parser for option values (util.c) ---- */

/* A scalar option value: the whole of arg a finite number in [lo, hi]. Returns 0, or 2 after a
 * message naming the option, the value, the range and its unit. */
int qo_cli_number(const char *who, const char *opt, const char *arg, double lo, double hi,
                  const char *unit, double *out);
/* A count option value (--max-samples): the whole of arg a whole number in [lo, hi]. Returns
 * 0, or 2 after a message naming the option, the value and the range. */
int qo_cli_count(const char *who, const char *opt, const char *arg, double lo, double hi, double *out);
/* A list option value for n joints: one number (every joint) or n, each finite and in
 * [lo, hi], spread to n values in out. arg NULL: nothing to do, 0. Returns 0, or 2 after a
 * message naming the rule broken. */
int qo_cli_list(const char *who, const char *opt, const char *arg, size_t n, double lo, double hi,
                double *out);
/* A list of 1-based joint numbers (1..n) into n flags. arg NULL: all 0. Returns 0 or 2. */
int qo_cli_joint_set(const char *who, const char *opt, const char *arg, size_t n, unsigned char *flags);

/* ---- planning shared by plan and stream (planopt.c) ---- */

/* Columns of one input line after the time: a CLI limit only (the library has none). */
#define QO_CLI_MAX_FIELDS 3072
/* Sample rate bounds of plan and stream's planning (Hz): the grid is whole ns, so 1 MHz keeps
 * it within 0.1 %; below 1 mHz a plan of any length is a handful of rows. */
#define QO_CLI_RATE_MIN 1e-3
#define QO_CLI_RATE_MAX 1e6
/* Samples one `plan` may print unless --max-samples says more (at 100 Hz: 2.8 hours), and the
 * most --max-samples accepts. */
#define QO_CLI_MAX_SAMPLES_DEFAULT 1000000.0
#define QO_CLI_MAX_SAMPLES_LIMIT 1e10

enum qo_cli_plan_optid {
    QO_CLI_OPT_PROFILE = 256, QO_CLI_OPT_RATE, QO_CLI_OPT_END, QO_CLI_OPT_COLUMNS, QO_CLI_OPT_DERIVS,
    QO_CLI_OPT_MIN, QO_CLI_OPT_MAX, QO_CLI_OPT_WRAP, QO_CLI_OPT_UNWRAPPED, QO_CLI_OPT_DEGREES,
    QO_CLI_OPT_FIXED, QO_CLI_OPT_VMAX, QO_CLI_OPT_AMAX, QO_CLI_OPT_JMAX, QO_CLI_OPT_SYNC,
    QO_CLI_OPT_MAX_SAMPLES, QO_CLI_OPT_MIN_DURATION, QO_CLI_OPT_DISCRETE, QO_CLI_OPT_VMIN,
    QO_CLI_OPT_AMIN, QO_CLI_OPT_TARGET_VELOCITIES, QO_CLI_OPT_LAST_
};
/* The getopt_long entries of the planning options (one table for plan and stream). */
#define QO_CLI_PLAN_OPTIONS                                                                       \
    { "profile", required_argument, NULL, QO_CLI_OPT_PROFILE },                                   \
    { "rate", required_argument, NULL, QO_CLI_OPT_RATE },                                         \
    { "end", required_argument, NULL, QO_CLI_OPT_END },                                           \
    { "columns", required_argument, NULL, QO_CLI_OPT_COLUMNS },                                   \
    { "derivs", required_argument, NULL, QO_CLI_OPT_DERIVS },                                     \
    { "min", required_argument, NULL, QO_CLI_OPT_MIN },                                           \
    { "max", required_argument, NULL, QO_CLI_OPT_MAX },                                           \
    { "wrap", required_argument, NULL, QO_CLI_OPT_WRAP },                                         \
    { "unwrapped", no_argument, NULL, QO_CLI_OPT_UNWRAPPED },                                     \
    { "degrees", no_argument, NULL, QO_CLI_OPT_DEGREES },                                         \
    { "fixed", no_argument, NULL, QO_CLI_OPT_FIXED },                                             \
    { "vmax", required_argument, NULL, QO_CLI_OPT_VMAX },                                         \
    { "amax", required_argument, NULL, QO_CLI_OPT_AMAX },                                         \
    { "jmax", required_argument, NULL, QO_CLI_OPT_JMAX },                                         \
    { "sync", required_argument, NULL, QO_CLI_OPT_SYNC },                                         \
    { "max-samples", required_argument, NULL, QO_CLI_OPT_MAX_SAMPLES },                           \
    { "min-duration", required_argument, NULL, QO_CLI_OPT_MIN_DURATION },                         \
    { "discrete", no_argument, NULL, QO_CLI_OPT_DISCRETE },                                       \
    { "vmin", required_argument, NULL, QO_CLI_OPT_VMIN },                                         \
    { "amin", required_argument, NULL, QO_CLI_OPT_AMIN },                                         \
    { "target-velocities", no_argument, NULL, QO_CLI_OPT_TARGET_VELOCITIES }

/* The planning options as given. Lists stay text until the joint count is known. */
struct qo_cli_plan_opts {
    int motion;                 /* 1: trapezoid|scurve targets, 0: keyframes */
    qo_spline_profile sprofile;
    qo_spline_end end;
    qo_spline_derivs derivs;
    int columns;                /* 1 p, 2 pv, 3 pva (0 until checked) */
    qo_motion_profile mprofile;
    qo_motion_sync sync;        /* --sync with one value (with a list: TIME, overridden) */
    const char *sync_list;      /* --sync with a comma list: one value per joint */
    const char *vmax, *amax, *jmax, *min, *max, *wrap;
    const char *vmin, *amin;    /* asymmetric limits (NULL: -vmax, -amax) */
    int target_vel;             /* --target-velocities: target lines t,p1..pN,v1..vN */
    double rate, max_samples;
    double min_duration;        /* --min-duration S (0 = none) */
    int discrete;               /* --discrete: durations in whole periods of --rate */
    int degrees, unwrapped, fixed;
    const char *key_opt, *motion_opt; /* an option of the other mode, to refuse by name */
    int sampled;                /* 1 (plan): the plan is printed at --rate, so an input whose
                                 * times already span more than --max-samples rows is refused
                                 * at the line that crosses it */
};
void qo_cli_plan_opts_default(struct qo_cli_plan_opts *o);
/* Takes one getopt_long result of QO_CLI_PLAN_OPTIONS. Returns 0 or 2 (message printed). */
int qo_cli_plan_opt(const char *who, struct qo_cli_plan_opts *o, int opt, const char *arg);
/* After the options: the combination makes sense. Returns 0 or 2 (message printed). */
int qo_cli_plan_opts_check(const char *who, struct qo_cli_plan_opts *o);

/* Input lines as read: rows of `width` numbers after the time. */
struct qo_cli_rows {
    size_t rows, cap, width;
    double *v;
    qo_traj_ns *t;
    long *line, first_line;
};
/* One input line (len from qo_cli_getline, or -1 for a C string): blank and '#' lines are
 * skipped; any error (NUL byte, not a number, not finite, out of float32 range, column count,
 * time out of range or out of order) prints a message naming the line and returns 1; nothing
 * is added. */
int qo_cli_rows_add(const char *who, const char *name, const struct qo_cli_plan_opts *o, int has_time,
                    long lineno, char *text, long len, struct qo_cli_rows *r);
/* Every line of path (NULL or "-": standard input); a read error (a directory) is an I/O
 * error. Needs 2 keyframes or 1 start line. Bounded: more than QO_CLI_INPUT_MAX bytes, more
 * than QO_CLI_MAX_VALUES numbers, more than --max-samples keyframes or targets or (o->sampled)
 * times spanning more than --max-samples rows stop the reading at the line that crosses the
 * bound. Returns 0 or 1 (message printed). */
int qo_cli_rows_read(const char *who, const struct qo_cli_plan_opts *o, const char *path,
                     struct qo_cli_rows *r);
void qo_cli_rows_free(struct qo_cli_rows *r);

/* A trajectory with its storage (heap: the command's, not the library's). */
struct qo_cli_plan {
    qo_traj tr;
    size_t n;
    double period;              /* of continuous joints */
    qo_traj_ns *t;
    float *store, *lo, *hi;
    unsigned char *wrap;
    qo_spline_settings_f32 sset;
    qo_motion_joint_f32 joints[QO_MOTION_MAX_JOINTS];
    qo_motion_limits_f32 lim[QO_MOTION_MAX_JOINTS];
};
/* Sets up p for n joints and cap keys / queued targets from the options (lists spread and
 * checked now). Returns 0, 1 (runtime) or 2 (usage), message printed. */
int qo_cli_plan_build(const char *who, const struct qo_cli_plan_opts *o, size_t n, size_t cap,
                      struct qo_cli_plan *p);
/* Pushes one row (n x columns numbers; continuous joints reduced in double first). Returns 0
 * or 1, message naming the line. */
int qo_cli_plan_push(const char *who, const char *name, struct qo_cli_plan *p, qo_traj_ns t,
                     const double *row, long lineno);
/* Targets: a trial run of the plan applying each row at its time; a target state the planner
 * refuses is named (its line) on stderr. *end = when the motion ends. Returns 0, 1 or 2. */
int qo_cli_plan_trial(const char *who, const char *name, const struct qo_cli_plan_opts *o,
                      const struct qo_cli_rows *r, qo_traj_ns *end);
/* build + push every row (+ plan the keyframes). Returns 0, 1 or 2. */
int qo_cli_plan_from_rows(const char *who, const char *name, const struct qo_cli_plan_opts *o,
                          const struct qo_cli_rows *r, struct qo_cli_plan *p);
void qo_cli_plan_free(struct qo_cli_plan *p);

/* Rotation representations of `qorient convert`. */
enum rep { REP_QUAT, REP_MATRIX, REP_ROTVEC, REP_AXISANGLE, REP_EULER };
struct rep_spec {
    enum rep kind;
    qo_euler_seq seq;   /* REP_EULER only */
};

/* The --fixed paths (fixed.c): the input record v (as read, degrees if `degrees`) converted
 * with the fixed-point core; o receives the output record (Euler: 3 angles + lock flag) and *n
 * its length. Inputs are converted to fixed point at the boundary, rounding and saturating;
 * a value that does not fit its format is an error, never silently clipped. */
qo_status qo_cli_convert_fixed(const struct rep_spec *from, const struct rep_spec *to,
                               const double *v, int degrees, double *o, size_t *n);
qo_status qo_cli_slerp_fixed(const double *v, double *o);

/* ---- the one parser of input numbers (util.c): every record of every subcommand, and the
 * lists of option values, go through qo_cli_parse_fields ---- */

/* Why a field is refused (the return values of qo_cli_parse_fields). */
#define QO_CLI_NUM_BAD (-1)       /* not a number: the whole field must parse ("1.5x", "") */
#define QO_CLI_NUM_MANY (-2)      /* more fields than the caller takes */
#define QO_CLI_NUM_NONFINITE (-3) /* nan, inf: not a finite number */
#define QO_CLI_NUM_RANGE (-4)     /* finite in the text, beyond float32 (1e39, 1e400) */

/* The field a refusal is about: its 1-based index and its text in the line (not quoted yet). */
struct qo_cli_field {
    size_t index;
    const char *text;
    size_t len;
};

/* Splits `line` into numbers separated by blanks and/or commas. Writes at most `max` values to
 * out and their count to *n. Returns 0, or one of QO_CLI_NUM_* above for the first field
 * refused, described in *bad (may be NULL). Every number the core takes is a float32, so a
 * value float32 cannot hold (it would round to infinity: |v| >= 2^128 - 2^103) is refused
 * here, as out of float32 range, apart from NaN and Inf. A line that is blank or starts with
 * '#' gives *n == 0. */
int qo_cli_parse_fields(const char *line, double *out, size_t max, size_t *n, struct qo_cli_field *bad);
/* The same without the description. */
int qo_cli_parse_numbers(const char *line, double *out, size_t max, size_t *n);
/* The reason of a QO_CLI_NUM_BAD, _NONFINITE or _RANGE refusal for a message, written to buf
 * (QO_CLI_REASON_CAP bytes are always enough): "out of float32 range: '1e39' (column 3)",
 * noun naming the field ("column", "value"). Returns buf. */
#define QO_CLI_REASON_CAP 256
const char *qo_cli_field_reason(int rc, const struct qo_cli_field *bad, const char *noun, char *buf,
                                size_t cap);

/* ---- user text in messages (util.c): one quoting for every message ---- */

/* The most bytes of a user's text a message repeats. */
#define QO_CLI_QUOTE_MAX 40
/* Room for a quoted text: each byte at most 4 characters, quotes, "..." and the NUL. */
#define QO_CLI_QUOTE_CAP (4 * QO_CLI_QUOTE_MAX + 6)
/* Writes s (len bytes, or up to its NUL when len < 0) to buf as 'TEXT', for a message: at most
 * QO_CLI_QUOTE_MAX bytes of it, "..." after the closing quote when there is more; a byte that
 * is not printable ASCII as \xNN and ' and \ as \' and \\, so a message never carries a NUL,
 * a control character or unbounded text from the input. buf of QO_CLI_QUOTE_CAP bytes holds
 * any text (a smaller one cuts it shorter). Returns buf. */
const char *qo_cli_quote(char *buf, size_t cap, const char *s, long len);
/* qo_cli_quote of the C string s into a buffer of its own (a C99 compound literal, alive to the
 * end of the enclosing block): for a message's argument list. */
#define QO_CLI_QUOTED(s) qo_cli_quote((char[QO_CLI_QUOTE_CAP]){ 0 }, QO_CLI_QUOTE_CAP, (s), -1)

/* Prints a float with enough significant digits (9) to read back the same float32. */
void qo_cli_print_f32(FILE *f, float v);

/* Prints a time given in ns as exact decimal seconds, no trailing zeros ("-12.5",
 * "10000000.05", "3"): no float rounding at any magnitude. */
void qo_cli_print_time(FILE *f, qo_traj_ns t);

/* The longest input line read, in characters without the newline: far above any record
 * (QO_CLI_MAX_FIELDS numbers), low enough that an endless line (/dev/zero, a binary file)
 * ends in a message at once instead of filling memory. */
#define QO_CLI_LINE_MAX 1048576L
/* The inputs the commands keep in memory (plan, gimbal, stream's FILE) are bounded as they are
 * read, and refused at the line that crosses a bound, never after reading them all: at most
 * QO_CLI_INPUT_MAX bytes (64 MiB: the time spent reading), --max-samples keyframes or targets,
 * and QO_CLI_MAX_VALUES numbers kept (keyframes x columns: the memory, a few tens of bytes
 * a number once planned). */
#define QO_CLI_INPUT_MAX 67108864UL
#define QO_CLI_MAX_VALUES 4194304UL

/* Reads one line of up to QO_CLI_LINE_MAX characters into *buf (grown with realloc). Returns
 * the length, -1 at end of input or on a read error (check ferror), QO_CLI_LINE_LONG for a
 * longer line (the rest of it is left unread: callers stop reading there),
 * QO_CLI_LINE_NOMEM, or QO_CLI_INPUT_BIG when *left (bytes the input may still take, newlines
 * counted; NULL: no bound) would go below 0: the byte after the bound is not read. The
 * trailing newline (and CR) is removed. A line with a NUL byte has strlen(*buf) < the length
 * returned: callers refuse it. */
#define QO_CLI_LINE_LONG (-2L)
#define QO_CLI_LINE_NOMEM (-3L)
#define QO_CLI_INPUT_BIG (-4L)
long qo_cli_getline(char **buf, size_t *cap, FILE *f, size_t *left);
/* What a qo_cli_getline result below -1 means, for "line N: ..." messages. */
const char *qo_cli_line_problem(long len);

/* The sample grid of plan and stream: time i is t0 + i/rate, exact to the ns from t0. */
qo_traj_ns qo_cli_grid(qo_traj_ns t0, double rate, double i);
/* The rows of the grid from t0 through tl: its points before tl, and tl (a keyframe plan prints
 * exactly these; a targets plan at least these), so a plan whose input already spans more than
 * --max-samples rows is refused while it is read. */
double qo_cli_grid_rows(qo_traj_ns t0, qo_traj_ns tl, double rate);

/* getopt_long's optind is global state: each subcommand resets it through this. */
void qo_cli_reset_getopt(void);

#endif
