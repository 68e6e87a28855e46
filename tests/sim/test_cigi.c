/* tests/sim/test_cigi.c: the CIGI 3.3 decoder against the host-side encoders in both byte orders (every field into
 * cu_sim_state, enable bits, views, groups, layers), hostile datagrams (each counted, the state untouched, later
 * packets still read) and Start of Frame byte by byte against the ICD's layout. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <math.h>
#include <string.h>
#include <cmocka.h>
#include "cigi.h"
#include "cigi_encode.h"

/* A datagram being built: the host's byte order and the bytes so far. */
typedef struct dg {
    int swap;
    size_t n;
    uint8_t b[2048];
} dg;

static void put(dg *d, size_t n)
{
    assert_int_not_equal(n, 0);
    d->n += n;
}
#define ADD(d, fn, ...)                                                                                               \
    do {                                                                                                              \
        fn##_put_t f_ = __VA_ARGS__;                                                                                  \
        put(d, cu_cigi_enc_##fn##_put(&f_, (d)->swap, (d)->b + (d)->n, sizeof (d)->b - (d)->n));                      \
    } while (0)
typedef cu_cigi_enc_ig_control ig_control_put_t;
typedef cu_cigi_enc_entity entity_put_t;
typedef cu_cigi_enc_view_control view_control_put_t;
typedef cu_cigi_enc_view_def view_def_put_t;
typedef cu_cigi_enc_celestial celestial_put_t;
typedef cu_cigi_enc_atmosphere atmosphere_put_t;
typedef cu_cigi_enc_weather weather_put_t;

static void open_dg(dg *d, int swap, uint32_t frame)
{
    memset(d, 0, sizeof *d);
    d->swap = swap;
    ADD(d, ig_control, {.ig_mode = 1, .timestamp_valid = 1, .host_frame = frame, .timestamp = 1000 + frame});
}

static const cu_cigi_enc_entity ENTITY = {.state = 1, .roll = 1.5f, .pitch = -2.5f, .yaw = 270.25f,
                                          .lat = 47.123456789, .lon = -122.5, .alt = 1500.25};
static const cu_cigi_enc_weather LAYER2 = {.layer_id = 2, .enable = 1, .scud = 1, .cloud_type = 7, .scud_frequency = 25,
                                           .coverage = 62.5f, .base = 1200, .thickness = 800, .transition = 100,
                                           .wind_speed = 12, .wind_dir = 290};

/* Every packet counted once: the invariant cu_cigi_stats documents. */
static void assert_stats_add_up(const cu_cigi_ig *ig)
{
    const cu_cigi_stats *s = &ig->stats;
    assert_int_equal(s->packets, s->applied + s->skipped + s->skipped_unknown + s->malformed + s->wrong_version +
                                     s->untrusted + s->nonfinite + s->out_of_range);
}

static int receive(cu_cigi_ig *ig, const dg *d, cu_sim_state *st)
{
    int n = cu_cigi_ig_receive(ig, d->b, d->n, st);
    assert_stats_add_up(ig);
    return n;
}

static void round_trip(int swap)
{
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 3, 0);
    cu_sim_state st = {0};
    dg d;
    open_dg(&d, swap, 1234);
    ADD(&d, entity, ENTITY);
    ADD(&d, view_def, {.view_id = 3, .group_id = 2, .enable = 63, .near_m = 0.5f, .far_m = 20000, .left = -40,
                       .right = 41, .top = 30, .bottom = -31});
    ADD(&d, view_control, {.view_id = 3, .enable = 63, .x = 1.25f, .y = -0.5f, .z = -2, .roll = 4, .pitch = 5,
                           .yaw = 6});
    ADD(&d, celestial, {.hour = 14, .minute = 35, .sun = 1, .date_valid = 1, .date = 6212024});
    ADD(&d, atmosphere, {.wind_speed = 7.5f, .wind_dir = 225, .pressure = 1013.25f});
    ADD(&d, weather, LAYER2);
    assert_int_equal(receive(&ig, &d, &st), 7);
    assert_int_equal(ig.stats.applied, 7);
    assert_int_equal(ig.swap, swap);
    assert_int_equal(ig.host_frame, 1234);
    assert_int_equal(ig.timestamp, 2234);
    assert_int_equal(ig.ig_mode, 1);
    assert_true(ig.timestamp_valid && ig.have_frame);
    assert_int_equal(st.changed, CU_SIM_POSE | CU_SIM_VIEW | CU_SIM_FRUSTUM | CU_SIM_TIME | CU_SIM_WIND |
                                     CU_SIM_LAYERS);
    assert_true(st.pose_valid);
    assert_true(st.lat_deg == 47.123456789 && st.lon_deg == -122.5 && st.alt_m == 1500.25);
    assert_true(st.yaw_deg == 270.25 && st.pitch_deg == -2.5 && st.roll_deg == 1.5);
    assert_true(st.view_xyz[0] == 1.25 && st.view_xyz[1] == -0.5 && st.view_xyz[2] == -2);
    assert_true(st.view_roll_deg == 4 && st.view_pitch_deg == 5 && st.view_yaw_deg == 6);
    assert_true(st.frustum_valid);
    assert_true(st.near_m == 0.5 && st.far_m == 20000);
    assert_true(st.fov_left_deg == -40 && st.fov_right_deg == 41 && st.fov_top_deg == 30 && st.fov_bottom_deg == -31);
    assert_int_equal(ig.view_group, 2);
    assert_true(st.time_valid);
    assert_int_equal(st.year, 2024);
    assert_int_equal(st.month, 6);
    assert_int_equal(st.day, 21);
    assert_int_equal(st.hour, 14);
    assert_int_equal(st.minute, 35);
    assert_true(st.second == 0);
    assert_true(st.wind_valid && st.wind_speed == 7.5 && st.wind_from_deg == 225);
    const cu_sim_layer *l = &st.layers[1];
    assert_true(l->enabled && l->scud);
    assert_int_equal(l->type, CU_SIM_CLOUD_CUMULUS);
    assert_true(l->coverage == 0.625 && l->scud_frequency == 0.25);
    assert_true(l->base_m == 1200 && l->thickness_m == 800 && l->transition_m == 100);
    assert_true(l->wind_speed == 12 && l->wind_from_deg == 290);
    assert_false(st.layers[0].enabled || st.layers[2].enabled);
}

static void test_round_trip_big_endian(void **state)
{
    (void)state;
    round_trip(0);
}

static void test_round_trip_little_endian(void **state)
{
    (void)state;
    round_trip(1);
}

/* A disabled field keeps its value; a View Definition's first fields come with the IG's default frustum. */
static void test_enable_bits(void **state)
{
    (void)state;
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 0, 0);
    cu_sim_state st = {0};
    dg d;
    open_dg(&d, 0, 1);
    ADD(&d, view_control, {.enable = 63, .x = 1, .y = 2, .z = 3, .roll = 4, .pitch = 5, .yaw = 6});
    ADD(&d, view_control, {.enable = CU_CIGI_EN_Y | CU_CIGI_EN_PITCH, .x = NAN, .y = 20, .z = 1e30f, .roll = NAN,
                           .pitch = 50, .yaw = INFINITY});
    ADD(&d, view_def, {.enable = CU_CIGI_EN_FAR | CU_CIGI_EN_TOP, .near_m = NAN, .far_m = 5000, .top = 25});
    ADD(&d, view_def, {.enable = CU_CIGI_EN_RIGHT, .left = 80, .right = 35});
    assert_int_equal(receive(&ig, &d, &st), 5);
    assert_true(st.view_xyz[0] == 1 && st.view_xyz[1] == 20 && st.view_xyz[2] == 3);
    assert_true(st.view_roll_deg == 4 && st.view_pitch_deg == 50 && st.view_yaw_deg == 6);
    assert_true(st.near_m == CU_CIGI_DEFAULT_NEAR_M && st.far_m == 5000);
    assert_true(st.fov_left_deg == -CU_CIGI_DEFAULT_HALF_H_DEG && st.fov_right_deg == 35);
    assert_true(st.fov_top_deg == 25 && st.fov_bottom_deg == -CU_CIGI_DEFAULT_HALF_V_DEG);
    /* no enable bit: applied, nothing changes */
    st.changed = 0;
    open_dg(&d, 0, 2);
    ADD(&d, view_control, {.enable = 0, .x = 99});
    assert_int_equal(receive(&ig, &d, &st), 2);
    assert_int_equal(st.changed, 0);
    assert_true(st.view_xyz[0] == 1);
}

/* Other views, other groups, other entities, inactive or attached ownship, non-cloud weather: skipped, not errors. */
static void test_not_for_this_ig(void **state)
{
    (void)state;
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 1, 7);
    cu_sim_state st = {0}, before;
    dg d;
    open_dg(&d, 1, 1);
    cu_cigi_enc_entity e = ENTITY;
    e.entity_id = 6;
    ADD(&d, entity, e);
    e.entity_id = 7, e.state = 0;
    ADD(&d, entity, e);
    e.state = 2;
    ADD(&d, entity, e);
    e.state = 1, e.attached = 1;
    ADD(&d, entity, e);
    ADD(&d, view_control, {.view_id = 2, .entity_id = 7, .enable = 63});
    ADD(&d, view_control, {.view_id = 1, .group_id = 4, .entity_id = 7, .enable = 63}); /* group 4: not ours (yet) */
    ADD(&d, view_control, {.view_id = 1, .entity_id = 8, .enable = 63});
    ADD(&d, view_def, {.view_id = 2, .enable = 63, .near_m = 1, .far_m = 2, .left = -1, .right = 1, .top = 1,
                       .bottom = -1});
    ADD(&d, view_def, {.view_id = 1, .orthographic = 1, .enable = 63, .near_m = 1, .far_m = 2, .left = -1,
                       .right = 1, .top = 1, .bottom = -1});
    ADD(&d, celestial, {.hour = 5, .date_valid = 0, .date = 1012000});
    cu_cigi_enc_weather w = LAYER2;
    w.scope = 1;
    ADD(&d, weather, w);
    w.scope = 2;
    ADD(&d, weather, w);
    w.scope = 0, w.layer_id = 0;
    ADD(&d, weather, w);
    w.layer_id = 4;
    ADD(&d, weather, w);
    before = st;
    assert_int_equal(receive(&ig, &d, &st), 1);
    assert_int_equal(ig.stats.skipped, 14);
    assert_memory_equal(&st, &before, sizeof st);

    /* the View Definition for our view puts it in group 4: View Control for group 4 now moves it, whatever its id */
    open_dg(&d, 1, 2);
    ADD(&d, view_def, {.view_id = 1, .group_id = 4, .enable = 0});
    ADD(&d, view_control, {.view_id = 9, .group_id = 4, .entity_id = 7, .enable = CU_CIGI_EN_Z, .z = -1.5f});
    e.attached = 0;
    ADD(&d, entity, e);
    assert_int_equal(receive(&ig, &d, &st), 4);
    assert_int_equal(ig.view_group, 4);
    assert_true(st.view_xyz[2] == -1.5 && st.pose_valid && st.lat_deg == ENTITY.lat);
}

/* One hostile packet between an IG Control and a sound Atmosphere Control: counted in the stats field at `counter`
 * (an offset into cu_cigi_stats), its message names the packet and the field, the state does not move, and the packet
 * after it is still read. */
#define STAT(f) offsetof(cu_cigi_stats, f)
static unsigned long stat_at(const cu_cigi_ig *ig, size_t off)
{
    unsigned long v;
    memcpy(&v, (const char *)&ig->stats + off, sizeof v);
    return v;
}

static void expect_rejected(dg *d, size_t counter, const char *fragment)
{
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 0, 0);
    cu_sim_state st = {0};
    st.frustum_valid = 1, st.near_m = 1, st.far_m = 1000, st.fov_left_deg = -30, st.fov_right_deg = 30;
    st.fov_top_deg = 20, st.fov_bottom_deg = -20;
    ADD(d, atmosphere, {.wind_speed = 3, .wind_dir = -90});
    cu_sim_state before = st;
    assert_int_equal(receive(&ig, d, &st), 2); /* IG Control and Atmosphere Control */
    if (stat_at(&ig, counter) != 1)
        fail_msg("'%s': counter at %zu is %lu (message '%s')", fragment, counter, stat_at(&ig, counter),
                 ig.last_error);
    if (!strstr(ig.last_error, fragment))
        fail_msg("message '%s' lacks '%s'", ig.last_error, fragment);
    assert_true(st.wind_valid && st.wind_speed == 3 && st.wind_from_deg == 270);
    st.wind_valid = before.wind_valid, st.wind_speed = before.wind_speed, st.wind_from_deg = before.wind_from_deg;
    st.changed = before.changed;
    assert_memory_equal(&st, &before, sizeof st);
}

static void test_hostile_values(void **state)
{
    (void)state;
    for (int swap = 0; swap < 2; swap++) {
        dg d;
        cu_cigi_enc_entity e = ENTITY;
#define ENTITY_WITH(field, value, counter, text)                                                                      \
    do {                                                                                                              \
        open_dg(&d, swap, 1);                                                                                         \
        e = ENTITY;                                                                                                   \
        e.field = value;                                                                                              \
        ADD(&d, entity, e);                                                                                           \
        expect_rejected(&d, STAT(counter), text);                                                                     \
    } while (0)
        ENTITY_WITH(lat, 91, out_of_range, "Entity Control: latitude 91 outside -90..90");
        ENTITY_WITH(lat, -90.000001, out_of_range, "latitude");
        ENTITY_WITH(lon, NAN, nonfinite, "Entity Control: longitude is nan");
        ENTITY_WITH(lon, 180.5, out_of_range, "longitude 180.5");
        ENTITY_WITH(alt, 2e6, out_of_range, "altitude 2e+06");
        ENTITY_WITH(alt, -INFINITY, nonfinite, "altitude is -inf");
        ENTITY_WITH(roll, 181, out_of_range, "roll");
        ENTITY_WITH(pitch, 90.5f, out_of_range, "pitch");
        ENTITY_WITH(yaw, NAN, nonfinite, "yaw");
        ENTITY_WITH(yaw, 1e30f, out_of_range, "yaw");
#define ONE(fn, counter, text, ...)                                                                                   \
    do {                                                                                                              \
        open_dg(&d, swap, 1);                                                                                         \
        ADD(&d, fn, __VA_ARGS__);                                                                                     \
        expect_rejected(&d, STAT(counter), text);                                                                     \
    } while (0)
        ONE(view_control, nonfinite, "View Control: x offset is nan", {.enable = CU_CIGI_EN_X, .x = NAN});
        ONE(view_control, out_of_range, "z offset", {.enable = CU_CIGI_EN_Z, .z = 2e5f});
        ONE(view_control, out_of_range, "pitch 91", {.enable = CU_CIGI_EN_PITCH, .pitch = 91});
        ONE(view_def, out_of_range, "View Definition: left -90 outside -90..90 (open)",
            {.enable = CU_CIGI_EN_LEFT, .left = -90});
        ONE(view_def, out_of_range, "left 31 not left of right 30", {.enable = CU_CIGI_EN_LEFT, .left = 31});
        ONE(view_def, out_of_range, "left 10 not left of right 10",
            {.enable = CU_CIGI_EN_LEFT | CU_CIGI_EN_RIGHT, .left = 10, .right = 10});
        ONE(view_def, out_of_range, "bottom 25 not below top 20", {.enable = CU_CIGI_EN_BOTTOM, .bottom = 25});
        ONE(view_def, out_of_range, "near 0 outside", {.enable = CU_CIGI_EN_NEAR, .near_m = 0});
        ONE(view_def, out_of_range, "near 2000 not nearer than far 1000", {.enable = CU_CIGI_EN_NEAR, .near_m = 2000});
        ONE(view_def, nonfinite, "far is inf", {.enable = CU_CIGI_EN_FAR, .far_m = INFINITY});
        ONE(view_def, nonfinite, "top is nan", {.enable = CU_CIGI_EN_TOP, .top = NAN});
        ONE(celestial, out_of_range, "Celestial Sphere Control: hour 24 outside 0..23",
            {.date_valid = 1, .hour = 24, .date = 1012024});
        ONE(celestial, out_of_range, "minute 60", {.date_valid = 1, .minute = 60, .date = 1012024});
        ONE(celestial, out_of_range, "date 02302024", {.date_valid = 1, .date = 2302024});
        ONE(celestial, out_of_range, "date 02292023", {.date_valid = 1, .date = 2292023});
        ONE(celestial, out_of_range, "date 02291900", {.date_valid = 1, .date = 2291900});
        ONE(celestial, out_of_range, "date 13012024", {.date_valid = 1, .date = 13012024});
        ONE(celestial, out_of_range, "date 00012024", {.date_valid = 1, .date = 12024});
        ONE(celestial, out_of_range, "date 01002024", {.date_valid = 1, .date = 1002024});
        ONE(celestial, out_of_range, "date 4294967295", {.date_valid = 1, .date = 0xffffffffu});
        ONE(atmosphere, nonfinite, "Atmosphere Control: horizontal wind speed is nan", {.wind_speed = NAN});
        ONE(atmosphere, out_of_range, "horizontal wind speed -1", {.wind_speed = -1});
        ONE(atmosphere, out_of_range, "wind direction 1000", {.wind_dir = 1000});
        cu_cigi_enc_weather w;
#define WEATHER_WITH(field, value, counter, text)                                                                     \
    do {                                                                                                              \
        open_dg(&d, swap, 1);                                                                                         \
        w = LAYER2;                                                                                                   \
        w.field = value;                                                                                              \
        ADD(&d, weather, w);                                                                                          \
        expect_rejected(&d, STAT(counter), text);                                                                     \
    } while (0)
        WEATHER_WITH(coverage, 100.5f, out_of_range, "Weather Control: coverage 100.5 outside 0..100");
        WEATHER_WITH(coverage, -1, out_of_range, "coverage -1");
        WEATHER_WITH(coverage, NAN, nonfinite, "coverage is nan");
        WEATHER_WITH(scud_frequency, 101, out_of_range, "scud frequency 101");
        WEATHER_WITH(base, INFINITY, nonfinite, "base elevation is inf");
        WEATHER_WITH(thickness, -5, out_of_range, "thickness -5");
        WEATHER_WITH(transition, 3e5f, out_of_range, "transition band");
        WEATHER_WITH(wind_speed, 400, out_of_range, "horizontal wind speed 400");
        WEATHER_WITH(wind_dir, NAN, nonfinite, "wind direction is nan");
    }
}

/* Weather with a valid layer leaves the other layers alone; a later packet of a layer replaces it whole. */
static void test_layers(void **state)
{
    (void)state;
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 0, 0);
    cu_sim_state st = {0};
    dg d;
    open_dg(&d, 0, 1);
    for (int id = 1; id <= 3; id++) {
        cu_cigi_enc_weather w = LAYER2;
        w.layer_id = (uint8_t)id, w.base = 1000.0f * (float)id, w.cloud_type = (uint8_t)(id + 10);
        w.enable = id != 2, w.wind_dir = -90;
        ADD(&d, weather, w);
    }
    assert_int_equal(receive(&ig, &d, &st), 4);
    for (int i = 0; i < 3; i++) {
        assert_true(st.layers[i].base_m == 1000.0 * (i + 1));
        assert_int_equal(st.layers[i].type, i + 11); /* "other" types are kept as given */
        assert_int_equal(st.layers[i].enabled, i != 1);
        assert_true(st.layers[i].wind_from_deg == 270);
    }
    /* from -1e-30 degrees: fmod keeps the sign, and 360 - 1e-30 rounds to 360, outside [0, 360) (found by fuzz_cigi) */
    open_dg(&d, 0, 2);
    ADD(&d, atmosphere, {.wind_speed = 1, .wind_dir = -1e-30f});
    ADD(&d, weather, {.layer_id = 1, .wind_dir = -360});
    assert_int_equal(receive(&ig, &d, &st), 3);
    assert_true(st.wind_from_deg == 0 && st.layers[0].wind_from_deg == 0);
}

/* Size field 0 or 1 would loop for ever: the datagram ends there, the next one is read. */
static void test_size_zero_ends_datagram(void **state)
{
    (void)state;
    for (unsigned size = 0; size < 2; size++) {
        cu_cigi_ig ig;
        cu_cigi_ig_init(&ig, 0, 0);
        cu_sim_state st = {0};
        dg d;
        open_dg(&d, 0, 1);
        size_t at = d.n;
        ADD(&d, entity, ENTITY);
        d.b[at + 1] = (uint8_t)size;
        ADD(&d, atmosphere, {.wind_speed = 3});
        assert_int_equal(receive(&ig, &d, &st), 1);
        assert_int_equal(ig.stats.malformed, 1);
        assert_int_equal(ig.stats.packets, 2);
        assert_non_null(strstr(ig.last_error, "size field"));
        assert_false(st.pose_valid || st.wind_valid);
        open_dg(&d, 0, 2);
        ADD(&d, entity, ENTITY);
        assert_int_equal(receive(&ig, &d, &st), 2);
        assert_true(st.pose_valid);
    }
}

/* A size field running past the end, a lone trailing byte, every truncation of a whole datagram: nothing read
 * outside the bytes given (ASan and valgrind watch), the complete packets before the cut still applied. */
static void test_truncated(void **state)
{
    (void)state;
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 0, 0);
    cu_sim_state st = {0};
    dg d;
    open_dg(&d, 0, 1);
    ADD(&d, atmosphere, {.wind_speed = 3});
    ADD(&d, entity, ENTITY);
    for (size_t len = 0; len <= d.n; len++) {
        uint8_t copy[sizeof d.b]; /* exactly len bytes on the heap-less stack copy: the decoder sees only those */
        memcpy(copy, d.b, len);
        cu_sim_state s = {0};
        int n = cu_cigi_ig_receive(&ig, copy, len, &s);
        assert_stats_add_up(&ig);
        int expect = len < 24 ? 0 : len < 56 ? 1 : len < 104 ? 2 : 3;
        assert_int_equal(n, expect);
        assert_int_equal(s.pose_valid, len == d.n);
    }
    open_dg(&d, 0, 2);
    ADD(&d, entity, ENTITY);
    d.n -= 1;
    assert_int_equal(receive(&ig, &d, &st), 1);
    assert_non_null(strstr(ig.last_error, "Entity Control (id 2) at offset 24: size 48 runs past the end"));
    open_dg(&d, 0, 3);
    d.b[d.n++] = 2;
    assert_int_equal(receive(&ig, &d, &st), 1);
    assert_non_null(strstr(ig.last_error, "lone byte at offset 24"));
    assert_null(cu_cigi_ig_receive(&ig, NULL, 100, &st) ? "read a NULL buffer" : NULL);
}

/* A known packet whose size field is not its 3.3 size is malformed and passed over by that size; unknown ids are
 * skipped by theirs. */
static void test_wrong_size_and_unknown(void **state)
{
    (void)state;
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 0, 0);
    cu_sim_state st = {0};
    dg d;
    open_dg(&d, 0, 1);
    size_t at = d.n;
    ADD(&d, entity, ENTITY);
    d.b[at + 1] = 52;
    d.n += 4;
    at = d.n;
    ADD(&d, atmosphere, {.wind_speed = 3});
    d.b[at + 1] = 24; /* shorter than its packet (the sender wrote only 24 bytes) */
    d.n -= 8;
    d.b[d.n++] = 200, d.b[d.n++] = 6, d.n += 4;              /* a user-defined packet */
    d.b[d.n++] = 4, d.b[d.n++] = 24, d.n += 22;              /* Articulated Part Control: not read by this IG */
    ADD(&d, atmosphere, {.wind_speed = 4});
    assert_int_equal(receive(&ig, &d, &st), 2);
    assert_int_equal(ig.stats.malformed, 2);
    assert_int_equal(ig.stats.skipped_unknown, 2);
    assert_int_equal(ig.stats.packets, 6);
    assert_non_null(strstr(ig.last_error, "Atmosphere Control: size field 24, the packet has 32 bytes"));
    assert_false(st.pose_valid);
    assert_true(st.wind_valid && st.wind_speed == 4);
}

/* The version: CIGI 2 (major 2), CIGI 3.0/3.1 (16-byte IG Control), minor versions other than 2 and 3. */
static void test_wrong_version(void **state)
{
    (void)state;
    static const struct { uint8_t major, minor, size; const char *text; } cases[] = {
        {2, 3, 0, "major version 2"}, {4, 3, 0, "major version 4"}, {3, 1, 0, "minor version 1"},
        {3, 15, 0, "minor version 15"}, {3, 3, 16, "16 bytes is CIGI 3.0/3.1"}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cu_cigi_ig ig;
        cu_cigi_ig_init(&ig, 0, 0);
        cu_sim_state st = {0};
        dg d = {0};
        ADD(&d, ig_control, {.major = cases[i].major, .minor = cases[i].minor, .size = cases[i].size});
        if (cases[i].size)
            d.n = cases[i].size;
        ADD(&d, entity, ENTITY);
        assert_int_equal(receive(&ig, &d, &st), 0);
        assert_int_equal(ig.stats.wrong_version, 1);
        assert_int_equal(ig.stats.packets, 1); /* nothing after it is read */
        assert_false(ig.have_frame || st.pose_valid);
        if (!strstr(ig.last_error, cases[i].text))
            fail_msg("message '%s' lacks '%s'", ig.last_error, cases[i].text);
    }
    /* 3.2 lays out everything read here as 3.3 does */
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 0, 0);
    cu_sim_state st = {0};
    dg d = {0};
    ADD(&d, ig_control, {.minor = 2, .host_frame = 5});
    ADD(&d, entity, ENTITY);
    assert_int_equal(receive(&ig, &d, &st), 2);
}

/* Packets before a valid IG Control are not trusted: none first, a bad magic number, a bad size, IG mode 3. */
static void test_untrusted(void **state)
{
    (void)state;
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 0, 0);
    cu_sim_state st = {0};
    dg d = {0};
    ADD(&d, entity, ENTITY);
    ADD(&d, ig_control, {.host_frame = 9});
    ADD(&d, atmosphere, {.wind_speed = 3});
    assert_int_equal(receive(&ig, &d, &st), 2);
    assert_int_equal(ig.stats.untrusted, 1);
    assert_false(st.pose_valid);
    assert_true(st.wind_valid);
    static const struct { cu_cigi_enc_ig_control ic; size_t counter; const char *text; } cases[] = {
        {{.magic = 0x1234}, STAT(malformed), "magic number 0x1234"},
        {{.magic = 0x8080}, STAT(malformed), "magic number 0x8080"},
        {{.size = 28}, STAT(malformed), "IG Control: size field 28"},
        {{.ig_mode = 3}, STAT(out_of_range), "IG mode 3"}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cu_cigi_ig_init(&ig, 0, 0);
        cu_sim_state s = {0};
        memset(&d, 0, sizeof d);
        ADD(&d, ig_control, cases[i].ic);
        if (cases[i].ic.size)
            d.n = cases[i].ic.size;
        ADD(&d, entity, ENTITY);
        ADD(&d, atmosphere, {.wind_speed = 3});
        assert_int_equal(receive(&ig, &d, &s), 0);
        assert_int_equal(stat_at(&ig, cases[i].counter), 1);
        assert_int_equal(ig.stats.untrusted, 2);
        assert_false(s.pose_valid || s.wind_valid || ig.have_frame);
        if (!strstr(ig.last_error, cases[i].text) && !strstr(ig.last_error, "not trusted"))
            fail_msg("message '%s' lacks '%s'", ig.last_error, cases[i].text);
    }
}

/* Byte order follows each datagram's IG Control; frames are taken one at a time. */
static void test_byte_order_and_frames(void **state)
{
    (void)state;
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 0, 0);
    cu_sim_state st = {0};
    dg d;
    for (int i = 0; i < 4; i++) {
        open_dg(&d, i & 1, 0x01020304u + (uint32_t)i);
        ADD(&d, entity, ENTITY);
        assert_int_equal(receive(&ig, &d, &st), 2);
        assert_int_equal(ig.swap, i & 1);
        assert_int_equal(ig.host_frame, 0x01020304u + (uint32_t)i);
        assert_true(st.lat_deg == ENTITY.lat);
        assert_true(ig.have_frame);
        cu_cigi_ig_frame_taken(&ig);
        assert_false(ig.have_frame);
    }
    assert_int_equal(ig.stats.datagrams, 4);
}

/* Start of Frame, expected bytes from the ICD's layout (not from an encoder): 101, 24, major 3, database -3 (0xfd),
 * status 2, IG mode 1 | timestamp valid 0x04 | WGS 84 0 | minor 3 << 4 = 0x35, magic 0x8000, IG frame 0x0a0b0c0d,
 * timestamp 777 = 0x309, last host frame 0xdeadbeef, four reserved zero bytes. */
static void test_start_of_frame_bytes(void **state)
{
    (void)state;
    cu_cigi_ig ig;
    cu_cigi_ig_init(&ig, 0, 0);
    cu_sim_state st = {0};
    dg d = {.swap = 1};
    ADD(&d, ig_control, {.database = -3, .ig_mode = 1, .host_frame = 0xdeadbeefu});
    receive(&ig, &d, &st);
    uint8_t out[32];
    memset(out, 0xaa, sizeof out);
    assert_int_equal(cu_cigi_start_of_frame(&ig, 0x0a0b0c0du, 777, 2, out, sizeof out), 24);
    static const uint8_t want[24] = {101, 24, 3, 0xfd, 2, 0x35, 0x80, 0x00, 0x0a, 0x0b, 0x0c, 0x0d,
                                     0x00, 0x00, 0x03, 0x09, 0xde, 0xad, 0xbe, 0xef, 0, 0, 0, 0};
    assert_memory_equal(out, want, sizeof want);
    assert_int_equal(out[24], 0xaa); /* nothing past the packet */
    cu_cigi_dec_sof f;
    assert_int_equal(cu_cigi_dec_sof_get(out, 24, &f), 0);
    assert_int_equal(f.ig_frame, 0x0a0b0c0du);
    assert_int_equal(f.last_host_frame, 0xdeadbeefu);
    assert_int_equal(f.database, -3);
    assert_int_equal(f.minor, 3);
    assert_int_equal(f.swap, 0);
    memset(out, 0xaa, sizeof out);
    assert_int_equal(cu_cigi_start_of_frame(&ig, 1, 1, 0, out, 23), 0);
    assert_int_equal(out[0], 0xaa);
}

/* The encoders themselves, against bytes from the ICD: a little-endian IG Control writes its magic as 00 80. */
static void test_encoder_bytes(void **state)
{
    (void)state;
    uint8_t b[24];
    cu_cigi_enc_ig_control ic = {.ig_mode = 2, .timestamp_valid = 1, .host_frame = 0x11223344u};
    assert_int_equal(cu_cigi_enc_ig_control_put(&ic, 1, b, sizeof b), 24);
    static const uint8_t le[12] = {1, 24, 3, 0, 0x36, 0, 0x00, 0x80, 0x44, 0x33, 0x22, 0x11};
    assert_memory_equal(b, le, sizeof le);
    assert_int_equal(cu_cigi_enc_ig_control_put(&ic, 0, b, sizeof b), 24);
    static const uint8_t be[12] = {1, 24, 3, 0, 0x36, 0, 0x80, 0x00, 0x11, 0x22, 0x33, 0x44};
    assert_memory_equal(b, be, sizeof be);
    assert_int_equal(cu_cigi_enc_ig_control_put(&ic, 0, b, 23), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip_big_endian),
        cmocka_unit_test(test_round_trip_little_endian),
        cmocka_unit_test(test_enable_bits),
        cmocka_unit_test(test_not_for_this_ig),
        cmocka_unit_test(test_hostile_values),
        cmocka_unit_test(test_layers),
        cmocka_unit_test(test_size_zero_ends_datagram),
        cmocka_unit_test(test_truncated),
        cmocka_unit_test(test_wrong_size_and_unknown),
        cmocka_unit_test(test_wrong_version),
        cmocka_unit_test(test_untrusted),
        cmocka_unit_test(test_byte_order_and_frames),
        cmocka_unit_test(test_start_of_frame_bytes),
        cmocka_unit_test(test_encoder_bytes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
