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
#include "qorient/status.h"

/* Subcommands: argv[0] is the subcommand name. Return the process exit status. */
int qo_cli_version(int argc, char **argv);
int qo_cli_convert(int argc, char **argv);
int qo_cli_slerp(int argc, char **argv);
int qo_cli_gimbal(int argc, char **argv);
int qo_cli_sim(int argc, char **argv);
int qo_cli_plan_keys(int argc, char **argv);
/* `qorient plan --profile trapezoid|scurve` (plan_moves.c). */
int qo_cli_plan_moves(int argc, char **argv);
/* `qorient plan`: --profile trapezoid|scurve go to plan_moves, the rest to plan_keys. */
int qo_cli_plan(int argc, char **argv);
int qo_cli_stream(int argc, char **argv);

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

/* Splits `line` in place into numbers separated by blanks and/or commas. Writes at most `max`
 * values to out and their count to *n. Returns 0 on success, -1 if a field is not a number
 * (the whole field must parse; "nan"/"inf" are accepted as numbers and left for the math to
 * reject), -2 if there are more than `max` fields. A line that is blank or starts with '#'
 * gives *n == 0. */
int qo_cli_parse_numbers(char *line, double *out, size_t max, size_t *n);

/* Prints a float with enough significant digits (9) to read back the same float32. */
void qo_cli_print_f32(FILE *f, float v);

/* Reads one line of any length into *buf (grown with realloc). Returns the length or -1 at
 * end of input. The trailing newline (and CR) is removed. */
long qo_cli_getline(char **buf, size_t *cap, FILE *f);

/* getopt_long's optind is global state: each subcommand resets it through this. */
void qo_cli_reset_getopt(void);

#endif
