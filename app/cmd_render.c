/* app/cmd_render.c: `cumulo render`: one frame to a PNG (tone-mapped sRGB) or PFM (linear radiance). */
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

static const char render_help[] =
    "usage: cumulo render SCENE -o OUT.png|OUT.pfm [options]\n"
    "Renders one frame of SCENE headless: OUT.png tone-mapped 8-bit sRGB, OUT.pfm linear radiance (float).\n"
    "  -o, --output FILE      the image to write (.png or .pfm)\n" CLI_COMMON_HELP;

int cmd_render(int argc, char **argv)
{
    static const struct option longopts[] = {CLI_COMMON_LONGOPTS, {"output", required_argument, NULL, 'o'},
                                             {NULL, 0, NULL, 0}};
    cli_opts o = {0};
    const char *out = NULL;
    int c;
    opterr = 0;
    optind = 1;
    while ((c = getopt_long(argc, argv, ":o:vh", longopts, NULL)) != -1) {
        int k = cli_common_getopt(&o, c, optarg, "cumulo render");
        if (k < 0)
            return 2;
        if (k)
            continue;
        switch (c) {
        case 'o': out = optarg; break;
        case 'h': fputs(render_help, stdout); return 0;
        case CLI_OPT_VERSION: cli_print_version(stdout, "cumulo"); return 0;
        case ':': fprintf(stderr, "cumulo render: %s needs a value\n", argv[optind - 1]); return 2;
        default: fprintf(stderr, "cumulo render: unknown option '%s'\n", argv[optind - 1]); return 2;
        }
    }
    for (; optind < argc; optind++) {
        if (o.scene_path) {
            fprintf(stderr, "cumulo render: more than one scene given ('%s')\n", argv[optind]);
            return 2;
        }
        o.scene_path = argv[optind];
    }
    if (!o.scene_path || !out) {
        fprintf(stderr, "usage: cumulo render SCENE -o OUT.png|OUT.pfm [--size WxH] [--backend egl|osmesa] "
                        "[--set section.key=value]... (cumulo render --help)\n");
        return 2;
    }
    int pfm = ends_with(out, ".pfm");
    if (!pfm && !ends_with(out, ".png")) {
        fprintf(stderr, "cumulo render: output '%s' must end in .png or .pfm\n", out);
        return 2;
    }
    o.linear = pfm;
    cli_session s;
    int rc = cli_session_open(&s, &o);
    if (rc || (rc = cli_session_render(&s)) != 0) {
        cli_session_close(&s);
        return rc;
    }
    cu_error err = {"cannot read the frame back"};
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
