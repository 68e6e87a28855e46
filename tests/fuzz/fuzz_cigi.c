/* tests/fuzz/fuzz_cigi.c: libFuzzer target for the CIGI 3.3 decoder: the input, split into datagrams at "CIGI", goes
 * into one IG; after each datagram the state stays finite and within its documented ranges and the stats add up. */
#include "fuzz.h"
#include "cigi.h"
#include <math.h>

#define IN(v, lo, hi) (isfinite(v) && (v) >= (lo) && (v) <= (hi))
#define DIRECTION(v) (isfinite(v) && (v) >= 0 && (v) < 360) /* [0, 360) */

static void check_state(const cu_sim_state *s)
{
    FUZZ_CHECK((s->changed & ~0x3fu) == 0, "changed bits 0x%x", s->changed);
    if (s->pose_valid) {
        FUZZ_CHECK(IN(s->lat_deg, -90, 90) && IN(s->lon_deg, -180, 180), "at %g %g", s->lat_deg, s->lon_deg);
        FUZZ_CHECK(IN(s->alt_m, -CU_CIGI_ALT_MAX_M, CU_CIGI_ALT_MAX_M), "altitude %g", s->alt_m);
        FUZZ_CHECK(IN(s->yaw_deg, -180, 360) && IN(s->pitch_deg, -90, 90) && IN(s->roll_deg, -180, 180),
                   "attitude %g %g %g", s->yaw_deg, s->pitch_deg, s->roll_deg);
    } else {
        FUZZ_CHECK(s->lat_deg == 0 && s->lon_deg == 0 && s->alt_m == 0 && s->yaw_deg == 0, "pose without valid");
    }
    for (int i = 0; i < 3; i++)
        FUZZ_CHECK(IN(s->view_xyz[i], -CU_CIGI_OFFSET_MAX_M, CU_CIGI_OFFSET_MAX_M), "view %d %g", i, s->view_xyz[i]);
    FUZZ_CHECK(IN(s->view_yaw_deg, -180, 360) && IN(s->view_pitch_deg, -90, 90) && IN(s->view_roll_deg, -180, 180),
               "view rotation %g %g %g", s->view_yaw_deg, s->view_pitch_deg, s->view_roll_deg);
    if (s->frustum_valid) {
        FUZZ_CHECK(isfinite(s->near_m) && s->near_m > 0 && s->near_m < s->far_m && s->far_m <= CU_CIGI_FAR_MAX_M,
                   "near %g far %g", s->near_m, s->far_m);
        FUZZ_CHECK(s->fov_left_deg > -90 && s->fov_left_deg < s->fov_right_deg && s->fov_right_deg < 90,
                   "left %g right %g", s->fov_left_deg, s->fov_right_deg);
        FUZZ_CHECK(s->fov_bottom_deg > -90 && s->fov_bottom_deg < s->fov_top_deg && s->fov_top_deg < 90,
                   "bottom %g top %g", s->fov_bottom_deg, s->fov_top_deg);
    } else {
        FUZZ_CHECK(s->near_m == 0 && s->far_m == 0 && s->fov_left_deg == 0, "frustum without valid");
    }
    if (s->time_valid) {
        FUZZ_CHECK(s->year >= 1 && s->year <= 9999 && s->month >= 1 && s->month <= 12 && s->day >= 1 &&
                       s->day <= 31, "date %d-%d-%d", s->year, s->month, s->day);
        FUZZ_CHECK(s->hour >= 0 && s->hour <= 23 && s->minute >= 0 && s->minute <= 59 && s->second == 0,
                   "time %d:%d:%g", s->hour, s->minute, s->second);
    } else {
        FUZZ_CHECK(s->year == 0 && s->hour == 0, "time without valid");
    }
    if (s->wind_valid)
        FUZZ_CHECK(IN(s->wind_speed, 0, CU_CIGI_WIND_MAX_MS) && DIRECTION(s->wind_from_deg),
                   "wind %g from %.17g", s->wind_speed, s->wind_from_deg);
    else
        FUZZ_CHECK(s->wind_speed == 0 && s->wind_from_deg == 0, "wind without valid");
    for (int i = 0; i < CU_SIM_LAYERS_MAX; i++) {
        const cu_sim_layer *l = &s->layers[i];
        FUZZ_CHECK((l->enabled == 0 || l->enabled == 1) && (l->scud == 0 || l->scud == 1), "layer %d flags", i);
        FUZZ_CHECK(l->type >= 0 && l->type <= 15, "layer %d type %d", i, l->type);
        FUZZ_CHECK(IN(l->coverage, 0, 1) && IN(l->scud_frequency, 0, 1), "layer %d coverage %g scud %g", i,
                   l->coverage, l->scud_frequency);
        FUZZ_CHECK(IN(l->base_m, -CU_CIGI_LAYER_MAX_M, CU_CIGI_LAYER_MAX_M) &&
                       IN(l->thickness_m, 0, CU_CIGI_LAYER_MAX_M) && IN(l->transition_m, 0, CU_CIGI_LAYER_MAX_M),
                   "layer %d base %g thickness %g transition %g", i, l->base_m, l->thickness_m, l->transition_m);
        FUZZ_CHECK(IN(l->wind_speed, 0, CU_CIGI_WIND_MAX_MS) && DIRECTION(l->wind_from_deg),
                   "layer %d wind %g from %.17g", i, l->wind_speed, l->wind_from_deg);
    }
}

static void check_ig(const cu_cigi_ig *ig, unsigned long datagrams)
{
    const cu_cigi_stats *s = &ig->stats;
    FUZZ_CHECK(s->datagrams == datagrams, "%lu datagrams counted, %lu given", s->datagrams, datagrams);
    FUZZ_CHECK(s->packets == s->applied + s->skipped + s->skipped_unknown + s->malformed + s->wrong_version +
                                 s->untrusted + s->nonfinite + s->out_of_range,
               "%lu packets, counted %lu + %lu + %lu + %lu + %lu + %lu + %lu + %lu", s->packets, s->applied,
               s->skipped, s->skipped_unknown, s->malformed, s->wrong_version, s->untrusted, s->nonfinite,
               s->out_of_range);
    FUZZ_CHECK(ig->ig_mode >= 0 && ig->ig_mode <= 2, "IG mode %d", ig->ig_mode);
    FUZZ_CHECK(ig->swap == 0 || ig->swap == 1, "swap %d", ig->swap);
    FUZZ_CHECK(memchr(ig->last_error, 0, sizeof ig->last_error) != NULL, "last_error not terminated");
    FUZZ_CHECK(ig->view_id == 0 && ig->entity_id == 0, "the IG's view or entity changed");
    uint8_t sof[24];
    FUZZ_CHECK(cu_cigi_start_of_frame(ig, 1, 2, 0, sof, sizeof sof) == 24 && sof[0] == 101 && sof[6] == 0x80,
               "Start of Frame");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 0, 0);
    cu_sim_state st;
    memset(&st, 0, sizeof st);
    unsigned long datagrams = 0;
    size_t start = 0;
    while (start <= size) {
        size_t end = start;
        while (end + 4 <= size && memcmp(data + end, "CIGI", 4))
            end++;
        if (end + 4 > size)
            end = size;
        unsigned long before = ig.stats.packets, applied = ig.stats.applied;
        int n = cu_cigi_ig_receive(&ig, data + start, end - start, &st);
        datagrams++;
        FUZZ_CHECK(n >= 0 && (unsigned long)n == ig.stats.applied - applied, "returned %d, applied %lu", n,
                   ig.stats.applied - applied);
        /* bounded work: a packet takes at least 2 bytes, but for a lone last byte */
        FUZZ_CHECK(ig.stats.packets - before <= (end - start) / 2 + 1, "%lu packets from %zu bytes",
                   ig.stats.packets - before, end - start);
        check_state(&st);
        check_ig(&ig, datagrams);
        start = end + 4;
    }
    return 0;
}
