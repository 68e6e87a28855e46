/* app/main.c: the `cumulo` program: dispatches to the subcommands render, bench, run and sun. */
#include "commands.h"
#include "session.h"
#include <stdio.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f,
            "usage: cumulo COMMAND [options]   (cumulo COMMAND --help for its options)\n"
            "  render SCENE -o OUT.png|OUT.pfm   one frame to a PNG (tone-mapped) or PFM (linear radiance)\n"
            "  bench  SCENE [--frames N] ...     frame times, glmark2-style lines, optional CSV\n"
            "  run    SCENE --platform P ...     the interactive / kiosk loop: a display, inputs that move the sun\n"
            "  sun    --time-utc T ...           the sun's elevation and azimuth at a UTC time and a place\n"
            "  expand SCENE [-o OUT.scene]       the scene with its [layer]s written out as [cloud] sections\n"
            "  ig     SCENE [--input SPEC] ...   image generator: a simulator (CIGI 3.3, FlightGear, X-Plane) drives it\n"
            "  --version                         version, display back ends and inputs of this build\n"
            "Exit status: 0 success, 1 runtime failure (bad scene file, GL or I/O error), 2 usage error.\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "-h") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "help") == 0) {
        usage(stdout);
        return 0;
    }
    if (strcmp(cmd, "--version") == 0 || strcmp(cmd, "version") == 0) {
        cli_print_version(stdout, "cumulo");
        return 0;
    }
    if (strcmp(cmd, "render") == 0)
        return cmd_render(argc - 1, argv + 1);
    if (strcmp(cmd, "bench") == 0)
        return cmd_bench(argc - 1, argv + 1);
    if (strcmp(cmd, "run") == 0)
        return cmd_run(argc - 1, argv + 1);
    if (strcmp(cmd, "expand") == 0)
        return cmd_expand(argc - 1, argv + 1);
    if (strcmp(cmd, "sun") == 0)
        return cmd_sun(argc - 1, argv + 1);
    if (strcmp(cmd, "ig") == 0)
        return cmd_ig(argc - 1, argv + 1);
    fprintf(stderr, "cumulo: unknown command '%s' (cumulo --help lists them)\n", cmd);
    return 2;
}
