#include "cli.h"

#include <errno.h>
#include <getopt.h>
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
    ssize_t n = getline(buf, cap, f);
    if (n < 0) return -1;
    while (n > 0 && ((*buf)[n - 1] == '\n' || (*buf)[n - 1] == '\r')) (*buf)[--n] = '\0';
    return (long)n;
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
