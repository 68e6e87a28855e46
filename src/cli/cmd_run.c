/* src/cli/cmd_run.c: `cumulo run` — the interactive/kiosk loop (display back end + inputs + renderer). */
#include "commands.h"
#include <stdio.h>

int cmd_run(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "cumulo run: not built in this revision yet\n");
    return 2;
}
