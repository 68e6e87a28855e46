/* src/core/scene_keys.h: the one table of scene keys (name, type, default, range, unit, doc, where it is stored) that
 * the parser, the defaults, the preset check and the documentation (build/cumulo-keys) all read. */
#ifndef CU_SCENE_KEYS_H
#define CU_SCENE_KEYS_H
#include "scene.h"
#include <stddef.h>

typedef enum cu_key_type {
    CU_KEY_NUMBER,  /* double */
    CU_KEY_INTEGER, /* int, a whole number */
    CU_KEY_ENUM,    /* int: the index of the value's name in values */
    CU_KEY_BOOL,    /* int 0/1, written as values[0] / values[1] (off / on) */
    CU_KEY_TIME,    /* char[CU_TIME_TEXT]: a UTC date and time in ISO 8601 (src/core/solar.c checks it) */
} cu_key_type;

typedef struct cu_scene_key {
    const char *section, *name;
    cu_key_type type;
    int count;                 /* numbers in the value: 1, 2 (output.size: width height) or 3 (a vector, RGB) */
    const char *const *values; /* CU_KEY_ENUM, CU_KEY_BOOL: the names, NULL-terminated */
    const char *def;           /* default in the file's syntax; NULL: none (a required key, or see doc) */
    double lo, hi;             /* numbers: legal range, inclusive */
    int lo_open;               /* 1: lo itself is excluded (the value must be > lo) */
    int multiple;              /* CU_KEY_INTEGER: the value must be a multiple of this (0: any) */
    const char *unit;          /* "" when the value has none */
    const char *doc;           /* one line of plain text */
    size_t offset;             /* where the value lives: offsetof(cu_scene, ...), or offsetof(cu_ellipsoid, ...) for
                                  keys of a repeated section */
    size_t given;              /* offsetof an int of cu_scene set to 1 when the file or --set gives the key; 0: none
                                  (offset 0 is cu_scene.name, never such a flag) */
} cu_scene_key;

typedef struct cu_scene_section {
    const char *name;
    int required; /* the file must have it */
    int repeated; /* may appear many times, each one an instance of keys (a cu_ellipsoid, a cu_scene_layer) */
    const char *doc;
    const cu_scene_key *keys; /* repeated: its table (offsets into the instance); else NULL: cu_scene_keys */
    int n_keys;
} cu_scene_section;

/* Counts are part of the declarations so that other files can size arrays by them; scene_keys.c checks them. */
#define CU_SCENE_KEY_COUNT 78
#define CU_ELLIPSOID_KEY_COUNT 2
#define CU_CLOUD_KEY_COUNT 7
#define CU_LAYER_KEY_COUNT 8
#define CU_SCENE_SECTION_COUNT 11

extern const cu_scene_key cu_scene_keys[CU_SCENE_KEY_COUNT];         /* offsets into cu_scene */
extern const cu_scene_key cu_ellipsoid_keys[CU_ELLIPSOID_KEY_COUNT]; /* offsets into cu_ellipsoid */
extern const cu_scene_key cu_cloud_keys[CU_CLOUD_KEY_COUNT];         /* a [cloud] after the first: cu_cloud_spec */
extern const cu_scene_key cu_layer_keys[CU_LAYER_KEY_COUNT];         /* offsets into cu_scene_layer */
extern const cu_scene_section cu_scene_sections[CU_SCENE_SECTION_COUNT]; /* in the order the docs list them */

/* The section called name, or NULL. */
const cu_scene_section *cu_scene_section_find(const char *name);
/* How many instances of sec the scene holds (1 for a section that is not repeated), and instance i's storage (the
 * scene itself when not repeated). */
int cu_scene_instances(const cu_scene *s, const cu_scene_section *sec);
void *cu_scene_instance(cu_scene *s, const cu_scene_section *sec, int i);
/* The key name of section (in the section's own table when it is repeated), or NULL. */
const cu_scene_key *cu_scene_key_find(const char *section, const char *name);
/* The table holding the keys of section sec (cu_scene_keys, or a repeated section's own) and its length. */
const cu_scene_key *cu_scene_section_keys(const cu_scene_section *sec, int *n);

/* Parses the value text of key k (NUL-terminated, blanks trimmed) into dst, the key's field. On failure returns 1, leaves
 * dst unchanged and fills err with a message that starts with at ("file:line:col", "--set ...") and names the key.
 * The multiple-of rule is not checked here: the parser reports it once the whole file is read. */
int cu_scene_key_parse(const cu_scene_key *k, void *dst, const char *text, const char *at, cu_error *err);

/* v as %g writes it, with more digits (up to 17) until it reads back as v, in buf: "179.0001", not "179". */
const char *cu_number_text(double v, char buf[32]);

/* How much larger than its smallest radius a scene may be: the GPU holds positions in fp32 (2^-24 relative), so a
 * point at distance L from where the chord is solved is off by 2^-24 L, which is 0.6% of r_min at L = 1e5 r_min. L is
 * the camera's distance from the cloud's centre (the ray start is moved to the cloud along the camera ray) and 4 R,
 * the longest sun-map ray (the sun plane sits at 2 R, R the cloud's bounding radius). */
#define CU_MAX_SCENE_TO_RADIUS 1e5
/* Noise texels: a position p (cloud-local, |p| <= R) reads the 64^3 tile at 8 p noise_scale / 1000 tiles, i.e.
 * 0.512 |p| noise_scale texels; fp32 keeps 1/16 texel there up to 2^20 texels: R noise_scale <= 2^20 / 0.512 m. */
#define CU_MAX_NOISE_EXTENT 2.05e6
/* The whole-scene ranges that tie keys together (the scene's size against its smallest radius, the noise scale
 * against the cloud's size): 0, or 1 with a message starting with file. */
int cu_scene_check_ranges(const cu_scene *s, const char *file, cu_error *err);

/* Writes the default of every key of keys[0..n-1] that has one into base (a cu_scene or a cu_ellipsoid). */
void cu_scene_keys_defaults(void *base, const cu_scene_key *keys, int n);
#endif
