#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "qorient/version.h"

/* The least magnitude float32 rounds to infinity (round to nearest even: FLT_MAX + half an
 * ulp, 2^128 - 2^103); every smaller finite value is a float32 once rounded. */
static const double F32_OVERFLOW = 0x1.ffffffp127;

static int is_sep(char c)
{
    return c == ' ' || c == '\t' || c == ',' || c == '\0';
}

int qo_cli_parse_fields(const char *line, double *out, size_t max, size_t *n, struct qo_cli_field *bad)
{
    const char *p = line;
    struct qo_cli_field scratch;
    if (bad == NULL) bad = &scratch;
    *n = 0;
    bad->index = 0;
    bad->text = line;
    bad->len = 0;
    while (*p == ' ' || *p == '\t') p++;
    if (*p == '#' || *p == '\0') return 0;
    for (;;) {
        char *end;
        const char *f;
        double v;
        int rc = 0;
        while (*p == ' ' || *p == '\t') p++;
        if (*p == '\0') break;
        f = p;
        while (!is_sep(*p)) p++;
        bad->index = *n + 1;
        bad->text = f;
        bad->len = (size_t)(p - f);
        /* The whole field must be the number: "1.5x" is not one, and neither is a field strtod
         * would reach by skipping a vertical tab or a form feed. */
        errno = 0;
        v = strtod(f, &end);
        if (end == f || end != p || isspace((unsigned char)*f)) return QO_CLI_NUM_BAD;
        if (*n >= max) return QO_CLI_NUM_MANY;
        /* inf and nan as text are not finite; a finite text beyond double (1e400, ERANGE) or
         * beyond float32 (1e39) is out of range, which the core's float32 cannot take either */
        if (isnan(v) || (isinf(v) && errno != ERANGE)) rc = QO_CLI_NUM_NONFINITE;
        else if (!(fabs(v) < F32_OVERFLOW)) rc = QO_CLI_NUM_RANGE;
        if (rc != 0) return rc;
        out[(*n)++] = v;
        while (*p == ' ' || *p == '\t') p++;
        if (*p == ',') {
            p++;
            while (*p == ' ' || *p == '\t') p++;
            if (*p == '\0' || *p == ',') { /* an empty field */
                bad->index = *n + 1;
                bad->text = p;
                bad->len = 0;
                return QO_CLI_NUM_BAD;
            }
        }
    }
    return 0;
}

int qo_cli_parse_numbers(const char *line, double *out, size_t max, size_t *n)
{
    return qo_cli_parse_fields(line, out, max, n, NULL);
}

const char *qo_cli_field_reason(int rc, const struct qo_cli_field *bad, const char *noun, char *buf,
                                size_t cap)
{
    char q[QO_CLI_QUOTE_CAP];
    snprintf(buf, cap, "%s: %s (%s %zu)",
             rc == QO_CLI_NUM_NONFINITE ? "not a finite number"
             : rc == QO_CLI_NUM_RANGE  ? "out of float32 range"
                                       : "not a number",
             qo_cli_quote(q, sizeof q, bad->text, (long)bad->len), noun, bad->index);
    return buf;
}

const char *qo_cli_quote(char *buf, size_t cap, const char *s, long len)
{
    static const char hex[] = "0123456789abcdef";
    size_t n = len < 0 ? strlen(s) : (size_t)len, i, o = 0;
    if (cap < 3) {
        if (cap > 0) buf[0] = '\0';
        return buf;
    }
    buf[o++] = '\'';
    for (i = 0; i < n && i < QO_CLI_QUOTE_MAX; i++) {
        unsigned char c = (unsigned char)s[i];
        /* room for this byte's 4 characters, the closing quote, "..." and the NUL */
        if (o + 4 + 5 > cap) break;
        if (c == '\'' || c == '\\') {
            buf[o++] = '\\';
            buf[o++] = (char)c;
        } else if (c >= 0x20 && c < 0x7f) {
            buf[o++] = (char)c;
        } else {
            buf[o++] = '\\';
            buf[o++] = 'x';
            buf[o++] = hex[c >> 4];
            buf[o++] = hex[c & 15];
        }
    }
    buf[o++] = '\'';
    if (i < n && o + 4 <= cap) {
        memcpy(buf + o, "...", 3);
        o += 3;
    }
    buf[o] = '\0';
    return buf;
}

void qo_cli_print_f32(FILE *f, float v)
{
    /* %.9g round-trips every float32; -0 prints as 0 so equal rotations compare as text. */
    if (v == 0.0f) v = 0.0f;
    fprintf(f, "%.9g", (double)v);
}

long qo_cli_getline(char **buf, size_t *cap, FILE *f, size_t *left)
{
    size_t n = 0;
    int c = EOF;
    if (*buf == NULL || *cap < 2) {
        char *nb = realloc(*buf, 256);
        if (nb == NULL) return QO_CLI_LINE_NOMEM;
        *buf = nb;
        *cap = 256;
    }
    for (;;) {
        /* the bound on the whole input first: reading stops at the first byte past it */
        if (left != NULL && *left == 0) {
            (*buf)[n] = '\0';
            if ((c = getc(f)) == EOF) break;
            return QO_CLI_INPUT_BIG;
        }
        if ((c = getc(f)) == EOF) break;
        if (left != NULL) (*left)--;
        if (c == '\n') break;
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
    return len == QO_CLI_LINE_LONG   ? "longer than 1048576 characters"
           : len == QO_CLI_INPUT_BIG ? "the input is longer than 67108864 bytes: nothing more is read"
                                     : "out of memory";
}

qo_traj_ns qo_cli_grid(qo_traj_ns t0, double rate, double i)
{
    /* exact ns from the first line's time (the rate is not a float32 here) */
    return t0 + (qo_traj_ns)llround(i * (1e9 / rate));
}

double qo_cli_grid_rows(qo_traj_ns t0, qo_traj_ns tl, double rate)
{
    /* grid points up to the last time, plus the last time when the grid misses it */
    double rows = floor((double)(tl - t0) * 1e-9 * rate + 1e-9);
    return rows + (rows <= 1e12 && qo_cli_grid(t0, rate, rows) >= tl ? 1.0 : 2.0);
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
    fprintf(stderr, "qorient %s: %s: %s is not %s%s%s\n", who, opt, QO_CLI_QUOTED(arg), range,
            unit ? " " : "", unit ? unit : "");
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
    fprintf(stderr, "qorient %s: %s: %s is not a whole number in [%g, %g]\n", who, opt,
            QO_CLI_QUOTED(arg), lo, hi);
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
    double v[QO_MOTION_MAX_JOINTS > 64 ? QO_MOTION_MAX_JOINTS : 64];
    size_t m = 0, i;
    char range[80], why[QO_CLI_REASON_CAP];
    struct qo_cli_field bad;
    int pr;
    if (arg == NULL) return 0;
    if (strlen(arg) >= 1024) {
        fprintf(stderr, "qorient %s: %s: the list is longer than 1023 characters\n", who, opt);
        return 2;
    }
    pr = qo_cli_parse_fields(arg, v, sizeof v / sizeof v[0], &m, &bad);
    if (pr != 0 && pr != QO_CLI_NUM_MANY) {
        fprintf(stderr, "qorient %s: %s: %s\n", who, opt, qo_cli_field_reason(pr, &bad, "value", why, sizeof why));
        return 2;
    }
    if (pr != 0 || m == 0) {
        fprintf(stderr, "qorient %s: %s: %s is not a list of numbers separated by commas\n", who, opt,
                QO_CLI_QUOTED(arg));
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
    double v[64];
    size_t m = 0, i;
    memset(flags, 0, n);
    if (arg == NULL) return 0;
    if (strlen(arg) >= 1024 || qo_cli_parse_numbers(arg, v, sizeof v / sizeof v[0], &m) != 0 || m == 0) {
        fprintf(stderr, "qorient %s: %s: %s is not a list of joint numbers\n", who, opt, QO_CLI_QUOTED(arg));
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
