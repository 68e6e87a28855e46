/* src/cli/cmd_sweep.c: `cumulo sweep`: the speed/accuracy sweep against the reference path tracer (issue 7). */
#include "commands.h"
#include <stdio.h>

int cmd_sweep(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "cumulo sweep: not built in this revision yet\n");
    return 2;
}
