/*
 * fuzz/fuzz_cli_numbers.c - the command's number parser qo_cli_parse_numbers
 * (cli/cli.h) on raw text: first byte = max (0..31), the rest the line, copied
 * into an exactly sized buffer (and out[] exactly max doubles) so ASan sees any overrun.
 * Properties from the header: returns 0 or one of QO_CLI_NUM_* (-1 not a number, -2 too many,
 * -3 not finite, -4 out of float32 range); *n <= max; a blank or '#' line gives *n == 0 with
 * 0; on 0 the fields are exactly the non-empty comma/blank separated tokens, each value is
 * what strtod reads from its token (an independent split done here) and is finite and a
 * finite float32 once converted (the compiler's own float32 rounding, not the parser's bound).
 */
#include "fuzz_common.h"
#include "../cli/cli.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    size_t max, n = 12345, len, i, k;
    char *line, *copy, *p;
    double *out;
    int rc;

    if (size == 0) return 0;
    max = data[0] % 32u;
    len = size - 1;
    line = malloc(len + 1);
    copy = malloc(len + 1);
    out = malloc(max ? max * sizeof *out : 1);
    if (line == NULL || copy == NULL || out == NULL) abort();
    memcpy(line, data + 1, len);
    line[len] = '\0';
    memcpy(copy, line, len + 1);

    rc = qo_cli_parse_numbers(line, out, max, &n);
    QO_FUZZ_CHECK(rc == 0 || rc == QO_CLI_NUM_BAD || rc == QO_CLI_NUM_MANY || rc == QO_CLI_NUM_NONFINITE ||
                      rc == QO_CLI_NUM_RANGE,
                  "parse_numbers returned %d", rc);
    QO_FUZZ_CHECK(n <= max, "parse_numbers n %zu > max %zu", n, max);
    p = copy + strspn(copy, " \t");
    if (*p == '\0' || *p == '#') QO_FUZZ_CHECK(rc == 0 && n == 0, "blank/comment line gave rc %d n %zu", rc, n);
    /* strtod skips any leading white space (\v \f \r \n too), so the parser reads "\v\t1"
     * as the number 1 across what this split calls a separator: a documented leniency (see
     * the report), not checked token by token. */
    if (rc == 0 && strpbrk(copy, "\v\f\r\n") == NULL) {
        /* independent split: tokens between blanks/commas; the line's own string ends at
         * its first NUL, as for the parser */
        k = 0;
        if (*p != '#') {
            char *tok = strtok(p, " \t,");
            while (tok != NULL) {
                char *e;
                double v = strtod(tok, &e);
                QO_FUZZ_CHECK(*e == '\0' && e != tok, "accepted token '%s' that strtod does not read whole", tok);
                QO_FUZZ_CHECK(k < n, "parse_numbers missed token %zu '%s'", k, tok);
                QO_FUZZ_CHECK(memcmp(&v, &out[k], sizeof v) == 0 || (v != v && out[k] != out[k]),
                              "token %zu '%s': %.17g, strtod %.17g", k, tok, out[k], v);
                k++;
                tok = strtok(NULL, " \t,");
            }
        }
        QO_FUZZ_CHECK(k == n, "parse_numbers gave %zu values for %zu tokens", n, k);
    }
    for (i = 0; rc == 0 && i < n; i++)
        QO_FUZZ_CHECK(isfinite(out[i]) && isfinite((float)out[i]), "accepted value %zu %.17g is not a finite float32",
                      i, out[i]);
    free(line);
    free(copy);
    free(out);
    return 0;
}
