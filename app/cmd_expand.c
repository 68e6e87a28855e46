/* app/cmd_expand.c: `cumulo expand`: a scene with its [layer]s written out as plain [cloud] sections, to edit. */
#include "commands.h"
#include "session.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char expand_help[] =
    "usage: cumulo expand SCENE [-o OUT.scene] [--set SECTION.KEY=V]...\n"
    "Writes SCENE with every [layer] replaced by the clouds it generates, as [cloud] and [ellipsoid] sections (each\n"
    "cloud keeps the layer's wind, lifetime and wrap, and its own life phase and noise offset), so it renders as\n"
    "before and can be edited. At most 1024 clouds and 4096 ellipsoids: lower a layer's coverage or extent for more.\n"
    "  -o, --output FILE      where to write it (default: standard output)\n"
    "  --set SECTION.KEY=V    override a scene value first (repeatable)\n"
    "  -h, --help             this help\n";

int cmd_expand(int argc, char **argv)
{
    static const struct option longopts[] = {{"output", required_argument, NULL, 'o'},
                                             {"set", required_argument, NULL, 'S'},
                                             {"help", no_argument, NULL, 'h'}, {NULL, 0, NULL, 0}};
    const char *out = NULL, *path = NULL, *sets[CLI_MAX_SETS];
    int nsets = 0, c;
    opterr = 0;
    optind = 1;
    while ((c = getopt_long(argc, argv, ":o:h", longopts, NULL)) != -1) {
        switch (c) {
        case 'o': out = optarg; break;
        case 'S':
            if (nsets == CLI_MAX_SETS) {
                fprintf(stderr, "cumulo expand: at most %d --set options\n", CLI_MAX_SETS);
                return 2;
            }
            sets[nsets++] = optarg;
            break;
        case 'h': fputs(expand_help, stdout); return 0;
        case ':': fprintf(stderr, "cumulo expand: %s needs a value\n", argv[optind - 1]); return 2;
        default: fprintf(stderr, "cumulo expand: unknown option '%s'\n", argv[optind - 1]); return 2;
        }
    }
    for (; optind < argc; optind++) {
        if (path) {
            fprintf(stderr, "cumulo expand: more than one scene given ('%s')\n", argv[optind]);
            return 2;
        }
        path = argv[optind];
    }
    if (!path) {
        fprintf(stderr, "usage: cumulo expand SCENE [-o OUT.scene] (cumulo expand --help)\n");
        return 2;
    }
    cu_scene *s;
    cu_error e;
    if (cu_scene_load(&s, path, &e)) {
        fprintf(stderr, "cumulo: %s\n", e.msg);
        return 1;
    }
    for (int i = 0; i < nsets; i++)
        if (cu_scene_set(s, sets[i], &e)) {
            fprintf(stderr, "cumulo: %s\n", e.msg);
            cu_scene_free(s);
            return 2;
        }
    if (cu_scene_expand(s, &e)) {
        fprintf(stderr, "cumulo: %s\n", e.msg);
        cu_scene_free(s);
        return 1;
    }
    size_t cap = 8u << 20;
    char *buf = malloc(cap);
    size_t len = buf ? cu_scene_format(s, buf, cap) : 0;
    cu_scene_free(s);
    if (!len) {
        fprintf(stderr, "cumulo: %s\n", buf ? "the expanded scene does not fit in 8 MiB" : "out of memory");
        free(buf);
        return 1;
    }
    FILE *f = out ? fopen(out, "wb") : stdout;
    int rc = 0;
    if (!f) {
        fprintf(stderr, "cumulo: cannot write %s: %s\n", out, strerror(errno));
        rc = 1;
    } else {
        fprintf(f, "# %s expanded by cumulo expand: its [layer]s as [cloud] sections\n", path);
        if (fwrite(buf, 1, len, f) != len || fflush(f) != 0 || ferror(f))
            rc = 1;
        if (out && fclose(f) != 0)
            rc = 1;
        if (rc)
            fprintf(stderr, "cumulo: cannot write %s: %s\n", out ? out : "standard output", strerror(errno));
    }
    free(buf);
    return rc;
}
