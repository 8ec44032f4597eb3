/*
 * fuzz/fuzz_cli_plan_keys.c - `qorient plan` over keyframes (cli/plan.c, cli/planopt.c,
 * qorient/spline.h underneath) end to end: the first two bytes pick the profile, columns,
 * end condition, derivative rule, rate, limits, wrap and --fixed; the rest is the keyframe
 * CSV given as FILE. Properties: exit status 0 or 1 (valid options; 2 only with no output);
 * every output row is a list of finite numbers (the command writes nothing else on stdout).
 * Not fuzzed: inputs whose key times span more than 4000 samples at the chosen rate - the
 * command writes span * rate rows by design (it refuses more than 1e9 itself).
 */
#include "fuzz_cli_common.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define FUZZ_PK_MAX_ROWS 4000.0

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    static const char *const profiles[] = { "linear", "cubic", "catmull", "spline", "quintic", "spline", "quintic", "cubic" };
    static const char *const rates[] = { "1", "10", "100", "1000" };
    static const char *const columns[] = { "p", "pv", "pva", "p" };
    char store[24][24];
    char *argv[26];
    int argc = 0, rc;
    uint8_t s0, s1;
    double t_lo, t_hi, rate;
    char *out;
    size_t out_len;

#define FUZZ_PK_ARG(str) do { strcpy(store[argc], (str)); argv[argc] = store[argc]; argc++; } while (0)
    if (size < 2) return 0;
    s0 = data[0];
    s1 = data[1];
    data += 2;
    size -= 2;
    if (memchr(data, '\0', size) != NULL) return 0;

    FUZZ_PK_ARG("plan");
    FUZZ_PK_ARG("--profile");
    FUZZ_PK_ARG(profiles[s0 & 7u]);
    /* only the combinations the command documents: cubic takes pv or pva, quintic any */
    if (strcmp(profiles[s0 & 7u], "cubic") == 0) {
        FUZZ_PK_ARG("--columns");
        FUZZ_PK_ARG(columns[1 + (s1 & 1u)]);
    } else if (strcmp(profiles[s0 & 7u], "quintic") == 0 && (s0 & 0x20u)) {
        FUZZ_PK_ARG("--columns");
        FUZZ_PK_ARG(columns[s1 & 3u]);
    }
    FUZZ_PK_ARG("--rate");
    FUZZ_PK_ARG(rates[(s0 >> 3) & 3u]);
    rate = strtod(rates[(s0 >> 3) & 3u], NULL);
    if (s0 & 0x40u) { FUZZ_PK_ARG("--end"); FUZZ_PK_ARG((s1 & 4u) ? "natural" : "rest"); }
    if (s0 & 0x80u) { FUZZ_PK_ARG("--derivs"); FUZZ_PK_ARG((s1 & 8u) ? "zero" : "estimated"); }
    if (s1 & 0x10u) { FUZZ_PK_ARG("--min"); FUZZ_PK_ARG("-1.5"); FUZZ_PK_ARG("--max"); FUZZ_PK_ARG("2"); }
    if (s1 & 0x20u) { FUZZ_PK_ARG("--wrap"); FUZZ_PK_ARG("1"); }
    if (s1 & 0x40u) FUZZ_PK_ARG("--fixed");
    if (s1 & 0x80u) FUZZ_PK_ARG("--degrees");
    argv[argc++] = qo_fz_cli_files_get()->in_path;
    argv[argc] = NULL;
#undef FUZZ_PK_ARG

    (void)qo_fz_cli_prescan(data, size, &t_lo, &t_hi);
    if (t_hi > t_lo && (t_hi - t_lo) * rate > FUZZ_PK_MAX_ROWS) return 0;

    rc = qo_fz_cli_run(QO_FZ_CLI_FN(qo_cli_plan), argc, argv, 0, data, size, &out, &out_len);
    /* 2: a usage error found once the keys are read (e.g. limits against the joint count):
     * then nothing may have been written */
    QO_FUZZ_CHECK(rc == 0 || rc == 1 || (rc == 2 && out_len == 0), "plan: exit status %d (%zu bytes out)", rc, out_len);
    qo_fz_cli_check_output(out, "plan");
    free(out);
    return 0;
}
