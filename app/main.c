/* src/cli/main.c: the `cumulo` program: dispatches to the subcommands render, bench and run. */
#include "commands.h"
#include <stdio.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f,
            "usage: cumulo <command> [options]\n"
            "  render SCENE -o OUT.png|OUT.pfm [--size WxH] [--backend egl|osmesa] [--set section.key=value]...\n"
            "  bench  SCENE [--frames N] [--warmup N] [--size WxH] [--backend B] [--set k=v]... [--csv FILE]\n"
            "  run    SCENE --platform drm|x11|wayland|headless [--frames N] [--fullscreen] [--input SPEC]...\n"
            "  sweep  [--scenes a,b,c] [--out DIR]   speed/accuracy sweep against the path tracer (make sweep)\n");
}

int main(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "render") == 0)
        return cmd_render(argc - 1, argv + 1);
    if (strcmp(cmd, "bench") == 0)
        return cmd_bench(argc - 1, argv + 1);
    if (strcmp(cmd, "run") == 0)
        return cmd_run(argc - 1, argv + 1);
    fprintf(stderr, "cumulo: unknown command '%s'\n", cmd);
    usage(stderr);
    return 2;
}
