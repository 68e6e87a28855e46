/* tests/sim/cigi_seeds.c: writes CIGI host datagrams made by the host-side encoders into a folder: the fuzz seeds of
 * tests/fuzz/seeds/cigi/ (`make cigi-seeds`); `--sof FILE` writes the IG's Start of Frame after one of them, for
 * tests/sim/cigi_tshark_check.sh to show tshark. */
#include "cigi.h"
#include "cigi_encode.h"
#include <stdio.h>
#include <string.h>

#define MARKER "CIGI" /* fuzz_cigi.c splits its input into datagrams here */

typedef struct buf {
    size_t n;
    uint8_t b[4096];
} buf;

/* One datagram of every packet a host sends, in byte order `swap`. */
static void every_packet(buf *o, int swap, uint32_t frame)
{
    size_t c = sizeof o->b;
    cu_cigi_enc_ig_control ic = {.database = 7, .ig_mode = 1, .timestamp_valid = 1, .host_frame = frame,
                                 .timestamp = 5678, .last_ig_frame = 99};
    o->n += cu_cigi_enc_ig_control_put(&ic, swap, o->b + o->n, c - o->n);
    cu_cigi_enc_entity e = {.state = 1, .parent_id = 5, .roll = 1.5f, .pitch = -2.5f, .yaw = 270.25f,
                            .lat = 47.123456789, .lon = -122.5, .alt = 1500.25};
    o->n += cu_cigi_enc_entity_put(&e, swap, o->b + o->n, c - o->n);
    cu_cigi_enc_view_control vc = {.view_id = 0, .enable = 0x25, .x = 1.25f, .y = -0.5f, .z = -2, .roll = 4,
                                   .pitch = 5, .yaw = 6};
    o->n += cu_cigi_enc_view_control_put(&vc, swap, o->b + o->n, c - o->n);
    cu_cigi_enc_view_def vd = {.view_id = 0, .group_id = 2, .enable = 0x3f, .mirror = 1, .pixel_replication = 2,
                               .view_type = 5, .reorder = 1, .near_m = 0.5f, .far_m = 20000, .left = -40,
                               .right = 41, .top = 30, .bottom = -31};
    o->n += cu_cigi_enc_view_def_put(&vd, swap, o->b + o->n, c - o->n);
    cu_cigi_enc_celestial cs = {.hour = 14, .minute = 35, .sun = 1, .stars = 1, .date_valid = 1, .date = 6212024,
                                .star_intensity = 50};
    o->n += cu_cigi_enc_celestial_put(&cs, swap, o->b + o->n, c - o->n);
    cu_cigi_enc_atmosphere a = {.model_enable = 1, .humidity = 40, .air_temp = 15, .visibility = 30000,
                                .wind_speed = 7.5f, .vertical_wind = 0.5f, .wind_dir = 225, .pressure = 1013.25f};
    o->n += cu_cigi_enc_atmosphere_put(&a, swap, o->b + o->n, c - o->n);
    cu_cigi_enc_weather w = {.layer_id = 2, .humidity = 80, .enable = 1, .scud = 1, .random_lightning = 1,
                             .cloud_type = 7, .severity = 3, .air_temp = 5, .visibility = 8000, .scud_frequency = 25,
                             .coverage = 62.5f, .base = 1200, .thickness = 800, .transition = 100, .wind_speed = 12,
                             .vertical_wind = 1, .wind_dir = 290, .pressure = 900, .aerosol = 0.25f};
    o->n += cu_cigi_enc_weather_put(&w, swap, o->b + o->n, c - o->n);
}

static void marker(buf *o)
{
    memcpy(o->b + o->n, MARKER, 4);
    o->n += 4;
}

static int save(const char *dir, const char *name, const buf *o)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(o->b, 1, o->n, f) != o->n || fclose(f)) {
        perror(path);
        return 1;
    }
    return 0;
}

/* The Start of Frame an IG answers every_packet with: IG frame 4242, timestamp 777 (10 us ticks), status 0. */
static int start_of_frame(const char *path)
{
    buf o = {0};
    every_packet(&o, 0, 1234);
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 0, 0);
    cu_sim_state st = {0};
    cu_cigi_ig_receive(&ig, o.b, o.n, &st);
    o.n = cu_cigi_start_of_frame(&ig, 4242, 777, 0, o.b, sizeof o.b);
    return save(".", path, &o);
}

int main(int argc, char **argv)
{
    if (argc == 3 && !strcmp(argv[1], "--sof"))
        return start_of_frame(argv[2]);
    if (argc != 2) {
        fprintf(stderr, "usage: cigi_seeds DIR | cigi_seeds --sof FILE\n");
        return 2;
    }
    int bad = 0;
    buf o = {0};
    every_packet(&o, 0, 1);
    bad |= save(argv[1], "every_packet_be", &o);
    o.n = 0;
    every_packet(&o, 1, 1);
    bad |= save(argv[1], "every_packet_le", &o);
    /* three datagrams: big-endian, little-endian, then one whose Weather Control has size field 0 */
    o.n = 0;
    every_packet(&o, 0, 1);
    marker(&o);
    every_packet(&o, 1, 2);
    marker(&o);
    every_packet(&o, 0, 3);
    o.b[o.n - 56 + 1] = 0;
    bad |= save(argv[1], "three_datagrams", &o);
    /* untrusted packets first, an unknown id, a known id with the wrong size, a lone byte */
    o.n = 0;
    cu_cigi_enc_atmosphere a = {.wind_speed = 3, .wind_dir = 90};
    o.n += cu_cigi_enc_atmosphere_put(&a, 0, o.b + o.n, sizeof o.b - o.n);
    cu_cigi_enc_ig_control ic = {.ig_mode = 1};
    o.n += cu_cigi_enc_ig_control_put(&ic, 0, o.b + o.n, sizeof o.b - o.n);
    o.b[o.n++] = 200, o.b[o.n++] = 4, o.n += 2;
    a.size = 28;
    o.n += cu_cigi_enc_atmosphere_put(&a, 0, o.b + o.n, sizeof o.b - o.n);
    o.b[o.n++] = 2;
    bad |= save(argv[1], "hostile", &o);
    return bad;
}
