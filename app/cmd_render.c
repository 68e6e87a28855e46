/* src/cli/cmd_render.c: `cumulo render`: one frame to a PNG (tone-mapped sRGB) or PFM (linear radiance). */
#include "commands.h"
#include "session.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int ends_with(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && strcmp(s + a - b, suffix) == 0;
}

int cmd_render(int argc, char **argv)
{
    cli_opts o = {0};
    const char *out = NULL;
    for (int i = 1; i < argc; i++) {
        int c = cli_common_option(&o, argc, argv, &i);
        if (c < 0)
            return 2;
        if (c)
            continue;
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
            out = argv[++i];
        } else if (argv[i][0] == '-') {
            fprintf(stderr, "cumulo render: unknown option '%s'\n", argv[i]);
            return 2;
        } else if (!o.scene_path) {
            o.scene_path = argv[i];
        } else {
            fprintf(stderr, "cumulo render: more than one scene given ('%s')\n", argv[i]);
            return 2;
        }
    }
    if (!o.scene_path || !out) {
        fprintf(stderr, "usage: cumulo render SCENE -o OUT.png|OUT.pfm [--size WxH] [--backend egl|osmesa] "
                        "[--set section.key=value]...\n");
        return 2;
    }
    int pfm = ends_with(out, ".pfm");
    if (!pfm && !ends_with(out, ".png")) {
        fprintf(stderr, "cumulo render: output '%s' must end in .png or .pfm\n", out);
        return 2;
    }
    o.linear = pfm;
    cli_session s;
    if (cli_session_open(&s, &o) || cli_session_render(&s)) {
        cli_session_close(&s);
        return 1;
    }
    cu_error err = {"cannot read the frame back"};
    int rc = 0;
    if (pfm) {
        float *px = malloc(sizeof(float) * 3 * (size_t)s.width * s.height);
        if (!px || cli_session_read_rgbf(&s, px) || cu_write_pfm(out, px, s.width, s.height, &err)) {
            fprintf(stderr, "cumulo: %s\n", px ? err.msg : "out of memory");
            rc = 1;
        }
        free(px);
    } else {
        uint8_t *px = malloc(4 * (size_t)s.width * s.height);
        if (!px || cli_session_read_rgba8(&s, px) || cu_write_png(out, px, s.width, s.height, &err)) {
            fprintf(stderr, "cumulo: %s\n", px ? err.msg : "out of memory");
            rc = 1;
        }
        free(px);
    }
    if (rc == 0)
        printf("wrote %s (%dx%d, %s)\n", out, s.width, s.height, s.be->name);
    cli_session_close(&s);
    return rc;
}
