/* qorient: the command-line front end over the core and the ports. */
#include "cli.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

struct qo_cli_cmd {
    const char *name;
    int (*fn)(int argc, char **argv);
    const char *summary;
};

/* One line per subcommand; keep sorted by the order a newcomer meets them. */
static const struct qo_cli_cmd cmds[] = {
    { "convert", qo_cli_convert, "convert rotations: quat, matrix, rotvec, axisangle, euler:SEQ" },
    { "slerp", qo_cli_slerp, "spherical linear interpolation of quaternion pairs" },
    { "plan", qo_cli_plan, "plan and sample multi-joint trajectories (keyframes or limited moves)" },
    { "gimbal", qo_cli_gimbal, "joint angles of a 2/3-axis gimbal along a quaternion keyframe path" },
    { "stream", qo_cli_stream, "plan and stream joint targets to drives over Modbus RTU/TCP or GPIO" },
    { "sim", qo_cli_sim, "simulated Modbus servo drive bank (register map, lag, faults)" },
    { "version", qo_cli_version, "print the version" },
};

static void usage(FILE *f)
{
    size_t i;
    fputs("usage: qorient COMMAND [OPTIONS] [ARGS]\n\n"
          "Orientation math and smooth joint motion from the shell.\n"
          "Numbers in, one record per line; errors name the line.\n\ncommands:\n", f);
    for (i = 0; i < sizeof cmds / sizeof cmds[0]; i++)
        fprintf(f, "  %-9s %s\n", cmds[i].name, cmds[i].summary);
    fputs("\n'qorient COMMAND --help' (or 'qorient help COMMAND') describes each command;\n"
          "'qorient --version' prints the version.\n", f);
}

/* The exit status once the output is out: a full disk or a closed descriptor (ENOSPC,
 * EBADF) is found at the last flush at the latest, and a run whose output did not all get
 * written is not a success. */
static int finish(int rc)
{
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "qorient: standard output: write error: %s\n", strerror(errno));
        return rc != 0 ? rc : 1;
    }
    return rc;
}

int main(int argc, char **argv)
{
    static char *hargv[3]; /* argv of `help CMD`: alive as long as argv */
    size_t i;
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "-V") == 0)
        return finish(qo_cli_version(1, argv + 1));
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
        (strcmp(argv[1], "help") == 0 && argc == 2)) {
        usage(stdout);
        return finish(0);
    }
    if (strcmp(argv[1], "help") == 0) {
        /* `qorient help CMD` is exactly `qorient CMD --help`: the same entry point runs. */
        if (argc > 3) {
            fputs("qorient help: one command at a time\n", stderr);
            return 2;
        }
        hargv[0] = argv[2];
        hargv[1] = (char *)"--help";
        hargv[2] = NULL;
        argv = hargv;
        argc = 2;
    } else {
        argv++;
        argc--;
    }
    for (i = 0; i < sizeof cmds / sizeof cmds[0]; i++) {
        if (strcmp(argv[0], cmds[i].name) == 0) {
            qo_cli_reset_getopt();
            return finish(cmds[i].fn(argc, argv));
        }
    }
    fprintf(stderr, "qorient: unknown command %s\n", QO_CLI_QUOTED(argv[0]));
    usage(stderr);
    return 2;
}
