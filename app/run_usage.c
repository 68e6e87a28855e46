/* app/run_usage.c: the help text of `cumulo run`, with the display back ends and inputs of this build. */
#include "run_usage.h"
#include "display.h"
#include "input_backend.h"

void run_list_display_backends(FILE *f)
{
    for (int i = 0; cu_display_backends[i]; i++)
        fprintf(f, " %s", cu_display_backends[i]->name);
    fprintf(f, " (headless = egl)\n");
}

void run_usage(FILE *f)
{
    fprintf(f,
        "usage: cumulo run SCENE [--platform drm|x11|wayland|headless] [--frames N] [--size WxH] [--fullscreen]\n"
        "                  [--mode WxH[@Hz]] [--device /dev/dri/cardN] [--input SPEC]... [--no-stdin]\n"
        "                  [--knob azimuth|elevation] [--step N] [--accel K] [--sun-elevation-range MIN:MAX]\n"
        "                  [--sun-azimuth-range MIN:MAX] [--clock [--clock-offset S] [--time-scale K]]\n"
        "                  [--set section.key=value]... [-v]\n"
        "  --input gpio:chip=gpiochip0,a=17,b=27[,button=22][,steps=4][,debounce=1000]   rotary encoder (libgpiod)\n"
        "  --input evdev:/dev/input/event3 | evdev:name=NAME   keyboard (arrows, +/-) or dial (USB knob, encoder)\n"
        "  --input stdin       commands: sun EL AZ | elevation EL | azimuth AZ | turn N | toggle | offset MINUTES |\n"
        "                      status | quit\n"
        "  stdin is read by default unless --no-stdin. Each sun change is logged on stderr as\n"
        "  'sun elevation=E azimuth=A source=S'; with --clock each change of the offset as\n"
        "  'clock utc=T offset=+Mmin elevation=E azimuth=A source=S'.\n"
        "  --platform NAME     display back end (default headless): drm full screen on DRM/KMS, x11 or wayland window\n"
        "  --frames N          stop after N frames (default: run until quit, SIGINT or SIGTERM)\n"
        "  --fullscreen        windowed back ends: cover the screen\n"
        "  --mode WxH[@Hz]     drm: the display mode (default: the connector's preferred one)\n"
        "  --device PATH       drm: /dev/dri/cardN or a /dev/dri/by-path name (default: probe)\n"
        "  --wait-display S    retry opening the display for up to S seconds, 0..3600 (boot: the KMS driver can\n"
        "                      come late; default 0)\n"
        "  --no-stdin          do not read commands from standard input (kiosks, systemd)\n"
        "  --knob AXIS         what the knob turns first: azimuth (default) or elevation; the button toggles\n"
        "  --step N            per detent: degrees, 0.001..90 (default 1; elevation moves half of it); with --clock\n"
        "                      minutes of the time of day, 0.001..1440 (default 10)\n"
        "  --accel K           acceleration of fast turns, 0..100 (default 0.25; 0: none)\n"
        "  --sun-elevation-range MIN:MAX, --sun-azimuth-range MIN:MAX   limits of the knob (degrees)\n"
        "  --clock             the sun follows the real clock (UTC) at the scene's [sun] latitude and longitude, the\n"
        "                      clouds drift in real time from its [scene] time. The knob, +/- and left/right offset\n"
        "                      the time of day by --step minutes (up/down: an hour), the button puts the offset back\n"
        "                      to 0, stdin 'offset MINUTES' sets it (-1440..1440); 'sun', 'elevation' and 'azimuth'\n"
        "                      are refused, --knob and the ranges do not apply, 'status' prints the time shown\n"
        "  --clock-offset S    with --clock: shift the clock by S seconds, -1e9..1e9 (default 0; -21600: the sky of\n"
        "                      six hours ago)\n"
        "  --time-scale K      with --clock: the clock runs K times as fast, 0 < K <= 1e6 (default 1; 1440: a day a\n"
        "                      minute); the clouds keep real time\n"
        "  --size WxH, --set SECTION.KEY=V, --data-dir DIR, -v   as for cumulo render (cumulo render --help)\n"
        "  -h, --help, --version\n");
    fprintf(f, "display back ends in this build:");
    run_list_display_backends(f);
    fprintf(f, "inputs in this build:");
    for (int i = 0; cu_input_backends[i]; i++)
        fprintf(f, " %s", cu_input_backends[i]->name);
    const cu_input_backend *gpio = cu_input_find(CU_INPUT_GPIO);
    fprintf(f, "\ngpio: %s\n", gpio ? gpio->lib : "not built (no libgpiod)");
}
