/* app/run_clock.c: `cumulo run --clock`: the sun from the wall clock at the scene's place, the clouds in real time,
 * the knob's offset of the time of day (see run_clock.h). */
#include "run_clock.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double clock_s(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static uint64_t mono_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static double elapsed_s(const run_clock *c) { return (double)(mono_ns() - c->t0) * 1e-9; }

int run_clock_option(cu_clock_ctl *ctl, const char *opt, const char *v)
{
    char *end;
    double x = strtod(v, &end);
    int shift = !strcmp(opt, "--clock-offset");
    if (end == v || *end || !(shift ? x >= -1e9 && x <= 1e9 : x > 0 && x <= 1e6)) {
        fprintf(stderr, "cumulo run: %s expects %s, got '%s'\n", opt,
                shift ? "seconds in -1e9..1e9" : "a factor K with 0 < K <= 1e6", v);
        return 1;
    }
    *(shift ? &ctl->shift_s : &ctl->scale) = x;
    return 0;
}

/* Sets the sun for the second the clock shows now, when it is another than the one it was set for (force: always).
 * A second moves the sun 0.004 degrees, too little to see, while moves redraw each cloud's sun and slab maps
 * (src/gpu/frame_maps.c): following the clock every frame would keep redrawing them. The angles are
 * taken here rather than through cu_renderer_set_sun_utc, which ties the sun to the scene time: that runs the clouds
 * at 1x while --time-scale runs the clock faster, and it would move the sun every frame. Returns 1 when it was set. */
static int aim(run_clock *c, cu_renderer *r, int force)
{
    double shown = floor(cu_clock_ctl_shown(&c->ctl, clock_s(CLOCK_REALTIME), elapsed_s(c)));
    if (shown == c->aimed && !force)
        return 0;
    c->aimed = shown;
    char utc[32];
    double el, az;
    cu_error e;
    /* geometric elevation at sea level, as the renderer takes a scene's time_utc (src/core/scene_sun.c) */
    if (cu_clock_format_utc(shown, utc, sizeof utc))
        snprintf(e.msg, sizeof e.msg, "the clock shows a time this machine cannot represent");
    else if (!cu_solar_position_at(utc, c->lat, c->lon, 0.0, 0, &el, &az, &e) && !cu_renderer_set_sun(r, el, az, &e)) {
        snprintf(c->utc, sizeof c->utc, "%s", utc);
        c->sun_failing = 0;
        return 1;
    }
    if (!c->sun_failing)
        fprintf(stderr, "cumulo: warning: --clock: %s; the sun stays where it is\n", e.msg);
    c->sun_failing = 1;
    return 0;
}

/* "WHAT utc=T offset=+Mmin elevation=E azimuth=A" and tail: the time the sun was set for and the sun. */
static void print_line(FILE *f, const char *what, const run_clock *c, const cu_renderer *r, const char *tail)
{
    double el, az;
    char off[32];
    cu_renderer_get_sun(r, &el, &az);
    cu_clock_format_offset(c->ctl.offset_s, off, sizeof off);
    fprintf(f, "%s utc=%s offset=%s elevation=%.3f azimuth=%.3f%s\n", what, c->utc, off, el, az, tail);
    fflush(f);
}

void run_clock_start(run_clock *c, const cu_clock_ctl *ctl, const cu_scene *scene, const char *scene_path,
                     cu_renderer *r)
{
    memset(c, 0, sizeof *c);
    c->ctl = *ctl;
    if (!cu_scene_sun_place(scene, &c->lat, &c->lon))
        fprintf(stderr, "cumulo: warning: %s gives no [sun] latitude or longitude: --clock shows the sun of 0 N 0 E "
                        "(set them in the scene, or --set sun.latitude=DEG --set sun.longitude=DEG)\n", scene_path);
    c->scene_t0 = cu_renderer_get_time(r);
    c->t0 = mono_ns();
    c->aimed = NAN;
    snprintf(c->utc, sizeof c->utc, "(none)");
    if (aim(c, r, 1))
        print_line(stderr, "clock", c, r, " source=start");
}

void run_clock_tick(run_clock *c, cu_renderer *r)
{
    cu_error e;
    aim(c, r, 0); /* first: the sun set by angles, the scene's time_utc (if any) no longer moves it with the time */
    if (cu_renderer_set_time(r, c->scene_t0 + elapsed_s(c), &e)) {
        if (!c->time_failing)
            fprintf(stderr, "cumulo: warning: --clock: %s; the clouds stay where they are\n", e.msg);
        c->time_failing = 1;
    } else {
        c->time_failing = 0;
    }
}

void run_clock_action(run_clock *c, const cu_action *a, const char *source, cu_renderer *r, long frames)
{
    char tail[160];
    if (a->kind == CU_ACT_STATUS) {
        aim(c, r, 0); /* the time shown now, to the second */
        snprintf(tail, sizeof tail, " frames=%ld", frames);
        print_line(stdout, "status", c, r, tail);
    } else if (a->kind == CU_ACT_SET_SUN || a->kind == CU_ACT_SET_EL || a->kind == CU_ACT_SET_AZ) {
        fprintf(stderr, "%s: with --clock the clock sets the sun: 'sun', 'elevation' and 'azimuth' are refused "
                        "(use 'offset MINUTES' or 'turn N')\n", source);
    } else if (cu_clock_ctl_apply(&c->ctl, a) && aim(c, r, 1)) {
        snprintf(tail, sizeof tail, " source=%s", source);
        print_line(stderr, "clock", c, r, tail);
    }
}

void run_clock_header(const run_clock *c, const cu_renderer *r)
{
    double el, az;
    char off[32];
    cu_renderer_get_sun(r, &el, &az);
    cu_clock_format_offset(c->ctl.offset_s, off, sizeof off);
    printf("    Sun:           clock utc=%s latitude=%.4f longitude=%.4f clock-offset=%+gs time-scale=%g\n"
           "                   offset=%s step=%gmin elevation=%.3f azimuth=%.3f\n", c->utc, c->lat, c->lon,
           c->ctl.shift_s + 0.0, c->ctl.scale, off, c->ctl.step_s / 60.0, el, az);
}
