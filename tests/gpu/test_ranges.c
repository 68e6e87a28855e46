/* tests/gpu/test_ranges.c: the extremes matrix of issue 18. Every numeric scene key, read from the key table, at its
 * bound and just inside it, with every other key at its largest or smallest legal value, renders an image with no
 * NaN or Inf pixel through the GPU renderer and the path tracer; just outside the bound it is rejected with a message
 * that shows the value. CUMULO_STRESS=1 (make stress): each key's bound combined with every other key's bound. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pt.h"
#include "render_util.h"
#include "scene.h"
#include "scene_keys.h"

#define OUT_DIR "build/test-output/ranges"
static int W = 32, H = 24;
static tr_ctx ctx;
static int stress, renders, rejected;

/* Every numeric key: the scene's, then the ellipsoid's (which the matrix gives to its first ellipsoid). */
static const cu_scene_key *keys[CU_SCENE_KEY_COUNT + CU_ELLIPSOID_KEY_COUNT];
static int nkeys;

static int numeric(const cu_scene_key *k)
{
    return k->type == CU_KEY_NUMBER || k->type == CU_KEY_INTEGER;
}

static int is(const cu_scene_key *k, const char *section, const char *name)
{
    return strcmp(k->section, section) == 0 && strcmp(k->name, name) == 0;
}

/* The smallest step an integer key can take (its multiple, else 1); 0 for real numbers. */
static double int_step(const cu_scene_key *k)
{
    return k->type == CU_KEY_INTEGER ? (k->multiple ? k->multiple : 1) : 0;
}

/* The legal bound (an open lo: the smallest double above it) and the value just inside or just outside it. */
static double bound(const cu_scene_key *k, int hi)
{
    return hi ? k->hi : k->lo_open ? nextafter(k->lo, INFINITY) : k->lo;
}

static double inside(const cu_scene_key *k, int hi)
{
    double b = bound(k, hi), s = int_step(k);
    return s ? b + (hi ? -s : s) : nextafter(b, hi ? -INFINITY : INFINITY);
}

static double outside(const cu_scene_key *k, int hi)
{
    double s = int_step(k);
    if (hi)
        return s ? k->hi + s : nextafter(k->hi, INFINITY);
    return k->lo_open ? k->lo : s ? k->lo - s : nextafter(k->lo, -INFINITY);
}

/* The value of every key in one case: a profile of the others (0: smallest, 1: largest), overridden for some. */
typedef struct ranges_case {
    double v[CU_SCENE_KEY_COUNT + CU_ELLIPSOID_KEY_COUNT];
    char label[160];
} ranges_case;

static int find(const char *section, const char *name)
{
    for (int i = 0; i < nkeys; i++)
        if (is(keys[i], section, name))
            return i;
    return -1;
}

/* The profile: every key at its bound, except where the bounds together make no picture. The camera sits at the
 * first ellipsoid's centre (the bounds of position and center are equal) and looks toward the opposite corner;
 * the noise scale is the largest the cloud's size allows (the whole-scene check, CU_MAX_NOISE_EXTENT). */
static void profile(ranges_case *c, int hi)
{
    for (int i = 0; i < nkeys; i++)
        c->v[i] = bound(keys[i], hi);
    c->v[find("camera", "look_at")] = bound(keys[find("camera", "look_at")], !hi);
    double r = c->v[find("ellipsoid", "radii")], *ns = &c->v[find("cloud", "noise_scale")];
    *ns = fmin(*ns, CU_MAX_NOISE_EXTENT / (2.0 * r)); /* R of the two ellipsoids below is < 2 r */
    /* The sun maps' size only sets how many texels run the same maths (their size, 2 R / n, enters no formula that
     * could overflow), and 4096^2 of them take minutes on a software renderer: the profiles keep the smallest, and
     * the key's own cases render its largest. */
    c->v[find("quality", "sun_map_size")] = bound(keys[find("quality", "sun_map_size")], 0);
}

static void put(char **p, const char *end, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(*p, (size_t)(end - *p), fmt, ap);
    va_end(ap);
    *p += n > 0 && n < end - *p ? n : 0;
}

/* The enum settings under which key k does something (light.osm_slices only counts with shadow = osm, ...). */
static const char *mode_for(const cu_scene_key *k)
{
    static const char *const map[][3] = {
        {"light", "osm_slices", "shadow = osm"},       {"light", "fom_coefficients", "shadow = fom"},
        {"ms", "octaves", "mode = octaves"},           {"ms", "a", "mode = octaves"},
        {"ms", "b", "mode = octaves"},                 {"ms", "c", "mode = octaves"},
        {"ms", "iterations", "mode = collector"},      {"cloud", "g", "phase = hg"},
        {"sky", "color", "model = constant"},
    };
    for (size_t i = 0; i < sizeof map / sizeof map[0]; i++)
        if (is(k, map[i][0], map[i][1]))
            return map[i][2];
    return NULL;
}

/* The scene file of case c, key `focus` (or -1) deciding the enum modes; `extra` is "section\nline" or NULL. Two
 * ellipsoids: the first at the keys' centre and radii, the second half its size toward the origin, overlapping. */
static void write_scene(const ranges_case *c, int focus, const char *extra, char *buf, size_t size)
{
    char *p = buf, *end = buf + size;
    const char *mode = focus >= 0 ? mode_for(keys[focus]) : NULL;
    for (int s = 0; s < CU_SCENE_SECTION_COUNT; s++) {
        const cu_scene_section *sec = &cu_scene_sections[s];
        if (sec->repeated)
            continue;
        put(&p, end, "[%s]\n", sec->name);
        for (int i = 0; i < nkeys; i++)
            if (strcmp(keys[i]->section, sec->name) == 0) {
                put(&p, end, "%s =", keys[i]->name);
                for (int j = 0; j < keys[i]->count; j++)
                    put(&p, end, " %.17g", c->v[i]);
                put(&p, end, "\n");
            }
        if (mode && strcmp(keys[focus]->section, sec->name) == 0)
            put(&p, end, "%s\n", mode);
        size_t ln = extra ? strcspn(extra, "\n") : 0;
        if (extra && strncmp(extra, sec->name, ln) == 0 && sec->name[ln] == 0)
            put(&p, end, "%s\n", extra + ln + 1);
    }
    double cc = c->v[find("ellipsoid", "center")], r = c->v[find("ellipsoid", "radii")];
    double c2 = cc - 0.5 * r * (cc > 0 ? 1 : -1), r2 = fmax(0.5 * r, keys[find("ellipsoid", "radii")]->lo);
    put(&p, end, "[ellipsoid]\ncenter = %.17g %.17g %.17g\nradii = %.17g %.17g %.17g\n", cc, cc, cc, r, r, r);
    put(&p, end, "[ellipsoid]\ncenter = %.17g %.17g %.17g\nradii = %.17g %.17g %.17g\n", c2, cc, c2, r2, r2, r);
}

/* Every value of both renderers finite; the GPU's also non-negative. */
static void check_finite(const float *px, long n, const char *who, const char *label, const char *text)
{
    for (long i = 0; i < n; i++)
        if (!isfinite(px[i]) || px[i] < 0.0f) {
            fprintf(stderr, "scene:\n%s", text);
            fail_msg("%s: %s: pixel %ld channel %ld = %g", who, label, i / 3, i % 3, px[i]);
        }
}

static pt_ctx pt; /* one path tracer, its noise built once */
static int pt_ready;

static int pt_reads(const cu_scene_key *k)
{
    return strcmp(k->section, "output") != 0 && strcmp(k->section, "light") != 0 && strcmp(k->section, "ms") != 0 &&
           (strcmp(k->section, "quality") != 0 || is(k, "quality", "noise_octaves"));
}

/* Parses the scene of case c; a legal combination must render finite through both renderers. Returns 1 if it
 * rendered, 0 if the whole-scene check rejected the combination (the caller decides whether that may be). */
static int run_case(const ranges_case *c, int focus, const char *extra)
{
    char text[8192];
    write_scene(c, focus, extra, text, sizeof text);
    cu_scene *s;
    cu_error e;
    if (cu_scene_parse(&s, "matrix.scene", text, strlen(text), &e)) {
        /* values inside every key's range: only a rule that ties keys together may object */
        if (strstr(e.msg, "' must be")) {
            fprintf(stderr, "scene:\n%s", text);
            fail_msg("%s: a legal value rejected: %s", c->label, e.msg);
        }
        rejected++;
        return 0;
    }
    renders++;
    /* the case being rendered, for a look when it fails or hangs */
    FILE *f = fopen(OUT_DIR "/last.scene", "w");
    if (f) {
        fprintf(f, "# %s\n%s", c->label, text);
        fclose(f);
    }
    if (tr_render_scene(&ctx, s))
        fail_msg("%s: %s", c->label, ctx.err);
    float *px = malloc(sizeof(float) * 3 * (size_t)W * H);
    tr_read_rgbf(&ctx, px);
    check_finite(px, (long)W * H * 3, "gpu", c->label, text);
    /* The path tracer at 3x2 pixels, 1 sample, few steps: its maths at the same extremes, cut paths included. It
     * reads no [quality] (but the noise), [light] or [ms] key: the GPU's approximations. */
    if (focus < 0 || pt_reads(keys[focus])) {
        float pm[3 * 6];
        pt_render_opts o = {3, 2, 1, 1, 7, 0, PT_MODE_RADIANCE, 0};
        s->width = 3;
        s->height = 2;
        if (pt_ready ? pt_ctx_set_scene(&pt, s, getenv("CUMULO_DATA_DIR"), &e)
                     : pt_ctx_init(&pt, s, getenv("CUMULO_DATA_DIR"), &e))
            fail_msg("%s: path tracer: %s", c->label, e.msg);
        pt_ready = 1;
        pt.max_steps = 2000;
        pt_counters k;
        if (pt_render(&pt, &o, pm, NULL, &k, &e))
            fail_msg("%s: path tracer: %s", c->label, e.msg);
        check_finite(pm, 3 * 6, "path tracer", c->label, text);
    }
    free(px);
    cu_scene_free(s);
    return 1;
}

static int setup(void **st)
{
    (void)st;
    stress = getenv("CUMULO_STRESS") != NULL;
    if (system("mkdir -p " OUT_DIR) != 0)
        return 1;
    for (int i = 0; i < CU_SCENE_KEY_COUNT; i++)
        if (numeric(&cu_scene_keys[i]))
            keys[nkeys++] = &cu_scene_keys[i];
    for (int i = 0; i < CU_ELLIPSOID_KEY_COUNT; i++)
        keys[nkeys++] = &cu_ellipsoid_keys[i];
    if (tr_open(&ctx, &cu_display_egl, W, H, 1)) {
        fprintf(stderr, "%s\n", ctx.err);
        return 1;
    }
    return 0;
}

static int teardown(void **st)
{
    (void)st;
    tr_close(&ctx);
    if (pt_ready)
        pt_ctx_free(&pt);
    return 0;
}

/* Each key at each bound (make stress: and just inside it), the others at the opposite extreme (its smallest value
 * with the others at their largest, and the reverse); where the whole-scene check rejects that pairing, with the
 * others at the same extreme. Either way the value must render in one of them. CUMULO_RANGES_KEY=name: that key
 * only (for a look at one). */
static void test_each_bound(void **st)
{
    (void)st;
    const char *only = getenv("CUMULO_RANGES_KEY");
    for (int i = 0; i < nkeys; i++)
        for (int hi = 0; hi < 2 && (!only || strcmp(only, keys[i]->name) == 0); hi++)
            for (int in = 0; in < (stress ? 2 : 1); in++) {
                ranges_case c;
                double v = in ? inside(keys[i], hi) : bound(keys[i], hi);
                int done = 0;
                for (int pr = 0; pr < 2 && !done; pr++) {
                    profile(&c, pr ? hi : !hi);
                    c.v[i] = v;
                    snprintf(c.label, sizeof c.label, "[%s] %s = %.17g (%s), the others at their %s", keys[i]->section,
                             keys[i]->name, v, in ? "just inside" : "the bound", (pr ? hi : !hi) ? "largest" : "smallest");
                    done = run_case(&c, i, NULL);
                }
                if (!done)
                    fail_msg("[%s] %s = %.17g renders in no profile", keys[i]->section, keys[i]->name, v);
            }
    printf("%d keys: %d renders, %d combinations rejected by the whole-scene check\n", nkeys, renders, rejected);
}

/* Just outside: rejected, the message naming the key and showing the value with the digits that make it fail. */
static void test_just_outside(void **st)
{
    (void)st;
    for (int i = 0; i < nkeys; i++)
        for (int hi = 0; hi < 2; hi++) {
            ranges_case c;
            profile(&c, !hi);
            double v = outside(keys[i], hi);
            c.v[i] = v;
            char text[8192], want[64], num[32];
            write_scene(&c, i, NULL, text, sizeof text);
            cu_scene *s;
            cu_error e;
            if (cu_scene_parse(&s, "matrix.scene", text, strlen(text), &e) == 0)
                fail_msg("[%s] %s = %.17g was accepted", keys[i]->section, keys[i]->name, v);
            snprintf(want, sizeof want, "'%s' must be", keys[i]->name);
            const char *got = strstr(e.msg, want) ? strstr(e.msg, "got ") : NULL;
            if (!got && !strstr(e.msg, want))
                fail_msg("[%s] %s = %.17g: message '%s' lacks \"%s\"", keys[i]->section, keys[i]->name, v, e.msg, want);
            if (int_step(keys[i]) && strstr(e.msg, "multiple of"))
                continue; /* lo - multiple of a multiple-of key: the rule names the key */
            if (!got || strtod(got + 4, NULL) != v)
                fail_msg("[%s] %s: '%s' does not show %s", keys[i]->section, keys[i]->name, e.msg,
                         cu_number_text(v, num));
        }
}

/* The findings that started the matrix, each with the rest of the scene as found: radii 1e6 with the camera inside
 * (now out of range), 1e5 (the bound), 1e-20 (out of range), and every key at its largest value at once, which is
 * only legal with the camera off the look-at point and the noise scale the cloud's size allows. */
static void test_findings(void **st)
{
    (void)st;
    ranges_case c;
    profile(&c, 1);
    snprintf(c.label, sizeof c.label, "every key at its largest legal value");
    assert_int_equal(run_case(&c, -1, NULL), 1);
    profile(&c, 1);
    c.v[find("cloud", "noise_scale")] = keys[find("cloud", "noise_scale")]->hi;
    snprintf(c.label, sizeof c.label, "every key at its largest, noise scale too");
    assert_int_equal(run_case(&c, -1, NULL), 0); /* the noise/size rule says why */
    c.v[find("cloud", "noise_scale")] = keys[find("cloud", "noise_scale")]->hi;
    assert_int_equal(run_case(&c, -1, "quality\nnoise = off"), 1);
    /* The camera inside a cloud that spans the legal space: the far plane 2e6 m out, the near one 5 cm, past what
     * an fp32 unprojection of the far plane holds (renderer.c, frame_camera). */
    static const char corners[] = "[camera]\nposition = -5e5 -5e5 -5e5\nlook_at = 0 0 0\n[sun]\nelevation = 30\n"
                                  "[cloud]\n[ellipsoid]\ncenter = -5e5 -5e5 -5e5\nradii = 1e5 1e5 1e5\n"
                                  "[ellipsoid]\ncenter = 5e5 5e5 5e5\nradii = 1e5 1e5 1e5\n";
    if (tr_render(&ctx, corners, NULL))
        fail_msg("opposite corners: %s", ctx.err);
    float *px = malloc(sizeof(float) * 3 * (size_t)W * H);
    tr_read_rgbf(&ctx, px);
    check_finite(px, (long)W * H * 3, "gpu", "camera inside a cloud across the legal space", corners);
    static const char base[] = "[camera]\nposition = 0 250 0\nlook_at = 0 250 100\n[sun]\nelevation = 30\n"
                               "[cloud]\n[ellipsoid]\ncenter = 0 250 0\nradii = %s\n";
    const char *radii[] = {"1e6 1e6 1e6", "1e-20 1e-20 1e-20", "1e5 1e5 1e5", "0.1 0.1 0.1"};
    for (int i = 0; i < 4; i++) {
        char text[512];
        snprintf(text, sizeof text, base, radii[i]);
        if (i < 2) {
            assert_int_not_equal(tr_render(&ctx, text, NULL), 0);
            assert_non_null(strstr(ctx.err, "'radii' must be in [0.1, 100000] m"));
            continue;
        }
        if (tr_render(&ctx, text, NULL))
            fail_msg("radii %s: %s", radii[i], ctx.err);
        tr_read_rgbf(&ctx, px);
        check_finite(px, (long)W * H * 3, "gpu", radii[i], text);
    }
    free(px);
}

/* make stress: every key's bound combined with every other key's bound, the rest at the profile of the first key's
 * opposite extreme (CUMULO_RANGES_KEY: the first key only). */
static void test_pairs(void **st)
{
    (void)st;
    if (!stress)
        skip();
    const char *only = getenv("CUMULO_RANGES_KEY");
    renders = rejected = 0;
    for (int i = 0; i < nkeys; i++)
        for (int hi = 0; hi < 2 && (!only || strcmp(only, keys[i]->name) == 0); hi++)
            for (int j = 0; j < nkeys; j++)
                for (int b = 0; b < 2 && j != i; b++) {
                    ranges_case c;
                    profile(&c, !hi);
                    c.v[i] = bound(keys[i], hi);
                    c.v[j] = bound(keys[j], b);
                    snprintf(c.label, sizeof c.label, "[%s] %s = %.17g, [%s] %s = %.17g", keys[i]->section,
                             keys[i]->name, c.v[i], keys[j]->section, keys[j]->name, c.v[j]);
                    run_case(&c, i, NULL);
                }
    printf("pairs: %d renders, %d combinations rejected by the whole-scene check\n", renders, rejected);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_just_outside),
        cmocka_unit_test(test_findings),
        cmocka_unit_test(test_each_bound),
        cmocka_unit_test(test_pairs),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
