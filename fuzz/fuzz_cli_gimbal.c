/*
 * fuzz/fuzz_cli_gimbal.c - `qorient gimbal` (cli/gimbal.c over qorient/gimbal.h)
 * end to end: the first two bytes pick the axis sequence, rate, interpolation, hold band,
 * rate limit, the tracking filter's --amax / --jmax and --degrees; the rest is the keyframe
 * text 't,w,x,y,z' given as FILE.
 * Properties: exit status 0 or 1 (valid options); every output row is a list of finite
 * numbers. Not fuzzed: inputs whose key times span between 4000 and 1e9 samples at the
 * chosen rate (the command writes them all by design; above 1e9 it refuses, and that refusal
 * IS fuzzed: fuzz/regress/cli_gimbal/ holds the span of 3e38 s that once overflowed the
 * sample count's conversion to unsigned long).
 */
#include "fuzz_cli_common.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    static const char *const seqs[] = { "ZYX", "zyx", "ZYZ", "xyx", "XZY", "YXZ", "zxz", "XYZ" };
    static const char *const rates[] = { "1", "10", "100", "1000" };
    static const char *const bands[] = { "1", "0", "0.0001", "90" };
    static const char *const vmaxs[] = { "1", "100", "0.5", "1000" };
    static const char *const amaxs[] = { "10", "0.001", "1e6", "1e13" }; /* the last: refused */
    static const char *const jmaxs[] = { "100", "1", "1e9", "0" };       /* the last: refused */
    char store[20][24];
    char *argv[22];
    int argc = 0, rc;
    uint8_t s0, s1;
    double t_lo, t_hi, rate, span;
    char *out;
    size_t out_len;

#define FUZZ_GB_ARG(str) do { strcpy(store[argc], (str)); argv[argc] = store[argc]; argc++; } while (0)
    if (size < 2) return 0;
    s0 = data[0];
    s1 = data[1];
    data += 2;
    size -= 2;
    if (memchr(data, '\0', size) != NULL) return 0;

    FUZZ_GB_ARG("gimbal");
    FUZZ_GB_ARG("--seq");
    FUZZ_GB_ARG(seqs[s0 & 7u]);
    FUZZ_GB_ARG("--rate");
    FUZZ_GB_ARG(rates[(s0 >> 3) & 3u]);
    rate = strtod(rates[(s0 >> 3) & 3u], NULL);
    FUZZ_GB_ARG("--interp");
    FUZZ_GB_ARG((s0 & 0x20u) ? "spline" : "slerp");
    if (s0 & 0x40u) { FUZZ_GB_ARG("--band"); FUZZ_GB_ARG(bands[s1 & 3u]); }
    if (s0 & 0x80u) { FUZZ_GB_ARG("--vmax"); FUZZ_GB_ARG(vmaxs[(s1 >> 2) & 3u]); }
    if (s1 & 0x10u) FUZZ_GB_ARG("--degrees");
    if (s1 & 0x20u) { FUZZ_GB_ARG("--amax"); FUZZ_GB_ARG(amaxs[(s1 >> 6) & 3u]); }
    if ((s1 & 0x21u) == 0x21u) { FUZZ_GB_ARG("--jmax"); FUZZ_GB_ARG(jmaxs[(s1 >> 1) & 1u ? 3u : (s1 >> 6) & 3u]); }
    argv[argc++] = qo_fz_cli_files_get()->in_path;
    argv[argc] = NULL;
#undef FUZZ_GB_ARG

    (void)qo_fz_cli_prescan(data, size, &t_lo, &t_hi);
    span = t_hi > t_lo ? (t_hi - t_lo) * rate : 0.0;
    if (span > 4000.0 && span <= 2e9) return 0;
    /* A rate limit makes the command catch up for up to an hour of samples after the last
     * key: bounded, but long at 1000 Hz. */
    if ((s0 & 0x80u) && rate > 100.0) return 0;
    /* So does the tracking filter until it settles: at --amax 0.001 that can be the hour. */
    if ((s1 & 0x20u) && rate > 10.0) return 0;

    rc = qo_fz_cli_run(QO_FZ_CLI_FN(qo_cli_gimbal), argc, argv, 0, data, size, &out, &out_len);
    /* exit 2 only for the refused filter limits (an --amax or --jmax out of range) */
    QO_FUZZ_CHECK(rc == 0 || rc == 1 || ((s1 & 0x20u) && rc == 2), "gimbal: exit status %d", rc);
    qo_fz_cli_check_output(out, "gimbal");
    free(out);
    return 0;
}
