/*
 * tests/fuzz/test_fuzz_regress.c - replays the fuzz inputs under `make test` (ASan + UBSan, gcc):
 * every file in fuzz/regress/NAME/ (inputs that once crashed or violated a property: each is
 * a regression test of the fix named in its file name) and every seed in fuzz/corpus/NAME/,
 * through the same target code as the libFuzzer build (fuzz/fuzz_NAME.c is included here with
 * its entry point renamed), with the same property checks: a violation fails the test and
 * names the file. The directory is ./fuzz, or $QO_FUZZ_DIR.
 */
/* 64-bit directory offsets on 32-bit hosts (armhf under qemu-user on a 64-bit file system):
 * without it readdir() fails with EOVERFLOW and the corpus looks empty. */
#define _FILE_OFFSET_BITS 64

#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

/* A property violation inside a target fails the running cmocka test (with its message). */
#define QO_FUZZ_FAIL(...) do { \
        print_error("fuzz property violated at %s:%d: ", __FILE__, __LINE__); \
        print_error(__VA_ARGS__); \
        print_error("\n"); \
        fail(); \
    } while (0)

/* The command's targets run build/qorient (the test is not linked with the CLI objects);
 * its number parser is compiled in from its source. */
#define QO_FUZZ_CLI_EXEC 1
#include "../cli/util.c"

#define QO_FUZZ_ENTRY fuzz_one_quat
#include "../fuzz/fuzz_quat.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_convert
#include "../fuzz/fuzz_convert.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_euler
#include "../fuzz/fuzz_euler.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_interp
#include "../fuzz/fuzz_interp.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_gimbal
#include "../fuzz/fuzz_gimbal.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_fxmath
#include "../fuzz/fuzz_fxmath.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_fx_orient
#include "../fuzz/fuzz_fx_orient.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_interp_fx
#include "../fuzz/fuzz_interp_fx.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_spline
#include "../fuzz/fuzz_spline.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_motion
#include "../fuzz/fuzz_motion.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_modbus_pack
#include "../fuzz/fuzz_modbus_pack.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_regmap
#include "../fuzz/fuzz_regmap.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_cli_numbers
#include "../fuzz/fuzz_cli_numbers.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_cli_convert
#include "../fuzz/fuzz_cli_convert.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_cli_plan_keys
#include "../fuzz/fuzz_cli_plan_keys.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_cli_gimbal
#include "../fuzz/fuzz_cli_gimbal.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_cli_plan_moves
#include "../fuzz/fuzz_cli_plan_moves.c"
#undef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY fuzz_one_traj
#include "../fuzz/fuzz_traj.c"
#undef QO_FUZZ_ENTRY

typedef int (*fuzz_entry)(const uint8_t *data, size_t size);

typedef struct fuzz_target {
    const char *name;
    fuzz_entry fn;
    unsigned edge_step;   /* 1: every edge tag; more for the targets that run a process */
} fuzz_target;

static const char *fuzz_dir(void)
{
    const char *d = getenv("QO_FUZZ_DIR");
    return d != NULL ? d : "fuzz";
}

/* Runs fn on every regular file of dir; returns how many (-1 if dir cannot be opened). */
static long replay_dir(const char *dir, fuzz_entry fn)
{
    DIR *dp = opendir(dir);
    struct dirent *de;
    long n = 0;
    if (dp == NULL) return -1;
    while ((de = readdir(dp)) != NULL) {
        char path[512];
        FILE *fp;
        uint8_t *buf;
        long len = -1;
        if (de->d_name[0] == '.') continue;
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        fp = fopen(path, "rb");
        if (fp == NULL) continue;   /* a subdirectory or unreadable entry */
        if (fseek(fp, 0, SEEK_END) == 0) len = ftell(fp);
        if (len < 0 || fseek(fp, 0, SEEK_SET) != 0) {
            fclose(fp);
            fail_msg("cannot read %s", path);
        }
        buf = malloc(len > 0 ? (size_t)len : 1);
        assert_non_null(buf);
        if (len > 0 && fread(buf, 1, (size_t)len, fp) != (size_t)len) {
            free(buf);
            fclose(fp);
            fail_msg("cannot read %s", path);
        }
        fclose(fp);
        print_message("replay %s (%ld bytes)\n", path, len);
        (void)fn(buf, (size_t)len);
        free(buf);
        n++;
    }
    closedir(dp);
    return n;
}

static void replay_target(void **state)
{
    const fuzz_target *t = *state;
    char dir[256];
    long seeds, regress;
    snprintf(dir, sizeof dir, "%s/corpus/%s", fuzz_dir(), t->name);
    seeds = replay_dir(dir, t->fn);
    if (seeds <= 0) fail_msg("%s: no seed corpus (%ld files); run from the repository root or set QO_FUZZ_DIR", dir, seeds);
    snprintf(dir, sizeof dir, "%s/regress/%s", fuzz_dir(), t->name);
    regress = replay_dir(dir, t->fn);
    print_message("%s: %ld seeds, %ld regression inputs replayed\n", t->name, seeds, regress < 0 ? 0 : regress);
}

/* The empty input and a run of each edge-value tag reach the decoders' "input exhausted" and
 * table paths in every target, independent of the committed files. */
static void edge_inputs(void **state)
{
    const fuzz_target *t = *state;
    uint8_t buf[256];
    unsigned tag;
    memset(buf, 0, sizeof buf);
    (void)t->fn(buf, 0);
    for (tag = 0x80; tag < 0x100; tag += t->edge_step) {
        memset(buf, (int)tag, sizeof buf);
        (void)t->fn(buf, sizeof buf / 8);
        (void)t->fn(buf, sizeof buf);
    }
}

static fuzz_target targets[] = {
    { "quat", fuzz_one_quat, 1 },
    { "convert", fuzz_one_convert, 1 },
    { "euler", fuzz_one_euler, 1 },
    { "interp", fuzz_one_interp, 1 },
    { "gimbal", fuzz_one_gimbal, 1 },
    { "fxmath", fuzz_one_fxmath, 1 },
    { "fx_orient", fuzz_one_fx_orient, 1 },
    { "regmap", fuzz_one_regmap, 1 },
    { "spline", fuzz_one_spline, 1 },
    { "motion", fuzz_one_motion, 1 },
    { "modbus_pack", fuzz_one_modbus_pack, 1 },
    { "cli_numbers", fuzz_one_cli_numbers, 1 },
    { "cli_convert", fuzz_one_cli_convert, 17 },
    { "cli_plan_keys", fuzz_one_cli_plan_keys, 17 },
    { "cli_plan_moves", fuzz_one_cli_plan_moves, 17 },
    { "interp_fx", fuzz_one_interp_fx, 1 },
    { "cli_gimbal", fuzz_one_cli_gimbal, 17 },
    { "traj", fuzz_one_traj, 1 },
};

#define T(i, name) { "replay " name, replay_target, NULL, NULL, &targets[i] }, \
                   { "edges " name, edge_inputs, NULL, NULL, &targets[i] }

int main(void)
{
    const struct CMUnitTest tests[] = {
        T(0, "quat"), T(1, "convert"), T(2, "euler"), T(3, "interp"), T(4, "gimbal"), T(5, "fxmath"),
        T(6, "fx_orient"), T(7, "regmap"), T(8, "spline"), T(9, "motion"), T(10, "modbus_pack"),
        T(11, "cli_numbers"), T(12, "cli_convert"), T(13, "cli_plan_keys"), T(14, "cli_plan_moves"),
        T(15, "interp_fx"), T(16, "cli_gimbal"), T(17, "traj"),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
