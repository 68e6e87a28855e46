/* src/core/scene_parse.c: parses INI-style scene files and --set overrides into a cu_scene through the key table
 * (scene_keys.c), rejecting bad input with file:line:column messages that name the field. */
#include "scene.h"
#include "error.h"
#include "presets.h"
#include "scene_keys.h"
#include "scene_sun.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LINE 4096
#define MAX_FILE (4 << 20)

void cu_scene_defaults(cu_scene *s)
{
    memset(s, 0, sizeof *s);
    cu_scene_keys_defaults(s, cu_scene_keys, CU_SCENE_KEY_COUNT);
}

double cu_scene_extinction_at(const cu_scene *s, double density_cm3)
{
    double rho = density_cm3 * 1e6;             /* m^-3 */
    double re = s->droplet_radius_um * 1e-6;    /* m */
    return rho * 2.0 * 3.14159265358979323846 * re * re;
}

double cu_scene_core_extinction(const cu_scene *s)
{
    return cu_scene_extinction_at(s, s->density_cm3);
}

int cu_scene_cloud_count(const cu_scene *s)
{
    return s->n_clouds > 0 ? s->n_clouds : s->n_ellipsoids > 0;
}

cu_cloud_spec cu_scene_cloud(const cu_scene *s, int i)
{
    cu_cloud_spec c = s->clouds[i];
    if (s->n_clouds == 0) { /* a scene built in code, not parsed: its ellipsoids are one cloud */
        memset(&c, 0, sizeof c);
        c.count = s->n_ellipsoids > CU_MAX_ELLIPSOIDS ? CU_MAX_ELLIPSOIDS : s->n_ellipsoids;
    }
    if (!c.has_density)
        c.density_cm3 = s->density_cm3;
    if (!c.has_boundary)
        c.boundary_m = s->boundary_m;
    if (!c.has_wind)
        memcpy(c.wind, s->cloud_wind, sizeof c.wind);
    if (!c.has_noise_offset) {
        /* A different part of the noise for each cloud, so written clouds of one shape do not look alike: steps of
         * an irrational fraction of the 1000 m tile, far from its period. */
        for (int a = 0; a < 3; a++)
            c.noise_offset[a] = s->cloud_noise_offset[a] + i * 1000.0 * (a == 0 ? 0.6180339887 : a == 1 ? 0.4142135624
                                                                                                        : 0.7320508076);
    }
    if (!c.has_lifetime)
        c.lifetime = s->cloud_lifetime;
    if (!c.has_life_phase)
        c.life_phase = s->cloud_life_phase;
    if (!c.has_wrap)
        c.wrap = s->cloud_wrap;
    return c;
}

/* The int a key of cu_scene_keys writes, for the multiple-of rule. */
static int int_field(const cu_scene *s, const cu_scene_key *k)
{
    return *(const int *)((const char *)s + k->offset);
}

/* Records that the file or --set gave k: presets leave it alone, and a key with a "given" flag sets it. */
static void mark_given(cu_scene *s, const cu_scene_key *k)
{
    s->explicit_key[k - cu_scene_keys] = 1;
    if (k->given)
        *(int *)((char *)s + k->given) = 1;
}

/* What the parser remembers about the file beyond the scene itself. */
typedef struct file_state {
    int have_section[CU_SCENE_SECTION_COUNT];
    int ell_line[CU_MAX_SCENE_ELLIPSOIDS];     /* line of each [ellipsoid] header */
    unsigned ell_seen[CU_MAX_SCENE_ELLIPSOIDS];/* bit i: cu_ellipsoid_keys[i] given */
    unsigned char seen[CU_SCENE_KEY_COUNT];    /* by index in the section's table: keys given in this instance */
    int cloud_headers;                         /* [cloud] headers so far: the second and later start a cloud */
} file_state;
typedef char ell_keys_fit[CU_ELLIPSOID_KEY_COUNT <= 32 && CU_ELLIPSOID_KEY_COUNT <= CU_SCENE_KEY_COUNT &&
                          CU_LAYER_KEY_COUNT <= CU_SCENE_KEY_COUNT && CU_CLOUD_KEY_COUNT <= CU_SCENE_KEY_COUNT ? 1 : -1];

/* Keys a later [cloud] may not give: they belong to every cloud (the phase table, the noise's scale). */
static int shared_cloud_key(const char *name)
{
    for (int i = 0; i < CU_CLOUD_KEY_COUNT; i++)
        if (strcmp(cu_cloud_keys[i].name, name) == 0)
            return 0;
    return 1;
}

/* Ends the file's cloud list: each cloud's ellipsoid count, empty clouds refused (the first may be empty when it
 * only sets the defaults, or when the sky is clear). */
static int finish_clouds(cu_scene *s, const char *file, const file_state *fs, cu_error *err)
{
    int n = fs->cloud_headers > 1 ? fs->cloud_headers : 1;
    for (int i = 0; i < n; i++)
        s->clouds[i].count = (i + 1 < n ? s->clouds[i + 1].first : s->n_ellipsoids) - s->clouds[i].first;
    for (int i = 1; i < n; i++)
        if (s->clouds[i].count == 0)
            return cu_fail(err, "%s:%d:1: [cloud] #%d has no [ellipsoid]", file, s->clouds[i].line, i + 1);
    for (int i = 0; i < n; i++)
        if (s->clouds[i].count > CU_MAX_ELLIPSOIDS)
            return cu_fail(err, "%s:%d:1: [cloud] #%d has %d ellipsoids; a cloud has at most %d (start another "
                                "[cloud])", file, s->clouds[i].line ? s->clouds[i].line : fs->ell_line[s->clouds[i].first],
                           i + 1, s->clouds[i].count, CU_MAX_ELLIPSOIDS);
    if (s->clouds[0].count == 0) { /* a settings-only first [cloud], or a clear sky */
        memmove(&s->clouds[0], &s->clouds[1], sizeof s->clouds[0] * (size_t)(n - 1));
        n--;
    }
    s->n_clouds = n;
    return 0;
}

/* The checks that span keys or need the whole scene: run after the file and after every --set, so both reject the
 * same scenes. `at` names where the values came from (the file, or the --set). */
static int scene_checks(const cu_scene *s, const char *at, cu_error *err)
{
    for (int i = 0; i < CU_SCENE_KEY_COUNT; i++) {
        const cu_scene_key *k = &cu_scene_keys[i];
        if (k->multiple && int_field(s, k) % k->multiple)
            return cu_fail(err, "%s: [%s] '%s' must be a multiple of %d, got %d", at, k->section, k->name,
                           k->multiple, int_field(s, k));
    }
    double dx = s->cam_look[0] - s->cam_pos[0], dy = s->cam_look[1] - s->cam_pos[1], dz = s->cam_look[2] - s->cam_pos[2];
    if (dx * dx + dy * dy + dz * dz < 1e-12)
        return cu_fail(err, "%s: [camera] 'look_at' equals 'position'; the view direction is undefined", at);
    if (s->has_time_utc && (s->explicit_key[cu_scene_key_find("sun", "elevation") - cu_scene_keys] ||
                            s->explicit_key[cu_scene_key_find("sun", "azimuth") - cu_scene_keys]))
        return cu_fail(err, "%s: [sun] gives time_utc and elevation or azimuth; the time and place decide the angles",
                       at);
    double el, az;
    cu_error e2;
    if (cu_scene_sun_at(s, s->time, &el, &az, &e2))
        return cu_fail(err, "%s: %.400s", at, e2.msg);
    return cu_scene_check_ranges(s, at, err);
}

/* What only a whole file can lack: its required sections and each ellipsoid's required keys. */
static int file_checks(cu_scene *s, const char *file, const file_state *fs, cu_error *err)
{
    for (int i = 0; i < CU_SCENE_SECTION_COUNT; i++)
        if (cu_scene_sections[i].required && !cu_scene_sections[i].repeated && !fs->have_section[i])
            return cu_fail(err, "%s: missing section [%s]", file, cu_scene_sections[i].name);
    if (finish_clouds(s, file, fs, err))
        return 1;
    for (int e = 0; e < s->n_ellipsoids; e++)
        for (int i = 0; i < CU_ELLIPSOID_KEY_COUNT; i++)
            if (!cu_ellipsoid_keys[i].def && !(fs->ell_seen[e] >> i & 1))
                return cu_fail(err, "%s:%d:1: [ellipsoid] #%d has no '%s'", file, fs->ell_line[e], e + 1,
                               cu_ellipsoid_keys[i].name);
    return scene_checks(s, file, err);
}

/* Applies the scene's quality preset to every key it lists that the file (or an earlier --set) did not set itself:
 * explicit keys win wherever they appear. */
static int apply_preset(cu_scene *s, const char *file, cu_error *err)
{
    const char *preset = cu_scene_key_find("quality", "preset")->values[s->preset];
    char list[2048];
    snprintf(list, sizeof list, "%s", cu_preset_settings((cu_preset)s->preset));
    char *save = NULL;
    for (char *item = strtok_r(list, ";", &save); item; item = strtok_r(NULL, ";", &save)) {
        char *eq = strchr(item, '='), *dot = strchr(item, '.');
        if (!eq || !dot || dot > eq)
            return cu_fail(err, "%s: preset '%s': malformed entry '%s'", file, preset, item);
        *eq = *dot = 0;
        const cu_scene_section *sec = cu_scene_section_find(item);
        const cu_scene_key *k = sec && !sec->repeated ? cu_scene_key_find(item, dot + 1) : NULL;
        if (!k)
            return cu_fail(err, "%s: preset '%s': unknown key '%s.%s'", file, preset, item, dot + 1);
        if (s->explicit_key[k - cu_scene_keys])
            continue;
        if (cu_scene_key_parse(k, (char *)s + k->offset, eq + 1, "preset", err))
            return 1;
    }
    return 0;
}

/* One "[section]" header (p at '[', col its column). */
static int parse_header(cu_scene *s, file_state *fs, const cu_scene_section **cur, char *p, const char *line,
                        const char *name, int lineno, int col, cu_error *err)
{
    char *close = strchr(p, ']');
    if (!close)
        return cu_fail(err, "%s:%d:%d: unterminated section header (missing ']')", name, lineno, col);
    if (close[1])
        return cu_fail(err, "%s:%d:%d: unexpected text after section header", name, lineno, (int)(close + 1 - line) + 1);
    *close = 0;
    const cu_scene_section *sec = cu_scene_section_find(p + 1);
    if (!sec)
        return cu_fail(err, "%s:%d:%d: unknown section [%.40s]", name, lineno, col, p + 1);
    int idx = (int)(sec - cu_scene_sections);
    int is_cloud = strcmp(sec->name, "cloud") == 0;
    if (fs->have_section[idx] && !sec->repeated && !is_cloud)
        return cu_fail(err, "%s:%d:%d: section [%s] appears twice", name, lineno, col, sec->name);
    fs->have_section[idx] = 1;
    *cur = sec;
    memset(fs->seen, 0, sizeof fs->seen);
    if (is_cloud) {
        int c = fs->cloud_headers++; /* the first [cloud] is cloud 1's (and every cloud's defaults) */
        if (c >= CU_MAX_CLOUDS)
            return cu_fail(err, "%s:%d:%d: too many [cloud] sections (at most %d; a [layer] generates any number)",
                           name, lineno, col, CU_MAX_CLOUDS);
        if (c > 0) {
            memset(&s->clouds[c], 0, sizeof s->clouds[c]);
            s->clouds[c].first = s->n_ellipsoids;
        }
        s->clouds[c].line = lineno;
    } else if (sec->keys == cu_layer_keys) {
        if (s->n_layers == CU_MAX_LAYERS)
            return cu_fail(err, "%s:%d:%d: too many [layer] sections (at most %d)", name, lineno, col, CU_MAX_LAYERS);
        cu_scene_keys_defaults(&s->layers[s->n_layers], cu_layer_keys, CU_LAYER_KEY_COUNT);
        s->layers[s->n_layers++].line = lineno;
    } else if (sec->repeated) {
        if (s->n_ellipsoids == CU_MAX_SCENE_ELLIPSOIDS)
            return cu_fail(err, "%s:%d:%d: too many [ellipsoid] sections (at most %d in a file)", name, lineno, col,
                           CU_MAX_SCENE_ELLIPSOIDS);
        fs->ell_line[s->n_ellipsoids] = lineno;
        cu_scene_keys_defaults(&s->ell[s->n_ellipsoids++], cu_ellipsoid_keys, CU_ELLIPSOID_KEY_COUNT);
    }
    return 0;
}

/* One "key = value" line of section sec (p at the key, col its column). */
static int parse_assignment(cu_scene *s, file_state *fs, const cu_scene_section *sec, char *p, const char *line,
                            const char *name, int lineno, int col, cu_error *err)
{
    char *eq = strchr(p, '=');
    if (!eq)
        return cu_fail(err, "%s:%d:%d: expected 'key = value' or '[section]'", name, lineno, col);
    if (!sec)
        return cu_fail(err, "%s:%d:%d: key outside any section", name, lineno, col);
    char *kend = eq;
    while (kend > p && (kend[-1] == ' ' || kend[-1] == '\t'))
        kend--;
    *kend = 0;
    char *val = eq + 1;
    while (*val == ' ' || *val == '\t')
        val++;
    int vcol = (int)(val - line) + 1;
    const cu_scene_key *k = cu_scene_key_find(sec->name, p);
    if (!k)
        return cu_fail(err, "%s:%d:%d: unknown key '%.40s' in [%s]", name, lineno, col, p, sec->name);
    int n, ki = (int)(k - cu_scene_section_keys(sec, &n));
    if (fs->seen[ki])
        return cu_fail(err, "%s:%d:%d: duplicate key '%s' in [%s]", name, lineno, col, k->name, sec->name);
    fs->seen[ki] = 1;
    if (!*val)
        return cu_fail(err, "%s:%d:%d: '%s' has no value", name, lineno, vcol, k->name);
    char at[700];
    snprintf(at, sizeof at, "%s:%d:%d", name, lineno, vcol);
    int later_cloud = strcmp(sec->name, "cloud") == 0 && fs->cloud_headers > 1;
    if (later_cloud) { /* a cloud of its own: its table, into its spec */
        if (shared_cloud_key(k->name))
            return cu_fail(err, "%s:%d:%d: '%s' is shared by every cloud: set it in the first [cloud] section", name,
                           lineno, col, k->name);
        cu_cloud_spec *c = &s->clouds[fs->cloud_headers - 1];
        const cu_scene_key *ck = NULL;
        for (int i = 0; i < CU_CLOUD_KEY_COUNT; i++)
            if (strcmp(cu_cloud_keys[i].name, k->name) == 0)
                ck = &cu_cloud_keys[i];
        if (cu_scene_key_parse(ck, (char *)c + ck->offset, val, at, err))
            return 1;
        *(int *)((char *)c + ck->given) = 1;
        return 0;
    }
    int inst = cu_scene_instances(s, sec) - 1;
    void *base = cu_scene_instance(s, sec, inst);
    if (cu_scene_key_parse(k, (char *)base + k->offset, val, at, err))
        return 1;
    if (sec->repeated && sec->keys == cu_ellipsoid_keys)
        fs->ell_seen[inst] |= 1u << ki;
    else if (!sec->repeated)
        mark_given(s, k);
    return 0;
}

/* Rejects a binary file as binary, wherever its first control byte sits, not as whatever syntax error its first
 * line happens to make. */
static int check_text(const char *name, const char *text, size_t len, cu_error *err)
{
    for (size_t i = 0, ln = 1, col = 1; i < len; i++, col++) {
        unsigned char c = (unsigned char)text[i];
        if (c == '\n') {
            ln++;
            col = 0;
        } else if (c == 0 || (c < 32 && c != '\t' && c != '\r') || c == 127) {
            return cu_fail(err, "%s:%d:%d: not a text file (byte 0x%02x)", name, (int)ln, (int)col, c);
        }
    }
    return 0;
}

static int parse_lines(cu_scene *s, file_state *fs, const char *name, const char *text, size_t len, cu_error *err)
{
    const cu_scene_section *sec = NULL;
    char line[MAX_LINE + 1];
    size_t pos = 0;
    int lineno = 0, any_content = 0;
    while (pos < len) {
        lineno++;
        size_t start = pos;
        while (pos < len && text[pos] != '\n')
            pos++;
        size_t n = pos - start;
        if (pos < len)
            pos++; /* skip '\n' */
        if (n > MAX_LINE)
            return cu_fail(err, "%s:%d:1: line is longer than %d characters", name, lineno, MAX_LINE);
        memcpy(line, text + start, n);
        line[n] = 0;
        if (n && line[n - 1] == '\r')
            line[--n] = 0;
        for (size_t i = 0; i < n; i++) {
            unsigned char c = (unsigned char)line[i];
            if (c == 0 || (c < 32 && c != '\t') || c == 127)
                return cu_fail(err, "%s:%d:%d: not a text file (byte 0x%02x)", name, lineno, (int)i + 1, c);
        }
        char *hash = strpbrk(line, "#;"); /* comments */
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
        if (*p == '[' ? parse_header(s, fs, &sec, p, line, name, lineno, col, err)
                      : parse_assignment(s, fs, sec, p, line, name, lineno, col, err))
            return 1;
    }
    if (!any_content)
        return cu_fail(err, "%s:1:1: empty scene file", name);
    return 0;
}

int cu_scene_parse(cu_scene **out, const char *name, const char *text, size_t len, cu_error *err)
{
    *out = NULL;
    if (len > MAX_FILE)
        return cu_fail(err, "%s: file is larger than %d bytes", name, MAX_FILE);
    if (check_text(name, text, len, err))
        return 1;
    cu_scene *s = malloc(sizeof *s);
    file_state *fs = calloc(1, sizeof *fs);
    if (!s || !fs) {
        free(s);
        free(fs);
        return cu_fail(err, "%s: out of memory", name);
    }
    cu_scene_defaults(s);
    snprintf(s->name, sizeof s->name, "%s", name);
    /* A UTF-8 byte-order mark (what some Windows editors write first) is not part of the text. */
    size_t bom = len >= 3 && !memcmp(text, "\xef\xbb\xbf", 3) ? 3 : 0;
    int rc = parse_lines(s, fs, name, text + bom, len - bom, err) || file_checks(s, name, fs, err) || apply_preset(s, name, err);
    free(fs);
    if (rc) {
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
        return cu_fail(err, "%s: cannot open: %s", path, strerror(errno));
    char *buf = malloc(MAX_FILE + 1);
    if (!buf) {
        fclose(f);
        return cu_fail(err, "%s: out of memory", path);
    }
    size_t n = fread(buf, 1, MAX_FILE + 1, f);
    int rerr = ferror(f);
    fclose(f);
    if (rerr) {
        free(buf);
        return cu_fail(err, "%s: read error", path);
    }
    int rc = cu_scene_parse(out, path, buf, n, err);
    free(buf);
    return rc;
}

/* One --set on s as given: the key's own checks only (cu_scene_set adds the whole-scene ones). */
static int set_key(cu_scene *s, const char *assignment, cu_error *err)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", assignment);
    char *eq = strchr(buf, '=');
    if (!eq)
        return cu_fail(err, "--set %s: expected section.key=value", assignment);
    *eq = 0;
    char *val = eq + 1;
    while (*val == ' ')
        val++;
    char *dot = strchr(buf, '.');
    if (!dot)
        return cu_fail(err, "--set %s: expected section.key=value", assignment);
    *dot = 0;
    const char *section = buf, *key = dot + 1;
    const cu_scene_section *sec = cu_scene_section_find(section);
    void *base = s;
    if (sec && sec->repeated) {
        /* ellipsoid.N.key, layer.N.key: N counted from 1 in file order */
        char *end;
        long idx = strtol(key, &end, 10);
        int count = cu_scene_instances(s, sec);
        if (end == key || *end != '.' || idx < 1 || idx > count)
            return cu_fail(err, "--set %s: use %s.N.key with N from 1 to %d", assignment, sec->name, count);
        base = cu_scene_instance(s, sec, (int)idx - 1);
        key = end + 1;
    }
    const cu_scene_key *k = cu_scene_key_find(section, key);
    if (!k)
        return cu_fail(err, "--set %s: unknown key '%s.%s'", assignment, section, key);
    char label[600];
    snprintf(label, sizeof label, "--set %.40s.%.40s", section, key);
    if (cu_scene_key_parse(k, (char *)base + k->offset, val, label, err))
        return 1;
    if (!sec->repeated) {
        mark_given(s, k);
        if (k == cu_scene_key_find("quality", "preset") && apply_preset(s, "--set", err))
            return 1;
    }
    return scene_checks(s, label, err);
}

int cu_scene_set(cu_scene *s, const char *assignment, cu_error *err)
{
    if (strlen(assignment) >= 512)
        return cu_fail(err, "--set: assignment too long");
    /* Control bytes are never part of a key or a value; naming them here keeps every later message free of them. */
    for (const unsigned char *p = (const unsigned char *)assignment; *p; p++)
        if (*p < 32 || *p == 127) {
            char shown[4 * 512 + 1];
            return cu_fail(err, "--set %s: control byte 0x%02x", cu_escape(shown, sizeof shown, assignment), *p);
        }
    /* All or nothing: a rejected --set, whichever check rejects it, leaves the scene as it was. */
    cu_scene *old = malloc(sizeof *old);
    if (!old)
        return cu_fail(err, "--set: out of memory");
    memcpy(old, s, sizeof *s);
    int rc = set_key(s, assignment, err);
    if (rc)
        memcpy(s, old, sizeof *s);
    free(old);
    return rc;
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
