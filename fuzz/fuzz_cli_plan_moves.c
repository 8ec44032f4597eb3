/*
 * fuzz/fuzz_cli_plan_moves.c - `qorient plan --profile trapezoid|scurve` (the limited moves of
 * cli/plan.c over qorient/motion.h) end to end: the first two bytes pick
 * the profile, the limits (from a small table, one value or one per joint), rate, sync, joint
 * limits, wrap, --degrees and --fixed; the rest is the target CSV given as FILE.
 * Properties: exit status 0 or 1 (the options are valid); every output row is a list of
 * finite numbers.
 * Not fuzzed: inputs with a number above 100 in magnitude or times spanning more than 40 s:
 * the command samples until the joints arrive (duration ~ distance / vmax) at the rate, so
 * bigger ones only make long outputs by design.
 */
#include "fuzz_cli_common.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    static const char *const vmaxs[] = { "10", "100", "1000", "5" };
    static const char *const amaxs[] = { "10", "1000", "2", "100" };
    static const char *const syncs[] = { "time", "phase", "none", "time" };
    char store[24][24];
    char *argv[25];
    int argc = 0, rc;
    uint8_t s0, s1;
    double t_lo, t_hi, big;
    char *out;
    size_t out_len;

#define FUZZ_PM_ARG(str) do { strcpy(store[argc], (str)); argv[argc] = store[argc]; argc++; } while (0)
    if (size < 2) return 0;
    s0 = data[0];
    s1 = data[1];
    data += 2;
    size -= 2;
    if (memchr(data, '\0', size) != NULL) return 0;

    FUZZ_PM_ARG("plan");
    FUZZ_PM_ARG("--profile");
    FUZZ_PM_ARG((s0 & 1u) ? "scurve" : "trapezoid");
    FUZZ_PM_ARG("--vmax");
    FUZZ_PM_ARG(vmaxs[(s0 >> 1) & 3u]);
    FUZZ_PM_ARG("--amax");
    FUZZ_PM_ARG(amaxs[(s0 >> 3) & 3u]);
    if ((s0 & 1u) || (s0 & 0x20u)) { FUZZ_PM_ARG("--jmax"); FUZZ_PM_ARG((s0 & 0x40u) ? "100" : "5000"); }
    FUZZ_PM_ARG("--rate");
    FUZZ_PM_ARG((s0 & 0x80u) ? "10" : "100");
    FUZZ_PM_ARG("--sync");
    FUZZ_PM_ARG(syncs[s1 & 3u]);
    if (s1 & 4u) { FUZZ_PM_ARG("--min"); FUZZ_PM_ARG("-1.5"); FUZZ_PM_ARG("--max"); FUZZ_PM_ARG("2"); }
    if (s1 & 8u) { FUZZ_PM_ARG("--wrap"); FUZZ_PM_ARG("1"); }
    if (s1 & 0x20u) FUZZ_PM_ARG("--degrees");
    if (s1 & 0x40u) FUZZ_PM_ARG("--fixed");
    argv[argc++] = qo_fz_cli_files_get()->in_path;
    argv[argc] = NULL;
#undef FUZZ_PM_ARG

    big = qo_fz_cli_prescan(data, size, &t_lo, &t_hi);
    if (big > 100.0 || (t_hi > t_lo && t_hi - t_lo > 40.0)) return 0;

    rc = qo_fz_cli_run(QO_FZ_CLI_FN(qo_cli_plan), argc, argv, 0, data, size, &out, &out_len);
    QO_FUZZ_CHECK(rc == 0 || rc == 1, "plan (moves): exit status %d", rc);
    qo_fz_cli_check_output(out, "plan (moves)");
    free(out);
    return 0;
}
