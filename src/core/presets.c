/* src/core/presets.c: the quality presets (see presets.h). Copied from docs/sweep_presets.txt, written by `make sweep`;
 * tests/app/test_cli.sh checks that the two agree, tests/core/test_keys.c that every entry is a key of the table in
 * scene_keys.c with a value in its range. */
#include "presets.h"

static const char *const SETTINGS[CU_PRESET_COUNT] = {
    /* high: the defaults */
    "quality.segments=5;quality.segment_ratio=1.6;quality.hull_tessellation=10;quality.max_intervals=6;"
    "quality.noise_octaves=5;quality.sun_map_size=128;light.shadow=peel;light.sun_intervals=3;"
    "light.sun_samples=32;light.sun_filter=bilinear;ms.mode=slab;ms.blur=200;ms.sky_light=on;ms.closure=on;"
    "quality.integration=exponential;quality.cloud_downsample=1",
    /* medium */
    "quality.segments=5;quality.segment_ratio=1.6;quality.hull_tessellation=10;quality.max_intervals=6;"
    "quality.noise_octaves=5;quality.sun_map_size=128;light.shadow=peel;light.sun_intervals=3;"
    "light.sun_samples=32;light.sun_filter=nearest;ms.mode=diffusion;ms.blur=400;ms.sky_light=on;ms.closure=on;"
    "quality.integration=exponential;quality.cloud_downsample=1",
    /* low */
    "quality.segments=5;quality.segment_ratio=1.6;quality.hull_tessellation=10;quality.max_intervals=6;"
    "quality.noise_octaves=5;quality.sun_map_size=128;light.shadow=peel;light.sun_intervals=3;"
    "light.sun_samples=32;light.sun_filter=nearest;ms.mode=diffusion;ms.blur=400;ms.sky_light=on;ms.closure=on;"
    "quality.integration=exponential;quality.cloud_downsample=2",
};

const char *cu_preset_settings(cu_preset p)
{
    return p >= 0 && p < CU_PRESET_COUNT ? SETTINGS[p] : SETTINGS[0];
}
