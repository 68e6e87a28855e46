/* src/core/scene_keys.c: the table of scene keys and sections (see scene_keys.h); scene_values.c reads their values. */
#include "scene_keys.h"
#include "error.h"
#include <math.h>
#include <string.h>

static const char *const phase_names[] = {"cornette-shanks", "hg", "mie", NULL};
static const char *const profile_names[] = {"tapered", "kol", NULL};
static const char *const ms_names[] = {"none", "octaves", "slab", "collector", "diffusion", NULL};
static const char *const sky_names[] = {"preetham", "constant", NULL};
static const char *const shadow_names[] = {"peel", "front", "osm", "fom", NULL};
static const char *const filter_names[] = {"nearest", "bilinear", NULL};
static const char *const planar_names[] = {"off", "on", "auto", NULL};
static const char *const bool_names[] = {"off", "on", NULL};
static const char *const integration_names[] = {"exponential", "kol", NULL};
static const char *const method_names[] = {"kol", "uniform", NULL}; /* in cu_method order (scene.h) */
static const char *const layer_type_names[] = {"cumulus-humilis", "cumulus-mediocris", "cumulus-congestus",
                                               NULL}; /* in cu_cumulus_type order (layer.h) */
static const char *const preset_names[] = {"high", "medium", "low", NULL}; /* in cu_preset order (presets.h) */

#define S(f) offsetof(cu_scene, f)
#define E(f) offsetof(cu_ellipsoid, f)
#define C(f) offsetof(cu_cloud_spec, f)
#define L(f) offsetof(cu_scene_layer, f)
/* One key per line: section, name, type, count, values, default, lo, hi, lo_open, multiple, unit, doc, field. */
#define NUM(sec, key, n, def, lo, hi, open, unit, doc, field) \
    {sec, key, CU_KEY_NUMBER, n, NULL, def, lo, hi, open, 0, unit, doc, field, 0}
#define INT(sec, key, n, def, lo, hi, mult, unit, doc, field) \
    {sec, key, CU_KEY_INTEGER, n, NULL, def, lo, hi, 0, mult, unit, doc, field, 0}
#define ENUM(sec, key, names, def, doc, field) {sec, key, CU_KEY_ENUM, 1, names, def, 0, 0, 0, 0, "", doc, field, 0}
#define BOOL(sec, key, def, doc, field) {sec, key, CU_KEY_BOOL, 1, bool_names, def, 0, 0, 0, 0, "", doc, field, 0}

const cu_scene_key cu_scene_keys[CU_SCENE_KEY_COUNT] = {
    /* time: |t| <= 1e9 s (32 years); positions move by wind x time and wrap, in double on the CPU */
    NUM("scene", "time", 1, "0", -1e9, 1e9, 0, "s", "scene time: wind, life cycles and the sun (with time_utc) follow it",
        S(time)),
    /* The database origin of `cumulo ig`: a host's geodetic positions become world metres about it (WGS84, exact
     * ECEF -> east-north-up, platform/sim/geodetic.c). Heights up to 1e5 m: above every cloud and aircraft. */
    NUM("scene", "origin_latitude", 1, "0", -90, 90, 0, "degrees",
        "where the world's origin is: WGS84 latitude, north positive (cumulo ig's database origin)", S(origin_lat)),
    NUM("scene", "origin_longitude", 1, "0", -180, 180, 0, "degrees",
        "... and longitude, east positive", S(origin_lon)),
    NUM("scene", "origin_altitude", 1, "0", -1e4, 1e5, 0, "m",
        "... and height above mean sea level (world y = 0 there)", S(origin_alt)),
    /* size <= 16384: GLES limits (GL_MAX_RENDERBUFFER_SIZE, checked at render time); the maths is per pixel */
    INT("output", "size", 2, "640 480", 1, 16384, 0, "pixels", "image width and height", S(width)),
    /* exposure <= 1e6: the tone curve squares exposure x radiance (tonemap.frag: x (2.51 x + 0.03)), which overflows
     * fp32 beyond 1.1e19; radiance is at most the sun disk's, irradiance / 6.8e-5 sr <= 1.5e10, so x <= 1.5e16. */
    NUM("output", "exposure", 1, "0.06", 0, 1e6, 1, "", "multiplies radiance (kcd/m^2) before the filmic tone curve",
        S(exposure)),
    /* |x| <= 5e5 m (the camera within 500 km of the origin): the renderer works cloud-local in fp32, and a point
     * 1.7e6 m away is held to 2^-24 x 1.7e6 = 0.1 m. How far from the smallest ellipsoid it may be is the
     * whole-scene check's (cu_scene_check_ranges): 1e5 of its radii. */
    NUM("camera", "position", 3, "0 0 0", -5e5, 5e5, 0, "m", "where the camera is; world: y up, x east, z south",
        S(cam_pos)),
    NUM("camera", "look_at", 3, "0 0 0", -5e5, 5e5, 0, "m", /* only its direction is used (normalised in fp64) */ "the point the camera looks at (not its position)",
        S(cam_look)),
    /* fov >= 0.1 deg: a pixel spans fov / height >= 0.1 deg / 16384 = 1.1e-7 rad, two fp32 ulps of a unit direction;
     * narrower, neighbouring pixels share one fp32 ray. <= 179: tan(fov / 2) <= 115, a finite frustum. */
    NUM("camera", "fov", 1, "50", 0.1, 179, 0, "degrees", "vertical field of view", S(cam_fov)),
    /* angles: only their sines and cosines enter, finite for any value; turbidity: Preetham's fit covers 1.7 .. 10 */
    NUM("sun", "elevation", 1, "0", -90, 90, 0, "degrees", "angle of the sun above the horizon", S(sun_elevation)),
    NUM("sun", "azimuth", 1, "0", -360, 720, 0, "degrees", "direction of the sun, from north toward east",
        S(sun_azimuth)),
    /* time_utc: 1900 .. 2100, the range of the Delta T model (solar.c) */
    {"sun", "time_utc", CU_KEY_TIME, 1, NULL, NULL, 0, 0, 0, 0, "",
     "UTC date and time (2026-06-21T12:00:00Z; +hh:mm offsets too): the sun from the solar position at latitude "
     "and longitude, following [scene] time; replaces elevation and azimuth", S(time_utc), S(has_time_utc)},
    NUM("sun", "latitude", 1, "0", -90, 90, 0, "degrees", "with time_utc or cumulo run --clock: the place, north positive",
        S(latitude)),
    NUM("sun", "longitude", 1, "0", -180, 180, 0, "degrees", "with time_utc or cumulo run --clock: the place, east positive",
        S(longitude)),
    NUM("sun", "turbidity", 1, "2.5", 1.7, 10, 0, "", "Preetham atmospheric turbidity", S(turbidity)),
    /* irradiance, sky colour <= 1e6 (Preetham's sun: ~100): with exposure <= 1e6 the tone curve stays finite (above) */
    {"sun", "irradiance", CU_KEY_NUMBER, 3, NULL, NULL, 0, 1e6, 0, 0, "",
     "RGB irradiance on a plane perpendicular to the rays; unset: from the Preetham model", S(sun_irradiance),
     S(has_sun_irradiance)},
    ENUM("sky", "model", sky_names, "preetham", "preetham, or constant: uniform radiance from every direction",
         S(sky_model)),
    NUM("sky", "color", 3, "0 0 0", 0, 1e6, 0, "", "RGB radiance of the constant sky", S(sky_color)),
    /* albedo in [0, 1]: a reflectance; above 1 the ground would amplify light */
    NUM("sky", "ground_albedo", 1, "0.2", 0, 1, 0, "", "Lambertian ground seen below the horizon", S(ground_albedo)),
    /* density <= 1e7 cm^-3 and r_e <= 1000 um: k_e <= 1e13 x 2 pi 1e-6 = 6.3e7 m^-1, so optical depths through a
     * 2e5 m chord reach 1.3e13, finite in fp32; the path tracer's steps per path are bounded (tools/pathtrace). */
    NUM("cloud", "density", 1, "400", 0, 1e7, 0, "cm^-3", "droplets in the core (rho_0)", S(density_cm3)),
    NUM("cloud", "droplet_radius", 1, "6", 0, 1000, 1, "um",
        "effective radius r_e (extinction 2 pi r_e^2 when the phase is analytic)", S(droplet_radius_um)),
    /* boundary <= 1e6 m: only d / h enters (d <= the largest radius, 1e5 m), so any h is finite; 1e6 keeps h > d */
    NUM("cloud", "boundary", 1, "62", 0, 1e6, 0, "m", "thickness h of the noisy boundary", S(boundary_m)),
    /* noise_scale <= 1e4 (a tile per 0.1 m); the product with the cloud's size is the whole-scene check's */
    NUM("cloud", "noise_scale", 1, "1", 0, 1e4, 1, "",
        "1: one 64^3 noise tile spans 1000 m (the 8x layer repeats every 125 m)", S(noise_scale)),
    ENUM("cloud", "phase", phase_names, "mie", "phase function: mie (data/mie_cloud.tbl), hg or cornette-shanks",
         S(phase)),
    /* |g| <= 0.99: the HG and Cornette-Shanks denominators (1 + g^2 - 2 g mu)^1.5 stay >= 1e-6, the forward peak
     * (1 + g) / (4 pi (1 - g)^2) <= 1.6e3 sr^-1, far from fp32 overflow */
    NUM("cloud", "g", 1, "0.86", -0.99, 0.99, 0, "", "asymmetry of hg and cornette-shanks", S(phase_g)),
    ENUM("cloud", "profile", profile_names, "tapered",
         "density profile: tapered noise, or kol (Kol eq. 3.1 as printed)", S(profile)),
    /* wind <= 200 m/s (jet streams reach 100); offsets within the noise coordinates' fp32 range (|x| <= 5e5 m) */
    NUM("cloud", "wind", 2, "0 0", -200, 200, 0, "m/s", "the cloud's drift toward east and north (every cloud's "
        "unless it gives its own)", S(cloud_wind)),
    NUM("cloud", "noise_offset", 3, "0 0 0", -5e5, 5e5, 0, "m",
        "where in the noise field the cloud sits (later clouds: a different place each by default)",
        S(cloud_noise_offset)),
    NUM("cloud", "lifetime", 1, "0", 0, 1e7, 0, "s", "forms, matures and dissolves over this, then forms again "
        "(0: lives forever)", S(cloud_lifetime)),
    NUM("cloud", "life_phase", 1, "0.5", 0, 1, 0, "", "where in its life the cloud is at time 0 (0.5: mature)",
        S(cloud_life_phase)),
    /* boil <= 20 m/s: a cloud's whole noise tile (1000 m) passes in a minute at most */
    NUM("cloud", "boil", 1, "0.3", 0, 20, 0, "m/s", "how fast the noise drifts through every cloud as time runs, its "
        "direction turning over ten minutes, so edges evolve (0: frozen)", S(boil)),
    /* wrap: a [layer]'s extent range */
    NUM("cloud", "wrap", 1, "0", 0, 500000, 0, "m", "side of the square about the origin the cloud wraps around as it "
        "drifts, fading at its border, as a [layer]'s clouds do (0: no wrap)", S(cloud_wrap)),
    /* [quality], [light] and [ms] counts: loop counts and array sizes the shaders are compiled with; no count enters
     * a formula as a magnitude. segment_ratio <= 10: knot_t in density.glsl is written as r^(j - n) so that r^n
     * never overflows (10^192 would over 3 merged chords of 64 segments). */
    INT("quality", "segments", 1, "5", 1, 64, 0, "", "march segments per ellipsoid crossed", S(segments)),
    NUM("quality", "segment_ratio", 1, "1.6", 1, 10, 0, "", "ratio of consecutive segment lengths (1: uniform)",
        S(segment_ratio)),
    /* boundary_step: a length; a chord takes at most 32 such steps (BOUNDARY_KNOTS_MAX in density.glsl) */
    NUM("quality", "boundary_step", 1, "15", 0, 1e4, 0, "m",
        "with noise: a ray's chord that never reaches a cloud's core is all noisy boundary (a silhouette, a thin "
        "rim); march it in even steps of at most this, up to 32, instead of quality.segments (0: segments everywhere; "
        "15 samples the noise's strongest octave, 31 m across at noise_scale 1, twice)",
        S(boundary_step)),
    /* ramp_step: a length; an entry ramp takes at most 16 such steps (RAMP_KNOTS_MAX in density.glsl) */
    NUM("quality", "ramp_step", 1, "0", 0, 1e4, 0, "m",
        "with noise: the noisy boundary where a ray's chord enters a cloud, as far as the core, is marched in even "
        "steps of at most this, up to 16 (0: its share of quality.segments, one step where the boundary is thin "
        "against the chord, which sees none of the noise)",
        S(ramp_step)),
    INT("quality", "hull_tessellation", 1, "10", 3, 64, 0, "",
        "latitude bands of the hull mesh (twice as many longitudes)", S(hull_tessellation)),
    INT("quality", "max_intervals", 1, "6", 1, CU_MAX_INTERVALS, 0, "",
        "in-cloud intervals composited per pixel (Kol: 6)", S(max_intervals)),
    BOOL("quality", "noise", "on", "fractal noise in the boundary", S(noise)),
    INT("quality", "noise_octaves", 1, "5", 1, 5, 0, "", "noise mip levels summed (Kol eq. 3.74 uses 5)",
        S(noise_octaves)),
    BOOL("quality", "noise_baked", "on", "fractal noise from one 64^3 texture holding its octaves' weighted sum: 2 "
         "texture reads a sample instead of 10; the noise moves by 0.0035 RMS, 0.04 at most, of its [-1, 1] "
         "(tests/core/test_noise_baked)", S(noise_baked)),
    INT("quality", "sun_map_size", 1, "128", 16, 4096, 0, "texels",
        "sun maps (opacity map, or front and back depth) per side", S(sun_map_size)),
    INT("quality", "sun_map_frames", 1, "4", 1, 16, 0, "frames",
        "a sun that creeps (or noise that boils on) has a cloud's maps, and the ground's shadow maps, made again over "
        "this many frames, a band of rows a frame, swapped in whole: a sun turned every frame costs this fraction of "
        "the maps a frame and lights up to 2N - 1 frames late; a jump of the sun (over 1 degree in a frame) remakes "
        "them at once (1: whole maps in one frame)", S(sun_map_frames)),
    INT("quality", "lod_pixels", 1, "48", 0, 16384, 0, "pixels",
        "in a field of clouds, one narrower than this on screen is marched with one segment fewer and two noise "
        "octaves (0: never)", S(lod_pixels)),
    /* up to 4096 pixels: an impostor's image is at most 256 texels a side, so a larger cloud would blur */
    INT("quality", "impostor_pixels", 1, "0", 0, 4096, 0, "pixels",
        "a cloud narrower than this on screen is drawn from an image of itself made from the eye (an impostor), "
        "remade when the direction to it turns by more than impostor_degrees, when its sun maps, shadows, life or "
        "boil move on, at most four a frame besides new ones (0: never)", S(impostor_pixels)),
    /* 0.01 .. 45 degrees: below, a cloud drifting in the wind would be remade every frame anyway */
    NUM("quality", "impostor_degrees", 1, "1", 0.01, 45, 0, "degrees",
        "how far the direction from the eye to a cloud may turn before its impostor is remade", S(impostor_degrees)),
    /* up to 64 pixels: a coarser grid's interpolation shows in a smooth sky (tests/gpu/test_sky.c measures it) */
    INT("quality", "sky_grid", 1, "16", 0, 64, 0, "pixels", "the sky worked out at the corners of cells this size and "
        "interpolated (not the sun, the horizon or shadows on the ground, which stay exact), from 8 up grown 2 or 4 "
        "times (to 64) where the sky bends little; 0: at every pixel",
        S(sky_grid)),
    /* 1..4: beyond a quarter a cloud's edge spans 4 output pixels per texel and the upsampling shows */
    INT("quality", "cloud_downsample", 1, "1", 1, 4, 0, "", "draw the clouds at 1/N of the resolution in each "
        "direction and upsample them (depth-aware against the host's depth): about N^2 fewer cloud pixels",
        S(cloud_downsample)),
    /* [0, 1]: both measures below are fractions; 0 turns it off (frame.c, pass_refine.c) */
    NUM("quality", "edge_refine", 1, "0", 0, 1, 0, "", "with cloud_downsample > 1 (and temporal_grid 1): the pixels "
        "whose four nearest low-resolution cloud texels differ by more than this, in coverage or in luminance "
        "contrast (max - min) / (max + min), are marched again at full resolution (a cloud's rim, a thin bright "
        "edge; needs half-float targets); 0: off", S(edge_refine)),
    /* 1..4: a 4 x 4 grid already waits 16 frames for each pixel's own ray */
    INT("quality", "temporal_grid", 1, "1", 1, 4, 0, "", "each frame marches one cloud pixel of every G x G block "
        "(a Bayer order) and reprojects the others from the frame before (camera motion and wind); each pixel is "
        "marched again within G^2 frames; 1: every pixel every frame", S(temporal_grid)),
    /* 1000 fps: 1 ms a frame, beyond what any display shows; 0: off */
    NUM("quality", "target_fps", 1, "0", 0, 1000, 0, "frames/s", "a frame budget: the renderer times its frames "
        "(GPU timer queries, else the wall clock) and draws the clouds at a coarser cloud_downsample and "
        "temporal_grid, up to the two maxima below, while frames take longer than 1/target_fps; 0: off", S(target_fps)),
    INT("quality", "max_downsample", 1, "2", 1, 4, 0, "", "target_fps: the coarsest cloud_downsample it may use "
        "(at least cloud_downsample)", S(max_downsample)),
    INT("quality", "max_temporal_grid", 1, "4", 1, 4, 0, "", "target_fps: the largest temporal_grid it may use (at "
        "least temporal_grid)", S(max_temporal_grid)),
    BOOL("quality", "cloud_shadows", "on", "clouds shade each other and the ground (needs half-float targets)",
         S(cloud_shadows)),
    ENUM("quality", "integration", integration_names, "exponential",
         "segment integration: exponential (energy-conserving) or kol (Kol's trapezoids, eq. 3.20)", S(integration)),
    ENUM("quality", "method", method_names, "kol",
         "how a pixel's ray is marched: kol (analytic chords, quality.segments log-spaced segments, sun maps) or "
         "uniform (the mainstream ray march: uniform_steps jittered steps, uniform_sun_steps toward the sun at each; "
         "the trade study's baseline; its multiple scattering is octaves unless ms.mode = none)",
         S(method)),
    /* steps are loop counts: 4..512 along the view, 1..32 toward the sun (the sun march's ratio 1 + 4/M: (1 + 4)^1 ..
     * 1.125^32 = 43, all finite in fp32) */
    INT("quality", "uniform_steps", 1, "64", 4, 512, 0, "", "method = uniform: steps along the view ray through the "
        "cloud", S(uniform_steps)),
    INT("quality", "uniform_sun_steps", 1, "6", 1, 32, 0, "", "method = uniform: steps toward the sun from each "
        "sample, each 1 + 4 / uniform_sun_steps times the last", S(uniform_sun_steps)),
    ENUM("quality", "preset", preset_names, "high",
         "the sweep's presets (src/core/presets.c; high: the defaults); keys set in the file or by --set win",
         S(preset)),
    ENUM("light", "shadow", shadow_names, "peel",
         "sun transmittance: peel (opacity map of the cloud's intervals), front (Kol), osm (opacity shadow maps) or "
         "fom (Fourier opacity maps)",
         S(shadow)),
    INT("light", "sun_intervals", 1, "3", 1, 4, 0, "", "most in-cloud intervals per sun ray the opacity map stores",
        S(sun_intervals)),
    INT("light", "sun_samples", 1, "32", 4, 64, 4, "", "trapezoids per interval in the opacity pass", S(sun_samples)),
    ENUM("light", "sun_filter", filter_names, "bilinear", "lookup of the opacity map: nearest or bilinear",
         S(sun_filter)),
    ENUM("light", "sun_planar", planar_names, "auto",
         "opacity map read as far below each texel's entry as the sample is below its own (where the lit surface is "
         "slanted to the sun, a texel's ray enters earlier or later than the sample's): on, off, or auto: on where a "
         "cloud's map texel, at the smallest map it may get (a field's: 16 texels), is wider than an eighth of its "
         "lit skin (the boundary, or a mean free path) and finer than an eighth of its lobes (the smallest middle "
         "semi-axis), where the surface is a plane across the texels read",
         S(sun_planar)),
    INT("light", "osm_slices", 1, "16", 4, 64, 4, "", "shadow = osm: opacity slices along the sun", S(osm_slices)),
    INT("light", "fom_coefficients", 1, "8", 1, 16, 0, "", "shadow = fom: Fourier terms", S(fom_coefficients)),
    ENUM("ms", "mode", ms_names, "slab",
         "multiple scattering: slab (Bouthors' model, Kol's fixed blur), collector (Bouthors' iterative collector "
         "search), octaves (Wrenninge), diffusion (flux-limited diffusion solved on a grid over each cloud) or none",
         S(ms_mode)),
    /* Wrenninge's a, b, c in [0, 1]: the octaves' factors a^o, b^o, c^o shrink, so their sums stay <= octaves */
    /* the defaults: `make fit-octaves` (docs/ms_octaves_fit.txt; tests/app/test_cli.sh checks), not the textbook's */
    INT("ms", "octaves", 1, "8", 1, 8, 0, "", "mode = octaves: Wrenninge's octave count (fitted to the path tracer)",
        S(ms_octaves)),
    NUM("ms", "a", 1, "0.2", 0, 1, 0, "", "mode = octaves: extinction factor per octave (fitted; textbook 0.5)",
        S(ms_a)),
    NUM("ms", "b", 1, "0.5", 0, 1, 0, "", "mode = octaves: scattering factor per octave (fitted)", S(ms_b)),
    NUM("ms", "c", 1, "0.5", 0, 1, 0, "", "mode = octaves: anisotropy factor per octave (fitted)", S(ms_c)),
    BOOL("ms", "sky_light", "on",
         "sky and ground light; with slab or collector and a Preetham sky, sky and ground told apart by the slab "
         "model",
         S(sky_light)),
    /* blur in (0, 1e6] m: log2(blur / texel) is the slab maps' LOD, finite for blur > 0 and clamped to the mips */
    NUM("ms", "blur", 1, "200", 0, 1e6, 1, "m",
        "mode = slab: width over which the slab maps are averaged around a point (Kol's fixed LOD)", S(ms_blur_m)),
    INT("ms", "iterations", 1, "10", 1, 32, 0, "", "mode = collector: most search steps (Bouthors eqs. 3.59-3.63)",
        S(ms_iterations)),
    INT("ms", "grid", 1, "32", 8, 96, 0, "", "mode = diffusion: cells along the longest side of a cloud's grid",
        S(ms_grid)),
    BOOL("ms", "lobe", "on",
         "mode = diffusion: light the phase function's forward lobe carries to the eye over several scatterings (which "
         "delta-M counts as unscattered): lit faces seen toward the sun",
         S(ms_lobe)),
    INT("ms", "frame_work", 1, "300", 1, 1000000, 0, "",
        "mode = diffusion: thousands of cell updates a frame for sampling and solving grids again (the sun turned, a "
        "cloud changed or came into view); a scene's first frame solves every grid whole",
        S(ms_frame_work)),
    BOOL("ms", "closure", "on",
         "slab and collector modes: scale multiple scattering so the clouds send out no more light than they "
         "intercept (the energy closure)",
         S(ms_closure)),
};

/* A [cloud] after the first: what may differ between clouds (the droplets and the phase function are shared). */
const cu_scene_key cu_cloud_keys[CU_CLOUD_KEY_COUNT] = {
    {"cloud", "density", CU_KEY_NUMBER, 1, NULL, NULL, 0, 1e7, 0, 0, "cm^-3", "droplets in the core (rho_0)",
     C(density_cm3), C(has_density)},
    {"cloud", "boundary", CU_KEY_NUMBER, 1, NULL, NULL, 0, 1e6, 0, 0, "m", "thickness h of the noisy boundary",
     C(boundary_m), C(has_boundary)},
    {"cloud", "wind", CU_KEY_NUMBER, 2, NULL, NULL, -200, 200, 0, 0, "m/s", "the cloud's drift", C(wind),
     C(has_wind)},
    {"cloud", "noise_offset", CU_KEY_NUMBER, 3, NULL, NULL, -5e5, 5e5, 0, 0, "m",
     "where in the noise field the cloud sits", C(noise_offset), C(has_noise_offset)},
    {"cloud", "lifetime", CU_KEY_NUMBER, 1, NULL, NULL, 0, 1e7, 0, 0, "s", "its life cycle (0: forever)", C(lifetime),
     C(has_lifetime)},
    {"cloud", "life_phase", CU_KEY_NUMBER, 1, NULL, NULL, 0, 1, 0, 0, "", "where in its life it is at time 0",
     C(life_phase), C(has_life_phase)},
    {"cloud", "wrap", CU_KEY_NUMBER, 1, NULL, NULL, 0, 500000, 0, 0, "m", "the square it wraps around (0: none)",
     C(wrap), C(has_wrap)},
};

/* [layer]: a generated field of cumulus (src/core/layer.c holds the size distribution and the shapes). */
const cu_scene_key cu_layer_keys[CU_LAYER_KEY_COUNT] = {
    ENUM("layer", "type", layer_type_names, "cumulus-mediocris",
         "cumulus-humilis (flat), cumulus-mediocris or cumulus-congestus (towering)", L(type)),
    /* the generator's own ranges (layer.c): a base within the troposphere, a layer 50 m .. 15 km thick */
    NUM("layer", "base", 1, "1000", 0, 20000, 0, "m", "cloud base above the ground", L(base)),
    NUM("layer", "thickness", 1, "1500", 50, 15000, 0, "m", "from the base to the tallest tops", L(thickness)),
    NUM("layer", "coverage", 1, "0.3", 0, 1, 0, "", "fraction of the sky covered, seen from straight above",
        L(coverage)),
    NUM("layer", "extent", 1, "20000", 100, 500000, 0, "m", "side of the square (centred on the origin) the clouds "
        "fill and wrap around", L(extent)),
    INT("layer", "seed", 1, "1", 0, 2147483647, 0, "", "the same seed gives the same sky on every machine", L(seed)),
    NUM("layer", "wind", 2, "5 0", -200, 200, 0, "m/s", "the layer's drift toward east and north", L(wind)),
    NUM("layer", "lifetime", 1, "900", 0, 1e7, 0, "s", "each cloud forms, matures and dissolves over this (0: "
        "forever)", L(lifetime)),
};

const cu_scene_key cu_ellipsoid_keys[CU_ELLIPSOID_KEY_COUNT] = {
    /* |x| <= 5e5 m, as the camera: fp32 holds the cloud-local frame (origin mid-cloud) to 0.1 m at 1.7e6 m. */
    NUM("ellipsoid", "center", 3, NULL, -5e5, 5e5, 0, "m", "centre, world coordinates (required)", E(center)),
    /* radii in [0.1, 1e5] m (a cumulus cell is 1 m .. 20 km). >= 0.1 m: the shaders' absolute slacks (1e-3 m chord
     * tolerance in extinction(), 5 cm end-sample nudge) stay small against the chord, and 1 / r^2 is far from fp32
     * overflow (radii 1e-20 made the chord's terms 1e42). <= 1e5 m: chords and optical depths stay finite (density
     * above), and the cloud's frame fits in fp32 (centre). The ratio to the scene's size: cu_scene_check_ranges. */
    NUM("ellipsoid", "radii", 3, NULL, 0.1, 1e5, 0, "m", "semi-axes along world x, y, z (required)", E(radii)),
};
#undef S
#undef E
#undef C
#undef L

const cu_scene_section cu_scene_sections[CU_SCENE_SECTION_COUNT] = {
    {"scene", 0, 0, "the scene's time and where it is on Earth", NULL, 0},
    {"output", 0, 0, "the image", NULL, 0},
    {"camera", 1, 0, "a pinhole camera", NULL, 0},
    {"sun", 1, 0, "the sun and the Preetham atmosphere", NULL, 0},
    {"sky", 0, 0, "the light from the sky and the ground", NULL, 0},
    {"cloud", 0, 0, "the droplets of every cloud; the first [cloud] also sets every cloud's defaults, and each further "
                    "[cloud] starts a new cloud (density, boundary, wind, noise_offset, lifetime, life_phase of its "
                    "own) made of the [ellipsoid] sections after it", NULL, 0},
    {"ellipsoid", 0, 1, "one ellipsoid of the current cloud; repeat the section for each, up to 64 a cloud",
     cu_ellipsoid_keys, CU_ELLIPSOID_KEY_COUNT},
    {"layer", 0, 1, "a generated field of cumulus; repeat for more layers, up to 8", cu_layer_keys,
     CU_LAYER_KEY_COUNT},
    {"quality", 0, 0, "speed against accuracy of the real-time renderer", NULL, 0},
    {"light", 0, 0, "the sun's transmittance through the cloud", NULL, 0},
    {"ms", 0, 0, "multiple scattering", NULL, 0},
};

/* Counts in the header match the tables; explicit and seen flags fit (scene.h). */
typedef char key_count_ok[sizeof cu_scene_keys / sizeof cu_scene_keys[0] == CU_SCENE_KEY_COUNT ? 1 : -1];
typedef char ell_count_ok[sizeof cu_ellipsoid_keys / sizeof cu_ellipsoid_keys[0] == CU_ELLIPSOID_KEY_COUNT ? 1 : -1];
typedef char cloud_count_ok[sizeof cu_cloud_keys / sizeof cu_cloud_keys[0] == CU_CLOUD_KEY_COUNT ? 1 : -1];
typedef char layer_count_ok[sizeof cu_layer_keys / sizeof cu_layer_keys[0] == CU_LAYER_KEY_COUNT ? 1 : -1];
typedef char keys_fit_flags[CU_SCENE_KEY_COUNT <= sizeof(((cu_scene *)0)->explicit_key) ? 1 : -1];
typedef char name_first[offsetof(cu_scene, name) == 0 ? 1 : -1]; /* cu_scene_key.given == 0 means none */

const cu_scene_section *cu_scene_section_find(const char *name)
{
    for (int i = 0; i < CU_SCENE_SECTION_COUNT; i++)
        if (strcmp(cu_scene_sections[i].name, name) == 0)
            return &cu_scene_sections[i];
    return NULL;
}

const cu_scene_key *cu_scene_section_keys(const cu_scene_section *sec, int *n)
{
    *n = sec->keys ? sec->n_keys : CU_SCENE_KEY_COUNT;
    return sec->keys ? sec->keys : cu_scene_keys;
}

int cu_scene_instances(const cu_scene *s, const cu_scene_section *sec)
{
    if (!sec->repeated)
        return 1;
    return sec->keys == cu_layer_keys ? s->n_layers : s->n_ellipsoids;
}

void *cu_scene_instance(cu_scene *s, const cu_scene_section *sec, int i)
{
    if (!sec->repeated)
        return s;
    return sec->keys == cu_layer_keys ? (void *)&s->layers[i] : (void *)&s->ell[i];
}

const cu_scene_key *cu_scene_key_find(const char *section, const char *name)
{
    const cu_scene_section *sec = cu_scene_section_find(section);
    if (!sec)
        return NULL;
    int n;
    const cu_scene_key *keys = cu_scene_section_keys(sec, &n);
    for (int i = 0; i < n; i++)
        if (strcmp(keys[i].section, section) == 0 && strcmp(keys[i].name, name) == 0)
            return &keys[i];
    return NULL;
}
