/* tools/sweep/main.c: `cumulo-sweep`, the speed/accuracy sweep against the reference path tracer (sweep.h lists the
 * parts). Exit status: 0 done (or --help, --version), 1 a runtime failure, 2 a usage error. */
#include "sweep.h"

int main(int argc, char **argv)
{
    static sweep sw;
    int rc = sw_parse_options(&sw, argc, argv);
    if (rc)
        return rc < 0 ? 0 : rc;
    return sw_run(&sw) ? 1 : 0;
}
