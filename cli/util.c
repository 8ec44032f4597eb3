#include "cli.h"

#include <errno.h>
#include <float.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "qorient/version.h"

int qo_cli_parse_numbers(char *line, double *out, size_t max, size_t *n)
{
    char *p = line;
    *n = 0;
    while (*p == ' ' || *p == '\t') p++;
    if (*p == '#' || *p == '\0') return 0;
    for (;;) {
        char *end;
        double v;
        while (*p == ' ' || *p == '\t') p++;
        if (*p == '\0') break;
        errno = 0;
        v = strtod(p, &end);
        if (end == p) return -1;
        /* The field must end at a separator: "1.5x" is not a number. */
        if (*end != '\0' && *end != ' ' && *end != '\t' && *end != ',') return -1;
        if (*n >= max) return -2;
        out[(*n)++] = v;
        p = end;
        while (*p == ' ' || *p == '\t') p++;
        if (*p == ',') {
            p++;
            while (*p == ' ' || *p == '\t') p++;
            if (*p == '\0' || *p == ',') return -1; /* empty field */
        }
    }
    return 0;
}

void qo_cli_print_f32(FILE *f, float v)
{
    /* %.9g round-trips every float32; -0 prints as 0 so equal rotations compare as text. */
    if (v == 0.0f) v = 0.0f;
    fprintf(f, "%.9g", (double)v);
}

long qo_cli_getline(char **buf, size_t *cap, FILE *f)
{
    size_t n = 0;
    int c = EOF;
    if (*buf == NULL || *cap < 2) {
        char *nb = realloc(*buf, 256);
        if (nb == NULL) return QO_CLI_LINE_NOMEM;
        *buf = nb;
        *cap = 256;
    }
    while ((c = getc(f)) != EOF && c != '\n') {
        if (n >= (size_t)QO_CLI_LINE_MAX) {
            (*buf)[n] = '\0';
            return QO_CLI_LINE_LONG;
        }
        if (n + 1 >= *cap) {
            size_t nc = *cap * 2 > (size_t)QO_CLI_LINE_MAX + 1 ? (size_t)QO_CLI_LINE_MAX + 1 : *cap * 2;
            char *nb = realloc(*buf, nc);
            if (nb == NULL) return QO_CLI_LINE_NOMEM;
            *buf = nb;
            *cap = nc;
        }
        (*buf)[n++] = (char)c;
    }
    /* a read error mid-line is not a short last line */
    if (c == EOF && (n == 0 || ferror(f))) return -1;
    (*buf)[n] = '\0';
    while (n > 0 && (*buf)[n - 1] == '\r') (*buf)[--n] = '\0';
    return (long)n;
}

const char *qo_cli_line_problem(long len)
{
    return len == QO_CLI_LINE_LONG ? "longer than 1048576 characters" : "out of memory";
}

void qo_cli_reset_getopt(void)
{
    optind = 1;
    opterr = 1;
}

int qo_cli_version(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    puts("qorient " QO_VERSION_STRING);
    return 0;
}

/* "[1e-06, 1e+12]" style range text for messages, open ends as such. */
static void range_text(char *buf, size_t cap, double lo, double hi)
{
    if (isinf(lo) && isinf(hi)) snprintf(buf, cap, "any finite number");
    else snprintf(buf, cap, "a number in [%g, %g]", lo, hi);
}

int qo_cli_number(const char *who, const char *opt, const char *arg, double lo, double hi,
                  const char *unit, double *out)
{
    char *end;
    char range[80];
    double v;
    errno = 0;
    v = strtod(arg, &end);
    *out = 0.0;
    if (end != arg && *end == '\0' && isfinite(v) && v >= lo && v <= hi) {
        *out = v;
        return 0;
    }
    range_text(range, sizeof range, lo, hi);
    fprintf(stderr, "qorient %s: %s: '%s' is not %s%s%s\n", who, opt, arg, range, unit ? " " : "",
            unit ? unit : "");
    return 2;
}

int qo_cli_count(const char *who, const char *opt, const char *arg, double lo, double hi, double *out)
{
    char *end;
    double v;
    v = strtod(arg, &end);
    *out = 0.0;
    if (end != arg && *end == '\0' && v >= lo && v <= hi && v == floor(v)) {
        *out = v;
        return 0;
    }
    fprintf(stderr, "qorient %s: %s: '%s' is not a whole number in [%g, %g]\n", who, opt, arg, lo, hi);
    return 2;
}

/* A list value in [lo, hi]. The lists hold limits for the float32 core, whose ends are float32
 * (QO_MOTION_LIMIT_MAX is 1e12f = 999999995904): a value that rounds to the float32 value of
 * an end, as the 1e12 the help names does, is in the range. */
static int list_in_range(double v, double lo, double hi)
{
    if (!isfinite(v)) return 0;
    if (v >= lo && v <= hi) return 1;
    if (!(fabs(v) <= FLT_MAX)) return 0;
    return (fabs(lo) <= FLT_MAX && (float)v == (float)lo) || (fabs(hi) <= FLT_MAX && (float)v == (float)hi);
}

int qo_cli_list(const char *who, const char *opt, const char *arg, size_t n, double lo, double hi,
                double *out)
{
    char buf[1024];
    double v[QO_MOTION_MAX_JOINTS > 64 ? QO_MOTION_MAX_JOINTS : 64];
    size_t m = 0, i;
    char range[80];
    int pr;
    if (arg == NULL) return 0;
    if (strlen(arg) >= sizeof buf) {
        fprintf(stderr, "qorient %s: %s: the list is longer than %zu characters\n", who, opt, sizeof buf - 1);
        return 2;
    }
    strcpy(buf, arg);
    pr = qo_cli_parse_numbers(buf, v, sizeof v / sizeof v[0], &m);
    if (pr != 0 || m == 0) {
        fprintf(stderr, "qorient %s: %s: '%s' is not a list of numbers separated by commas\n", who, opt, arg);
        return 2;
    }
    if (m != 1 && m != n) {
        fprintf(stderr, "qorient %s: %s has %zu values for %zu joint(s) (give 1 or %zu)\n", who, opt, m, n, n);
        return 2;
    }
    range_text(range, sizeof range, lo, hi);
    for (i = 0; i < m; i++)
        if (!list_in_range(v[i], lo, hi)) {
            fprintf(stderr, "qorient %s: %s: value %zu (%g) is not %s\n", who, opt, i + 1, v[i], range);
            return 2;
        }
    for (i = 0; i < n; i++) out[i] = v[m == 1 ? 0 : i];
    return 0;
}

int qo_cli_joint_set(const char *who, const char *opt, const char *arg, size_t n, unsigned char *flags)
{
    char buf[1024];
    double v[64];
    size_t m = 0, i;
    memset(flags, 0, n);
    if (arg == NULL) return 0;
    if (strlen(arg) < sizeof buf) strcpy(buf, arg);
    else buf[0] = 'x', buf[1] = '\0';
    if (qo_cli_parse_numbers(buf, v, sizeof v / sizeof v[0], &m) != 0 || m == 0) {
        fprintf(stderr, "qorient %s: %s: '%s' is not a list of joint numbers\n", who, opt, arg);
        return 2;
    }
    for (i = 0; i < m; i++) {
        if (!(v[i] >= 1.0 && v[i] <= (double)n) || v[i] != floor(v[i])) {
            fprintf(stderr, "qorient %s: %s: '%g' is not a joint number 1..%zu\n", who, opt, v[i], n);
            return 2;
        }
        flags[(size_t)v[i] - 1] = 1;
    }
    return 0;
}

void qo_cli_print_time(FILE *f, qo_traj_ns t)
{
    unsigned long long a = t < 0 ? 0ULL - (unsigned long long)t : (unsigned long long)t;
    unsigned long long sec = a / 1000000000ULL, frac = a % 1000000000ULL;
    char digits[16];
    int k = 9;
    fprintf(f, "%s%llu", t < 0 ? "-" : "", sec);
    if (frac == 0) return;
    snprintf(digits, sizeof digits, "%09llu", frac);
    while (k > 0 && digits[k - 1] == '0') digits[--k] = '\0';
    fprintf(f, ".%s", digits);
}
