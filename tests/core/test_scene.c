/* tests/core/test_scene.c: the scene parser on good files and on hostile input, each bad case with its exact
 * message. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "scene.h"

#define MIN_SCENE "[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\nelevation = 30\n[cloud]\n" \
                  "[ellipsoid]\ncenter = 0 0 0\nradii = 1 2 3\n"

static int parse(const char *text, cu_scene **s, cu_error *e)
{
    return cu_scene_parse(s, "t.scene", text, strlen(text), e);
}

static void test_good_minimal_and_defaults(void **st)
{
    (void)st;
    cu_scene *s;
    cu_error e;
    assert_int_equal(parse(MIN_SCENE, &s, &e), 0);
    assert_int_equal(s->n_ellipsoids, 1);
    assert_true(s->ell[0].radii[2] == 3.0);
    assert_int_equal(s->width, 640);
    assert_int_equal(s->segments, 5);
    assert_true(s->density_cm3 == 400.0 && s->droplet_radius_um == 6.0);
    /* k_e = 400e6 m^-3 * 2 pi (6e-6 m)^2 = 0.0905 m^-1 (DESIGN.md) */
    assert_true(fabs(cu_scene_core_extinction(s) - 0.0904779) < 1e-6);
    cu_scene_free(s);
}

static void test_good_default_scene_file(void **st)
{
    (void)st;
    cu_scene *s;
    cu_error e;
    int rc = cu_scene_load(&s, "scenes/cumulus.scene", &e);
    if (rc)
        fail_msg("%s", e.msg);
    assert_int_equal(s->n_ellipsoids, 8);
    assert_true(s->cam_pos[2] == -1200.0 && s->sun_azimuth == 135.0 && s->boundary_m == 62.0);
    assert_int_equal(s->phase, CU_PHASE_MIE);
    cu_scene_free(s);
}

static void test_comments_crlf_and_set(void **st)
{
    (void)st;
    const char *t = "# comment\r\n[camera]   ; trailing\r\nposition = 1, 2, 3 # commas allowed\r\nlook_at=0 0 0\r\n"
                    "[sun]\r\nelevation = -5\r\nazimuth = 270\r\n[cloud]\r\nphase = hg\r\ng = 0.5\r\n"
                    "[ellipsoid]\r\ncenter = 0 0 0\r\nradii = 1 1 1\r\n[ellipsoid]\r\ncenter = 5 0 0\r\nradii = 2 2 2\r\n";
    cu_scene *s;
    cu_error e;
    assert_int_equal(parse(t, &s, &e), 0);
    assert_true(s->cam_pos[1] == 2.0 && s->sun_elevation == -5.0 && s->phase == CU_PHASE_HG);
    assert_int_equal(cu_scene_set(s, "quality.segments=12", &e), 0);
    assert_int_equal(s->segments, 12);
    assert_int_equal(cu_scene_set(s, "ellipsoid.2.radii=3 4 5", &e), 0);
    assert_true(s->ell[1].radii[1] == 4.0);
    assert_int_equal(cu_scene_set(s, "ms.mode=octaves", &e), 0);
    assert_int_equal(s->ms_mode, CU_MS_OCTAVES);
    assert_int_equal(cu_scene_set(s, "sun.irradiance=1 2 3", &e), 0);
    assert_int_equal(s->has_sun_irradiance, 1);
    cu_scene_free(s);
}

/* Many clouds: each later [cloud] starts a cloud of the [ellipsoid] sections after it; what it does not give is the
 * first [cloud]'s; a clear sky and a scene of layers alone are valid. */
static void test_many_clouds(void **st)
{
    (void)st;
    const char *text = "[camera]\nposition = 0 0 -3000\nlook_at = 0 0 0\n[sun]\n"
                       "[ellipsoid]\ncenter = 0 0 0\nradii = 10 10 10\n"        /* before any [cloud]: cloud 1's */
                       "[cloud]\ndensity = 300\nwind = 4 -2\nlifetime = 600\n"
                       "[ellipsoid]\ncenter = 20 0 0\nradii = 10 10 10\n"
                       "[cloud]\nboundary = 5\nnoise_offset = 1 2 3\n"
                       "[ellipsoid]\ncenter = 500 0 0\nradii = 10 10 10\n[ellipsoid]\ncenter = 520 0 0\nradii = 9 9 9\n"
                       "[cloud]\ndensity = 50\nwind = 0 0\n[ellipsoid]\ncenter = -500 0 0\nradii = 10 10 10\n";
    cu_scene *s;
    cu_error e;
    assert_int_equal(parse(text, &s, &e), 0);
    assert_int_equal(s->n_clouds, 3);
    assert_int_equal(s->n_ellipsoids, 5);
    cu_cloud_spec a = cu_scene_cloud(s, 0), b = cu_scene_cloud(s, 1), c = cu_scene_cloud(s, 2);
    assert_int_equal(a.first, 0);
    assert_int_equal(a.count, 2);
    assert_int_equal(b.first, 2);
    assert_int_equal(b.count, 2);
    assert_int_equal(c.first, 4);
    assert_int_equal(c.count, 1);
    assert_true(a.density_cm3 == 300 && b.density_cm3 == 300 && c.density_cm3 == 50);
    assert_true(a.boundary_m == 62 && b.boundary_m == 5 && c.boundary_m == 62);
    assert_true(a.wind[0] == 4 && a.wind[1] == -2 && b.wind[0] == 4 && c.wind[0] == 0 && c.wind[1] == 0);
    assert_true(a.lifetime == 600 && b.lifetime == 600);
    assert_true(b.noise_offset[0] == 1 && b.noise_offset[2] == 3);
    assert_true(a.noise_offset[0] == 0 && c.noise_offset[0] != a.noise_offset[0]); /* each its own look */
    /* --set on the first [cloud] changes every cloud that does not say otherwise */
    assert_int_equal(cu_scene_set(s, "cloud.density=100", &e), 0);
    assert_true(cu_scene_cloud(s, 1).density_cm3 == 100 && cu_scene_cloud(s, 2).density_cm3 == 50);
    cu_scene_free(s);

    /* a clear sky */
    assert_int_equal(parse("[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[cloud]\n", &s, &e), 0);
    assert_int_equal(s->n_clouds, 0);
    assert_int_equal(s->n_layers, 0);
    cu_scene_free(s);
    /* layers, and --set layer.N.key */
    assert_int_equal(parse("[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[layer]\ncoverage = 0.2\n"
                           "[layer]\ntype = cumulus-congestus\nbase = 2000\nwind = 3 4\nseed = 9\n",
                           &s, &e), 0);
    assert_int_equal(s->n_clouds, 0);
    assert_int_equal(s->n_layers, 2);
    assert_true(s->layers[0].coverage == 0.2 && s->layers[0].base == 1000 && s->layers[1].base == 2000);
    assert_int_equal(s->layers[1].type, 2);
    assert_int_equal(s->layers[1].seed, 9);
    assert_true(s->layers[1].wind[1] == 4);
    assert_int_equal(cu_scene_set(s, "layer.2.coverage=0.5", &e), 0);
    assert_true(s->layers[1].coverage == 0.5);
    assert_int_not_equal(cu_scene_set(s, "layer.3.coverage=0.5", &e), 0);
    assert_string_equal(e.msg, "--set layer.3.coverage=0.5: use layer.N.key with N from 1 to 2");
    assert_int_not_equal(cu_scene_set(s, "layer.1.coverage=2", &e), 0);
    assert_true(s->layers[0].coverage == 0.2); /* all or nothing */
    cu_scene_free(s);
}

typedef struct bad_case {
    const char *text;
    const char *message;
} bad_case;

/* Every entry: a hostile input and the exact message the user must see. */
static const bad_case bad[] = {
    {"", "t.scene:1:1: empty scene file"},
    {"# only a comment\n\n", "t.scene:1:1: empty scene file"},
    /* many clouds: each later [cloud] starts one, needs its own ellipsoids, and may not change what every cloud
     * shares */
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\ncenter = 0 0 0\nradii = 1 1 1\n[cloud]\n[cloud]\n[ellipsoid]\ncenter = 5 0 0\nradii = 1 1 1\n",
     "t.scene:9:1: [cloud] #2 has no [ellipsoid]"},
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\ncenter = 0 0 0\nradii = 1 1 1\n[cloud]\nphase = hg\n",
     "t.scene:10:1: 'phase' is shared by every cloud: set it in the first [cloud] section"},
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\ncenter = 0 0 0\nradii = 1 1 1\n[cloud]\nwind = 1 2 3\n",
     "t.scene:10:8: 'wind' needs 2 numbers, got more"},
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\ncenter = 0 0 0\nradii = 1 1 1\n[cloud]\ndensity = -1\n",
     "t.scene:10:11: 'density' must be in [0, 1e+07] cm^-3, got -1"},
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[layer]\ncoverage = 1.5\n", "t.scene:6:12: 'coverage' must be in [0, 1], got 1.5"},
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[layer]\ntype = stratus\n",
     "t.scene:6:8: 'type' must be one of cumulus-humilis | cumulus-mediocris | cumulus-congestus, got 'stratus'"},
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[scene]\ntime = nan\n", "t.scene:6:8: 'time' is NaN"},
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[cloud]\n[ellipsoid]\ncenter=0 0 0\nradii=1 1 1\n", "t.scene: missing section [sun]"},
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\ncenter = 0 0 0\nradii = 200 120\n",
     "t.scene:8:9: 'radii' needs 3 numbers, got 2"},
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\ncenter = 0 0 0\nradii = 1 -2 3\n",
     "t.scene:8:9: 'radii' must be in [0.1, 100000] m, got -2"},
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\ncenter = 0 0 0\nradii = 1 0 3\n",
     "t.scene:8:9: 'radii' must be in [0.1, 100000] m, got 0"},
    {"[camera]\nposition = nan 0 0\n", "t.scene:2:12: 'position' is NaN"},
    {"[camera]\nfov = inf\n", "t.scene:2:7: 'fov' is out of range (inf)"},
    {"[camera]\nfov = 1e400\n", "t.scene:2:7: 'fov' is out of range (1e400)"},
    {"[cloud]\ndensity = 1e300\n", "t.scene:2:11: 'density' must be in [0, 1e+07] cm^-3, got 1e+300"},
    {"[camera]\nfov = 50\nfov = 60\n", "t.scene:3:1: duplicate key 'fov' in [camera]"},
    {"[camera]\nzoom = 2\n", "t.scene:2:1: unknown key 'zoom' in [camera]"},
    {"[weather]\n", "t.scene:1:1: unknown section [weather]"},
    {"[camera\n", "t.scene:1:1: unterminated section header (missing ']')"},
    {"fov = 50\n", "t.scene:1:1: key outside any section"},
    {"[camera]\nfov 50\n", "t.scene:2:1: expected 'key = value' or '[section]'"},
    {"[camera]\nfov =\n", "t.scene:2:6: 'fov' has no value"},
    {"[camera]\nfov = 5O\n", "t.scene:2:7: 'fov' expects a number, got '5O'"},
    {"[cloud]\nphase = rayleigh\n", "t.scene:2:9: 'phase' must be one of cornette-shanks | hg | mie, got 'rayleigh'"},
    {"[quality]\nsegments = 2.5\n", "t.scene:2:12: 'segments' must be a whole number, got 2.5"},
    {"[quality]\nsegments = 0\n", "t.scene:2:12: 'segments' must be in [1, 64], got 0"},
    {"[camera]\nposition = 1 2 3 4\n", "t.scene:2:12: 'position' needs 3 numbers, got more"},
    {"[camera]\n\x01\x02garbage\n", "t.scene:2:1: not a text file (byte 0x01)"},
    {"[camera]\nposition = 0 0 0\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\ncenter = 0 0 0\nradii = 1 1 1\n",
     "t.scene: [camera] 'look_at' equals 'position'; the view direction is undefined"},
    {"[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\nradii = 1 1 1\n",
     "t.scene:6:1: [ellipsoid] #1 has no 'center'"},
    {"[camera]\n[camera]\n", "t.scene:2:1: section [camera] appears twice"},
    {"[sun]\nelevation = 91\n", "t.scene:2:13: 'elevation' must be in [-90, 90] degrees, got 91"},
    /* values shown with the digits that make them fail (%g printed "got 179" and "got 5") */
    {"[camera]\nfov = 179.0001\n", "t.scene:2:7: 'fov' must be in [0.1, 179] degrees, got 179.0001"},
    {"[quality]\nsegments = 5.0000001\n", "t.scene:2:12: 'segments' must be a whole number, got 5.0000001"},
    {"[output]\nexposure = 0\n", "t.scene:2:12: 'exposure' must be positive, got 0"},
    {"[cloud]\nnoise_scale = 1e-400\n", "t.scene:2:15: 'noise_scale' must be positive, got 0"},
    /* whole-scene ranges (scene_keys.h): the scene's size against its smallest radius, noise against size */
    {"[camera]\nposition = 0 0 -20000\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\ncenter = 0 0 0\n"
     "radii = 0.1 1 1\n",
     "t.scene: the scene is too large for its smallest radius, 0.1 m: the camera is 20000 m from the cloud's centre, "
     "the cloud's radius is 1 m; the distance and 4x the radius must each be at most 100000 smallest radii "
     "(single-precision positions)"},
    {"[camera]\nposition = 0 0 -2000\nlook_at = 0 0 0\n[sun]\n[cloud]\nnoise_scale = 10000\n[ellipsoid]\n"
     "center = 0 0 0\nradii = 300 300 300\n",
     "t.scene: [cloud] 'noise_scale' 10000 is too fine for a cloud of radius 300 m: radius x noise_scale must be at "
     "most 2.05e+06 m for single precision noise coordinates (or quality.noise = off)"},
};

static void test_bad_inputs(void **st)
{
    (void)st;
    int n = (int)(sizeof bad / sizeof bad[0]);
    assert_true(n >= 15);
    for (int i = 0; i < n; i++) {
        cu_scene *s = (cu_scene *)1;
        cu_error e;
        memset(&e, 0, sizeof e);
        int rc = parse(bad[i].text, &s, &e);
        if (rc == 0 || s != NULL || strcmp(e.msg, bad[i].message) != 0)
            fail_msg("case %d: rc=%d\n  got:      '%s'\n  expected: '%s'", i, rc, e.msg, bad[i].message);
    }
}

static void test_nul_byte_and_truncated_binary(void **st)
{
    (void)st;
    const char t[] = "[camera]\nfov = 5\0\xff\xfe";
    cu_scene *s;
    cu_error e;
    assert_int_not_equal(cu_scene_parse(&s, "t.scene", t, sizeof t - 1, &e), 0);
    assert_string_equal(e.msg, "t.scene:2:8: not a text file (byte 0x00)");
    /* a file cut in the middle of a value */
    const char *u = MIN_SCENE "[quality]\nsegments = 1";
    assert_int_not_equal(cu_scene_parse(&s, "t.scene", u, strlen(u) - 1, &e), 0);
    assert_string_equal(e.msg, "t.scene:11:11: 'segments' has no value");
}

static void test_bad_set(void **st)
{
    (void)st;
    cu_scene *s;
    cu_error e;
    assert_int_equal(parse(MIN_SCENE, &s, &e), 0);
    assert_int_not_equal(cu_scene_set(s, "quality.segments", &e), 0);
    assert_string_equal(e.msg, "--set quality.segments: expected section.key=value");
    assert_int_not_equal(cu_scene_set(s, "quality.bogus=1", &e), 0);
    assert_string_equal(e.msg, "--set quality.bogus=1: unknown key 'quality.bogus'");
    assert_int_not_equal(cu_scene_set(s, "ellipsoid.2.radii=1 1 1", &e), 0);
    assert_string_equal(e.msg, "--set ellipsoid.2.radii=1 1 1: use ellipsoid.N.key with N from 1 to 1");
    assert_int_not_equal(cu_scene_set(s, "camera.fov=nan", &e), 0);
    assert_string_equal(e.msg, "--set camera.fov: 'fov' is NaN");
    assert_int_not_equal(cu_scene_set(s, "ellipsoid.1.radii=1 1 -1", &e), 0);
    assert_string_equal(e.msg, "--set ellipsoid.radii: 'radii' must be in [0.1, 100000] m, got -1");
    /* a failed --set leaves the value unchanged */
    assert_true(s->ell[0].radii[2] == 3.0);
    cu_scene_free(s);
}

/* The knob fields a preset may set, for comparing scenes. */
static void knobs(const cu_scene *s, double v[12])
{
    double k[12] = {s->segments, s->segment_ratio, s->hull_tessellation, s->max_intervals, s->noise_octaves,
                    s->sun_map_size, s->shadow, s->sun_intervals, s->sun_samples, s->ms_mode, s->ms_blur_m,
                    s->integration};
    memcpy(v, k, sizeof k);
}

static void test_presets(void **st)
{
    (void)st;
    cu_scene *s, *d;
    cu_error e;
    double a[12], b[12];
    assert_int_equal(parse(MIN_SCENE, &d, &e), 0);
    /* high is the defaults */
    assert_int_equal(parse(MIN_SCENE "[quality]\npreset = high\n", &s, &e), 0);
    knobs(s, a);
    knobs(d, b);
    assert_memory_equal(a, b, sizeof a);
    cu_scene_free(s);
    /* medium and low change something (they come from the sweep: src/presets.c) */
    for (int p = 0; p < 2; p++) {
        assert_int_equal(parse(p ? MIN_SCENE "[quality]\npreset = low\n" : MIN_SCENE "[quality]\npreset = medium\n",
                               &s, &e), 0);
        knobs(s, a);
        assert_true(memcmp(a, b, sizeof a) != 0);
        /* a later --set of the preset replaces it completely: back to high is back to the defaults */
        assert_int_equal(cu_scene_set(s, "quality.preset=high", &e), 0);
        knobs(s, a);
        assert_memory_equal(a, b, sizeof a);
        cu_scene_free(s);
    }
    /* keys given in the file win, before or after the preset line, and so do earlier --set values */
    assert_int_equal(parse(MIN_SCENE "[quality]\nsegments = 7\npreset = low\n", &s, &e), 0);
    assert_int_equal(s->segments, 7);
    cu_scene_free(s);
    assert_int_equal(parse(MIN_SCENE "[quality]\npreset = low\nsegments = 7\n", &s, &e), 0);
    assert_int_equal(s->segments, 7);
    assert_int_equal(cu_scene_set(s, "light.shadow=fom", &e), 0);
    assert_int_equal(cu_scene_set(s, "quality.preset=medium", &e), 0);
    assert_int_equal(s->segments, 7);
    assert_int_equal(s->shadow, CU_SHADOW_FOM);
    cu_scene_free(s);
    /* a bad name is an error with its place */
    assert_int_not_equal(parse(MIN_SCENE "[quality]\npreset = ultra\n", &s, &e), 0);
    assert_non_null(strstr(e.msg, "t.scene:11:10"));
    cu_scene_free(d);
}

static void test_missing_file(void **st)
{
    (void)st;
    cu_scene *s;
    cu_error e;
    assert_int_not_equal(cu_scene_load(&s, "no/such.scene", &e), 0);
    assert_string_equal(e.msg, "no/such.scene: cannot open: No such file or directory");
}

/* Every whole-scene check of the file runs on --set too, and a --set it rejects leaves the scene as it was. */
static void test_set_cross_field(void **st)
{
    (void)st;
    cu_scene *s, *before;
    cu_error e;
    assert_int_equal(parse(MIN_SCENE, &s, &e), 0);
    assert_int_equal(parse(MIN_SCENE, &before, &e), 0);
    assert_int_not_equal(cu_scene_set(s, "camera.look_at=0 0 -10", &e), 0);
    assert_string_equal(e.msg, "--set camera.look_at: [camera] 'look_at' equals 'position'; the view direction is "
                               "undefined");
    assert_int_not_equal(cu_scene_set(s, "camera.position=0 0 0", &e), 0);
    assert_string_equal(e.msg, "--set camera.position: [camera] 'look_at' equals 'position'; the view direction is "
                               "undefined");
    assert_int_not_equal(cu_scene_set(s, "light.sun_samples=6", &e), 0);
    assert_string_equal(e.msg, "--set light.sun_samples: [light] 'sun_samples' must be a multiple of 4, got 6");
    assert_int_not_equal(cu_scene_set(s, "light.osm_slices=9", &e), 0);
    assert_memory_equal(s, before, sizeof *s);
    /* presets break no check, and moving one end of the view at a time is fine while they differ */
    assert_int_equal(cu_scene_set(s, "quality.preset=low", &e), 0);
    assert_int_equal(cu_scene_set(s, "camera.look_at=0 0 -20", &e), 0);
    assert_int_equal(cu_scene_set(s, "camera.position=0 0 -20.5", &e), 0);
    cu_scene_free(s);
    cu_scene_free(before);
}

/* A UTF-8 byte-order mark is skipped; control bytes given to --set come back escaped, never raw. */
static void test_bom_and_control_bytes(void **st)
{
    (void)st;
    cu_scene *s;
    cu_error e;
    assert_int_equal(parse("\xef\xbb\xbf" MIN_SCENE, &s, &e), 0);
    assert_true(s->ell[0].radii[2] == 3.0);
    /* only at the very start: elsewhere it is a syntax error like any other text */
    cu_scene *t = NULL;
    assert_int_not_equal(parse(MIN_SCENE "\xef\xbb\xbf[sky]\n", &t, &e), 0);
    assert_null(t);
    assert_int_not_equal(cu_scene_set(s, "quality.\x1b[31mx=1", &e), 0);
    assert_null(strchr(e.msg, '\x1b'));
    assert_non_null(strstr(e.msg, "\\x1b[31mx"));
    assert_int_not_equal(cu_scene_set(s, "cloud.phase=\x1b]0;pwned\x07", &e), 0);
    assert_null(strchr(e.msg, '\x1b'));
    assert_null(strchr(e.msg, '\x07'));
    assert_non_null(strstr(e.msg, "\\x1b]0;pwned\\x07"));
    cu_scene_free(s);
}

/* The place a host's clock shows the sun at (cumulo run --clock): the scene's or --set's, or 0 0 and "not given". */
static void test_sun_place(void **st)
{
    (void)st;
    cu_scene *s;
    cu_error e;
    double lat = 1, lon = 1;
    assert_int_equal(parse(MIN_SCENE, &s, &e), 0);
    assert_int_equal(cu_scene_sun_place(s, &lat, &lon), 0);
    assert_true(lat == 0.0 && lon == 0.0);
    assert_int_equal(cu_scene_set(s, "sun.longitude=-3.5", &e), 0);
    assert_int_equal(cu_scene_sun_place(s, &lat, &lon), 1);
    assert_true(lat == 0.0 && lon == -3.5);
    cu_scene_free(s);
    assert_int_equal(parse("[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\nlatitude = 0\n[cloud]\n"
                           "[ellipsoid]\ncenter = 0 0 0\nradii = 1 2 3\n", &s, &e), 0);
    assert_int_equal(cu_scene_sun_place(s, &lat, &lon), 1); /* 0 N given is a place, not a default */
    cu_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_good_minimal_and_defaults), cmocka_unit_test(test_good_default_scene_file),
        cmocka_unit_test(test_comments_crlf_and_set),    cmocka_unit_test(test_bad_inputs), cmocka_unit_test(test_many_clouds),
        cmocka_unit_test(test_nul_byte_and_truncated_binary), cmocka_unit_test(test_bad_set),
        cmocka_unit_test(test_missing_file),          cmocka_unit_test(test_presets),
        cmocka_unit_test(test_set_cross_field),       cmocka_unit_test(test_bom_and_control_bytes),
        cmocka_unit_test(test_sun_place),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
