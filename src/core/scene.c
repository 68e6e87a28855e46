/* src/scene.c: parses INI-style scene files and --set overrides into a cu_scene, rejecting bad input with
 * file:line:column messages that name the field. */
#include "scene.h"
#include "presets.h"
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LINE 4096
#define MAX_FILE (4 << 20)

typedef enum { K_DOUBLE, K_INT, K_ENUM } key_kind;

typedef struct key_def {
    const char *section, *name;
    key_kind kind;
    int count;              /* numbers expected */
    size_t offset;          /* into cu_scene, or into cu_ellipsoid for section "ellipsoid" */
    double lo, hi;          /* inclusive range */
    int lo_open;            /* 1: value must be > lo */
    const char *const *enum_names;
    const char *unit;
} key_def;

static const char *const phase_names[] = {"cornette-shanks", "hg", "mie", NULL};
static const char *const profile_names[] = {"tapered", "kol", NULL};
static const char *const ms_names[] = {"none", "octaves", "slab", "collector", NULL};
static const char *const sky_names[] = {"preetham", "constant", NULL};
static const char *const shadow_names[] = {"peel", "front", "osm", "fom", NULL};
static const char *const filter_names[] = {"nearest", "bilinear", NULL};
static const char *const bool_names[] = {"off", "on", NULL};
static const char *const integration_names[] = {"exponential", "kol", NULL};
static const char *const preset_names[] = {"high", "medium", "low", NULL};

#define S(f) offsetof(cu_scene, f)
#define E(f) offsetof(cu_ellipsoid, f)
static const key_def keys[] = {
    {"output", "size", K_INT, 2, S(width), 1, 16384, 0, NULL, "pixels"},
    {"output", "exposure", K_DOUBLE, 1, S(exposure), 0, 1e6, 1, NULL, ""},
    {"camera", "position", K_DOUBLE, 3, S(cam_pos), -1e7, 1e7, 0, NULL, "m"},
    {"camera", "look_at", K_DOUBLE, 3, S(cam_look), -1e7, 1e7, 0, NULL, "m"},
    {"camera", "fov", K_DOUBLE, 1, S(cam_fov), 0, 179, 1, NULL, "degrees"},
    {"sun", "elevation", K_DOUBLE, 1, S(sun_elevation), -90, 90, 0, NULL, "degrees"},
    {"sun", "azimuth", K_DOUBLE, 1, S(sun_azimuth), -360, 720, 0, NULL, "degrees"},
    {"sun", "turbidity", K_DOUBLE, 1, S(turbidity), 1.7, 10, 0, NULL, ""},
    {"sun", "irradiance", K_DOUBLE, 3, S(sun_irradiance), 0, 1e9, 0, NULL, ""},
    {"sky", "model", K_ENUM, 1, S(sky_model), 0, 0, 0, sky_names, ""},
    {"sky", "color", K_DOUBLE, 3, S(sky_color), 0, 1e9, 0, NULL, ""},
    {"sky", "ground_albedo", K_DOUBLE, 1, S(ground_albedo), 0, 1, 0, NULL, ""},
    {"cloud", "density", K_DOUBLE, 1, S(density_cm3), 0, 1e7, 0, NULL, "cm^-3"},
    {"cloud", "droplet_radius", K_DOUBLE, 1, S(droplet_radius_um), 0, 1000, 1, NULL, "um"},
    {"cloud", "boundary", K_DOUBLE, 1, S(boundary_m), 0, 1e6, 0, NULL, "m"},
    {"cloud", "noise_scale", K_DOUBLE, 1, S(noise_scale), 0, 1e4, 1, NULL, ""},
    {"cloud", "phase", K_ENUM, 1, S(phase), 0, 0, 0, phase_names, ""},
    {"cloud", "g", K_DOUBLE, 1, S(phase_g), -0.99, 0.99, 0, NULL, ""},
    {"cloud", "profile", K_ENUM, 1, S(profile), 0, 0, 0, profile_names, ""},
    {"ellipsoid", "center", K_DOUBLE, 3, E(center), -1e7, 1e7, 0, NULL, "m"},
    {"ellipsoid", "radii", K_DOUBLE, 3, E(radii), 0, 1e6, 1, NULL, "m"},
    {"quality", "segments", K_INT, 1, S(segments), 1, 64, 0, NULL, ""},
    {"quality", "segment_ratio", K_DOUBLE, 1, S(segment_ratio), 1, 10, 0, NULL, ""},
    {"quality", "hull_tessellation", K_INT, 1, S(hull_tessellation), 3, 64, 0, NULL, ""},
    {"quality", "max_intervals", K_INT, 1, S(max_intervals), 1, CU_MAX_INTERVALS, 0, NULL, ""},
    {"quality", "noise", K_ENUM, 1, S(noise), 0, 0, 0, bool_names, ""},
    {"quality", "noise_octaves", K_INT, 1, S(noise_octaves), 1, 5, 0, NULL, ""},
    {"quality", "sun_map_size", K_INT, 1, S(sun_map_size), 16, 4096, 0, NULL, "texels"},
    {"quality", "integration", K_ENUM, 1, S(integration), 0, 0, 0, integration_names, ""},
    {"quality", "preset", K_ENUM, 1, S(preset), 0, 0, 0, preset_names, ""},
    {"light", "shadow", K_ENUM, 1, S(shadow), 0, 0, 0, shadow_names, ""},
    {"light", "sun_intervals", K_INT, 1, S(sun_intervals), 1, 4, 0, NULL, ""},
    {"light", "sun_samples", K_INT, 1, S(sun_samples), 4, 64, 0, NULL, ""},
    {"light", "sun_filter", K_ENUM, 1, S(sun_filter), 0, 0, 0, filter_names, ""},
    {"light", "osm_slices", K_INT, 1, S(osm_slices), 4, 64, 0, NULL, ""},
    {"light", "fom_coefficients", K_INT, 1, S(fom_coefficients), 1, 16, 0, NULL, ""},
    {"ms", "mode", K_ENUM, 1, S(ms_mode), 0, 0, 0, ms_names, ""},
    {"ms", "octaves", K_INT, 1, S(ms_octaves), 1, 8, 0, NULL, ""},
    {"ms", "a", K_DOUBLE, 1, S(ms_a), 0, 1, 0, NULL, ""},
    {"ms", "b", K_DOUBLE, 1, S(ms_b), 0, 1, 0, NULL, ""},
    {"ms", "c", K_DOUBLE, 1, S(ms_c), 0, 1, 0, NULL, ""},
    {"ms", "sky_light", K_ENUM, 1, S(sky_light), 0, 0, 0, bool_names, ""},
    {"ms", "blur", K_DOUBLE, 1, S(ms_blur_m), 0, 1e6, 1, NULL, "m"},
    {"ms", "iterations", K_INT, 1, S(ms_iterations), 1, 32, 0, NULL, ""},
    {"ms", "closure", K_ENUM, 1, S(ms_closure), 0, 0, 0, bool_names, ""},
};
#undef S
#undef E
#define N_KEYS ((int)(sizeof keys / sizeof keys[0]))
/* cu_scene.explicit_key has one flag per key */
typedef char keys_fit_explicit_flags[N_KEYS <= (int)sizeof(((cu_scene *)0)->explicit_key) ? 1 : -1];

static const char *const sections[] = {"output", "camera", "sun", "sky", "cloud", "ellipsoid", "quality", "light",
                                       "ms", NULL};

void cu_scene_defaults(cu_scene *s)
{
    memset(s, 0, sizeof *s);
    s->width = 640;
    s->height = 480;
    s->exposure = 0.06;
    s->cam_fov = 50;
    s->turbidity = 2.5;
    s->sky_model = CU_SKY_PREETHAM;
    s->ground_albedo = 0.2;
    s->density_cm3 = 400;
    s->droplet_radius_um = 6;
    s->boundary_m = 62;
    s->noise_scale = 1;
    s->phase = CU_PHASE_MIE;
    s->phase_g = 0.86;
    s->profile = CU_PROFILE_TAPERED;
    s->segments = 5;
    s->segment_ratio = 1.6;
    s->hull_tessellation = 10;
    s->max_intervals = 6;
    s->noise = 1;
    s->noise_octaves = 5;
    s->sun_map_size = 128;
    s->shadow = CU_SHADOW_PEEL;
    s->sun_intervals = 3;
    s->sun_samples = 32;
    s->sun_filter = 1;
    s->osm_slices = 16;
    s->fom_coefficients = 8;
    s->ms_mode = CU_MS_SLAB;
    s->ms_blur_m = 200;
    s->ms_iterations = 10;
    s->ms_closure = 1;
    s->ms_octaves = 4;
    s->ms_a = 0.5;
    s->ms_b = 0.5;
    s->ms_c = 0.5;
    s->sky_light = 1;
}

double cu_scene_core_extinction(const cu_scene *s)
{
    double rho = s->density_cm3 * 1e6;          /* m^-3 */
    double re = s->droplet_radius_um * 1e-6;    /* m */
    return rho * 2.0 * 3.14159265358979323846 * re * re;
}

static int fail(cu_error *err, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
    }
    return 1;
}

/* Where a message points: "file:line:col" for files, "--set" for overrides. */
typedef struct where {
    const char *file;
    int line;
} where;

static void where_str(char *buf, size_t n, where w, int col)
{
    if (w.line > 0)
        snprintf(buf, n, "%s:%d:%d", w.file, w.line, col);
    else
        snprintf(buf, n, "%s", w.file);
}

static const key_def *find_key(const char *section, const char *name)
{
    for (int i = 0; i < N_KEYS; i++)
        if (strcmp(keys[i].section, section) == 0 && strcmp(keys[i].name, name) == 0)
            return &keys[i];
    return NULL;
}

/* Parses the value text of one key into dst; text is NUL-terminated and trimmed. col is its column. */
static int parse_value(const key_def *k, void *dst, const char *text, where w, int col, cu_error *err)
{
    char at[700];
    where_str(at, sizeof at, w, col);
    if (k->kind == K_ENUM) {
        for (int i = 0; k->enum_names[i]; i++)
            if (strcmp(text, k->enum_names[i]) == 0) {
                if (k->enum_names == bool_names)
                    *(int *)dst = i;
                else
                    *(int *)dst = i; /* all enums are int-sized */
                return 0;
            }
        char choices[200] = "";
        for (int i = 0; k->enum_names[i]; i++) {
            strncat(choices, i ? " | " : "", sizeof choices - strlen(choices) - 1);
            strncat(choices, k->enum_names[i], sizeof choices - strlen(choices) - 1);
        }
        return fail(err, "%s: '%s' must be one of %s, got '%.40s'", at, k->name, choices, text);
    }
    double vals[4];
    int n = 0;
    const char *p = text;
    while (*p) {
        while (*p == ' ' || *p == '\t' || *p == ',')
            p++;
        if (!*p)
            break;
        if (n == k->count) {
            return fail(err, "%s: '%s' needs %d number%s, got more", at, k->name, k->count, k->count > 1 ? "s" : "");
        }
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || (*end && *end != ' ' && *end != '\t' && *end != ','))
            return fail(err, "%s: '%s' expects a number, got '%.*s'", at, k->name,
                        (int)strcspn(p, " \t,") > 40 ? 40 : (int)strcspn(p, " \t,"), p);
        if (isnan(v))
            return fail(err, "%s: '%s' is NaN", at, k->name);
        if (isinf(v) || errno == ERANGE) {
            if (isinf(v) || fabs(v) > 1.0)
                return fail(err, "%s: '%s' is out of range (%.*s)", at, k->name, (int)(end - p) > 40 ? 40 : (int)(end - p), p);
            v = 0.0; /* underflow to zero is harmless */
        }
        if (k->kind == K_INT && v != floor(v))
            return fail(err, "%s: '%s' must be a whole number, got %g", at, k->name, v);
        vals[n++] = v;
        p = end;
    }
    if (n != k->count)
        return fail(err, "%s: '%s' needs %d number%s, got %d", at, k->name, k->count, k->count > 1 ? "s" : "", n);
    for (int i = 0; i < n; i++) {
        double v = vals[i];
        int bad = k->lo_open ? !(v > k->lo) : !(v >= k->lo);
        if (bad || v > k->hi) {
            if (k->lo_open && k->lo == 0 && v <= 0)
                return fail(err, "%s: '%s' must be positive, got %g", at, k->name, v);
            return fail(err, "%s: '%s' must be in [%g, %g]%s%s, got %g", at, k->name, k->lo, k->hi,
                        k->unit[0] ? " " : "", k->unit, v);
        }
    }
    for (int i = 0; i < n; i++) {
        if (k->kind == K_INT)
            ((int *)dst)[i] = (int)vals[i];
        else
            ((double *)dst)[i] = vals[i];
    }
    return 0;
}

static void *key_target(cu_scene *s, const key_def *k, int ellipsoid)
{
    if (strcmp(k->section, "ellipsoid") == 0)
        return (char *)&s->ell[ellipsoid] + k->offset;
    return (char *)s + k->offset;
}

static int is_section(const char *name)
{
    for (int i = 0; sections[i]; i++)
        if (strcmp(sections[i], name) == 0)
            return 1;
    return 0;
}

/* Bits of which keys were seen in the current section instance, to reject duplicates. */
typedef struct seen_set {
    unsigned char seen[64];
} seen_set;

static int post_checks(cu_scene *s, const char *file, int have_sections[], const int ell_line[],
                       const unsigned char ell_seen[][2], cu_error *err)
{
    static const char *const required[] = {"camera", "sun", "cloud", NULL};
    for (int i = 0; required[i]; i++) {
        int idx = 0;
        while (strcmp(sections[idx], required[i]) != 0)
            idx++;
        if (!have_sections[idx])
            return fail(err, "%s: missing section [%s]", file, required[i]);
    }
    if (s->n_ellipsoids == 0)
        return fail(err, "%s: missing section [ellipsoid] (a cloud needs at least one)", file);
    for (int e = 0; e < s->n_ellipsoids; e++) {
        if (!ell_seen[e][0])
            return fail(err, "%s:%d:1: [ellipsoid] #%d has no 'center'", file, ell_line[e], e + 1);
        if (!ell_seen[e][1])
            return fail(err, "%s:%d:1: [ellipsoid] #%d has no 'radii'", file, ell_line[e], e + 1);
    }
    if (s->sun_samples % 4)
        return fail(err, "%s: [light] 'sun_samples' must be a multiple of 4, got %d", file, s->sun_samples);
    if (s->osm_slices % 4)
        return fail(err, "%s: [light] 'osm_slices' must be a multiple of 4, got %d", file, s->osm_slices);
    double dx = s->cam_look[0] - s->cam_pos[0], dy = s->cam_look[1] - s->cam_pos[1], dz = s->cam_look[2] - s->cam_pos[2];
    if (dx * dx + dy * dy + dz * dz < 1e-12)
        return fail(err, "%s: [camera] 'look_at' equals 'position'; the view direction is undefined", file);
    return 0;
}

/* Applies the scene's quality preset to every key it lists that the file (or an earlier --set) did not set itself:
 * explicit keys win wherever they appear. */
static int apply_preset(cu_scene *s, const char *file, cu_error *err)
{
    char list[2048];
    snprintf(list, sizeof list, "%s", cu_preset_settings((cu_preset)s->preset));
    char *save = NULL;
    for (char *item = strtok_r(list, ";", &save); item; item = strtok_r(NULL, ";", &save)) {
        char *eq = strchr(item, '='), *dot = strchr(item, '.');
        if (!eq || !dot || dot > eq)
            return fail(err, "%s: preset '%s': malformed entry '%s'", file, preset_names[s->preset], item);
        *eq = *dot = 0;
        const key_def *k = find_key(item, dot + 1);
        if (!k)
            return fail(err, "%s: preset '%s': unknown key '%s.%s'", file, preset_names[s->preset], item, dot + 1);
        if (s->explicit_key[k - keys])
            continue;
        where w = {"preset", 0};
        if (parse_value(k, key_target(s, k, 0), eq + 1, w, 0, err))
            return 1;
    }
    return 0;
}

int cu_scene_parse(cu_scene **out, const char *name, const char *text, size_t len, cu_error *err)
{
    *out = NULL;
    if (len > MAX_FILE)
        return fail(err, "%s: file is larger than %d bytes", name, MAX_FILE);
    cu_scene *s = malloc(sizeof *s);
    if (!s)
        return fail(err, "%s: out of memory", name);
    cu_scene_defaults(s);
    snprintf(s->name, sizeof s->name, "%s", name);

    int have_sections[16] = {0};
    int ell_line[CU_MAX_ELLIPSOIDS] = {0};
    unsigned char ell_seen[CU_MAX_ELLIPSOIDS][2];
    memset(ell_seen, 0, sizeof ell_seen);
    char section[32] = "";
    int cur_ell = -1;
    seen_set seen;
    memset(&seen, 0, sizeof seen);
    char line[MAX_LINE + 1];
    size_t pos = 0;
    int lineno = 0;
    int any_content = 0;

    /* A binary file is reported as binary, wherever its first control byte sits, not as whatever syntax error its
     * first line happens to make. */
    for (size_t i = 0, ln = 1, col = 1; i < len; i++, col++) {
        unsigned char c = (unsigned char)text[i];
        if (c == '\n') {
            ln++;
            col = 0;
        } else if (c == 0 || (c < 32 && c != '\t' && c != '\r') || c == 127) {
            free(s);
            return fail(err, "%s:%d:%d: not a text file (byte 0x%02x)", name, (int)ln, (int)col, c);
        }
    }
    while (pos < len) {
        lineno++;
        size_t start = pos;
        while (pos < len && text[pos] != '\n')
            pos++;
        size_t n = pos - start;
        if (pos < len)
            pos++; /* skip '\n' */
        if (n > MAX_LINE) {
            free(s);
            return fail(err, "%s:%d:1: line is longer than %d characters", name, lineno, MAX_LINE);
        }
        memcpy(line, text + start, n);
        line[n] = 0;
        if (n && line[n - 1] == '\r')
            line[--n] = 0;
        for (size_t i = 0; i < n; i++) {
            unsigned char c = (unsigned char)line[i];
            if (c == 0 || (c < 32 && c != '\t') || c == 127) {
                free(s);
                return fail(err, "%s:%d:%d: not a text file (byte 0x%02x)", name, lineno, (int)i + 1, c);
            }
        }
        /* strip comments */
        char *hash = strpbrk(line, "#;");
        if (hash)
            *hash = 0;
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        char *e = p + strlen(p);
        while (e > p && (e[-1] == ' ' || e[-1] == '\t'))
            *--e = 0;
        if (!*p)
            continue;
        any_content = 1;
        int col = (int)(p - line) + 1;
        if (*p == '[') {
            char *close = strchr(p, ']');
            if (!close) {
                free(s);
                return fail(err, "%s:%d:%d: unterminated section header (missing ']')", name, lineno, col);
            }
            if (close[1]) {
                free(s);
                return fail(err, "%s:%d:%d: unexpected text after section header", name, lineno,
                            (int)(close + 1 - line) + 1);
            }
            *close = 0;
            const char *sec = p + 1;
            if (!is_section(sec)) {
                free(s);
                return fail(err, "%s:%d:%d: unknown section [%.40s]", name, lineno, col, sec);
            }
            int idx = 0;
            while (strcmp(sections[idx], sec) != 0)
                idx++;
            if (have_sections[idx] && strcmp(sec, "ellipsoid") != 0) {
                free(s);
                return fail(err, "%s:%d:%d: section [%s] appears twice", name, lineno, col, sec);
            }
            have_sections[idx] = 1;
            snprintf(section, sizeof section, "%s", sec);
            memset(&seen, 0, sizeof seen);
            if (strcmp(sec, "ellipsoid") == 0) {
                if (s->n_ellipsoids == CU_MAX_ELLIPSOIDS) {
                    free(s);
                    return fail(err, "%s:%d:%d: too many [ellipsoid] sections (at most %d)", name, lineno, col,
                                CU_MAX_ELLIPSOIDS);
                }
                cur_ell = s->n_ellipsoids++;
                ell_line[cur_ell] = lineno;
            }
            continue;
        }
        char *eq = strchr(p, '=');
        if (!eq) {
            free(s);
            return fail(err, "%s:%d:%d: expected 'key = value' or '[section]'", name, lineno, col);
        }
        if (!section[0]) {
            free(s);
            return fail(err, "%s:%d:%d: key outside any section", name, lineno, col);
        }
        char *kend = eq;
        while (kend > p && (kend[-1] == ' ' || kend[-1] == '\t'))
            kend--;
        *kend = 0;
        char *val = eq + 1;
        while (*val == ' ' || *val == '\t')
            val++;
        int vcol = (int)(val - line) + 1;
        const key_def *k = find_key(section, p);
        if (!k) {
            free(s);
            return fail(err, "%s:%d:%d: unknown key '%.40s' in [%s]", name, lineno, col, p, section);
        }
        int ki = (int)(k - keys);
        if (seen.seen[ki]) {
            free(s);
            return fail(err, "%s:%d:%d: duplicate key '%s' in [%s]", name, lineno, col, k->name, section);
        }
        seen.seen[ki] = 1;
        s->explicit_key[ki] = 1;
        if (!*val) {
            free(s);
            return fail(err, "%s:%d:%d: '%s' has no value", name, lineno, vcol, k->name);
        }
        where w = {name, lineno};
        if (parse_value(k, key_target(s, k, cur_ell < 0 ? 0 : cur_ell), val, w, vcol, err)) {
            free(s);
            return 1;
        }
        if (strcmp(section, "ellipsoid") == 0)
            ell_seen[cur_ell][strcmp(k->name, "center") == 0 ? 0 : 1] = 1;
        if (strcmp(section, "sun") == 0 && strcmp(k->name, "irradiance") == 0)
            s->has_sun_irradiance = 1;
    }
    if (!any_content) {
        free(s);
        return fail(err, "%s:1:1: empty scene file", name);
    }
    if (post_checks(s, name, have_sections, ell_line, (const unsigned char(*)[2])ell_seen, err) ||
        apply_preset(s, name, err)) {
        free(s);
        return 1;
    }
    *out = s;
    return 0;
}

int cu_scene_load(cu_scene **out, const char *path, cu_error *err)
{
    *out = NULL;
    FILE *f = fopen(path, "rb");
    if (!f)
        return fail(err, "%s: cannot open: %s", path, strerror(errno));
    char *buf = malloc(MAX_FILE + 1);
    if (!buf) {
        fclose(f);
        return fail(err, "%s: out of memory", path);
    }
    size_t n = fread(buf, 1, MAX_FILE + 1, f);
    int rerr = ferror(f);
    fclose(f);
    if (rerr) {
        free(buf);
        return fail(err, "%s: read error", path);
    }
    int rc = cu_scene_parse(out, path, buf, n, err);
    free(buf);
    return rc;
}

int cu_scene_set(cu_scene *s, const char *assignment, cu_error *err)
{
    char buf[512];
    if (strlen(assignment) >= sizeof buf)
        return fail(err, "--set: assignment too long");
    snprintf(buf, sizeof buf, "%s", assignment);
    char *eq = strchr(buf, '=');
    if (!eq)
        return fail(err, "--set %s: expected section.key=value", assignment);
    *eq = 0;
    char *val = eq + 1;
    while (*val == ' ')
        val++;
    char *dot = strchr(buf, '.');
    if (!dot)
        return fail(err, "--set %s: expected section.key=value", assignment);
    *dot = 0;
    const char *section = buf, *key = dot + 1;
    int ell = 0;
    if (strcmp(section, "ellipsoid") == 0) {
        /* ellipsoid.N.key, N counted from 1 in file order */
        char *end;
        long idx = strtol(key, &end, 10);
        if (end == key || *end != '.' || idx < 1 || idx > s->n_ellipsoids)
            return fail(err, "--set %s: use ellipsoid.N.key with N from 1 to %d", assignment, s->n_ellipsoids);
        ell = (int)idx - 1;
        key = end + 1;
    }
    const key_def *k = find_key(section, key);
    if (!k)
        return fail(err, "--set %s: unknown key '%s.%s'", assignment, section, key);
    where w = {"--set", 0};
    char label[600];
    snprintf(label, sizeof label, "--set %.40s.%.40s", section, key);
    w.file = label;
    int old_samples = s->sun_samples, old_slices = s->osm_slices;
    if (parse_value(k, key_target(s, k, ell), val, w, 0, err))
        return 1;
    if (s->sun_samples % 4) {
        s->sun_samples = old_samples;
        return fail(err, "--set light.sun_samples: must be a multiple of 4");
    }
    if (s->osm_slices % 4) {
        s->osm_slices = old_slices;
        return fail(err, "--set light.osm_slices: must be a multiple of 4");
    }
    if (strcmp(section, "ellipsoid") != 0)
        s->explicit_key[k - keys] = 1;
    if (strcmp(section, "quality") == 0 && strcmp(key, "preset") == 0 && apply_preset(s, "--set", err))
        return 1;
    if (strcmp(section, "sun") == 0 && strcmp(key, "irradiance") == 0)
        s->has_sun_irradiance = 1;
    return 0;
}

void cu_scene_output_size(const cu_scene *s, int *width, int *height)
{
    *width = s->width;
    *height = s->height;
}

void cu_scene_free(cu_scene *s)
{
    free(s);
}
