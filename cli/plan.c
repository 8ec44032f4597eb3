/* `qorient plan`: one command, two planners. Keyframe profiles (linear, cubic, catmull,
 * spline, quintic) are sampled by plan_keys.c; limited moves (trapezoid, scurve) by
 * plan_moves.c. Only --profile decides, so both share the input format and common options. */
#include "cli.h"

#include <string.h>

static int is_motion_profile(const char *p)
{
    return strcmp(p, "trapezoid") == 0 || strcmp(p, "scurve") == 0;
}

int qo_cli_plan(int argc, char **argv)
{
    int i;
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--") == 0) break;
        if (strcmp(argv[i], "--profile") == 0 && i + 1 < argc && is_motion_profile(argv[i + 1]))
            return qo_cli_plan_moves(argc, argv);
        if (strncmp(argv[i], "--profile=", 10) == 0 && is_motion_profile(argv[i] + 10))
            return qo_cli_plan_moves(argc, argv);
    }
    return qo_cli_plan_keys(argc, argv);
}
