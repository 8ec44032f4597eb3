/*
 * fuzz/fuzz_cli_convert.c - `qorient convert FROM TO [--degrees] [--fixed]` and
 * `qorient slerp [--fixed]` (cli/convert.c) end to end: the first byte picks the
 * subcommand, the representations and the options, the rest is the command's standard input.
 * Properties (DESIGN.md's text contract): exit status 0 or 1; every output line is a list of
 * finite numbers, "error: REASON", or a copied blank/'#' line; one output line per input line.
 */
#include "fuzz_cli_common.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    static const char *const reps[] = {
        "quat", "matrix", "rotvec", "axisangle", "euler:xyz", "euler:ZYX", "euler:zxz", "euler:YXY"
    };
    char a0[16], a1[16], a2[16], a3[16], a4[16];
    char *argv[6];
    int argc = 0, rc;
    uint8_t sel, sel2;
    char *out;
    size_t out_len, in_lines = 0, out_lines = 0, i;

    if (size < 2) return 0;
    sel = data[0];
    sel2 = data[1];
    data += 2;
    size -= 2;
    /* commands read lines: a NUL inside one ends the string early (not a contract case) */
    if (memchr(data, '\0', size) != NULL) return 0;

    if (sel & 0x80u) {
        strcpy(a0, "slerp");
        argv[argc++] = a0;
        if (sel & 1u) { strcpy(a1, "--fixed"); argv[argc++] = a1; }
        argv[argc] = NULL;
        rc = qo_fz_cli_run(QO_FZ_CLI_FN(qo_cli_slerp), argc, argv, 1, data, size, &out, &out_len);
    } else {
        strcpy(a0, "convert");
        argv[argc++] = a0;
        strcpy(a1, reps[sel & 7u]);
        argv[argc++] = a1;
        strcpy(a2, reps[(sel >> 3) & 7u]);
        argv[argc++] = a2;
        if (sel & 0x40u) { strcpy(a3, "--degrees"); argv[argc++] = a3; }
        if (sel2 & 1u) { strcpy(a4, "--fixed"); argv[argc++] = a4; }
        argv[argc] = NULL;
        rc = qo_fz_cli_run(QO_FZ_CLI_FN(qo_cli_convert), argc, argv, 1, data, size, &out, &out_len);
    }
    QO_FUZZ_CHECK(rc == 0 || rc == 1, "%s: exit status %d", a0, rc);
    qo_fz_cli_check_output(out, a0);
    for (i = 0; i < size; i++) in_lines += data[i] == '\n';
    if (size > 0 && data[size - 1] != '\n') in_lines++;
    for (i = 0; i < out_len; i++) out_lines += out[i] == '\n';
    QO_FUZZ_CHECK(out_lines == in_lines, "%s: %zu output lines for %zu input lines", a0, out_lines, in_lines);
    free(out);
    return 0;
}
