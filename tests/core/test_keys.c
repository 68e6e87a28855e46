/* tests/core/test_keys.c: the scene key table (src/core/scene_keys.c) is consistent, its defaults are legal values, and
 * every quality preset (src/core/presets.c) names keys of the table with values in their ranges. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <string.h>
#include "presets.h"
#include "scene_keys.h"

static cu_scene scratch; /* large: off the stack */

/* Every key: a known section, a unique name, a type that matches its fields, a field inside its struct. */
static void check_keys(const cu_scene_key *keys, int n, size_t struct_size, int repeated)
{
    for (int i = 0; i < n; i++) {
        const cu_scene_key *k = &keys[i];
        const cu_scene_section *sec = cu_scene_section_find(k->section);
        if (!sec || sec->repeated != repeated)
            fail_msg("%s.%s: section not in cu_scene_sections, or in the wrong table", k->section, k->name);
        assert_ptr_equal(cu_scene_key_find(k->section, k->name), k); /* unique */
        assert_true(k->count >= 1 && k->count <= 3);
        int named = k->type == CU_KEY_ENUM || k->type == CU_KEY_BOOL;
        if (named != (k->values != NULL) || (named && k->count != 1))
            fail_msg("%s.%s: names given iff the type is enum or bool", k->section, k->name);
        if (k->type == CU_KEY_BOOL)
            assert_true(strcmp(k->values[0], "off") == 0 && strcmp(k->values[1], "on") == 0 && !k->values[2]);
        if (!named && !(k->lo <= k->hi))
            fail_msg("%s.%s: empty range", k->section, k->name);
        assert_true(k->multiple == 0 || k->type == CU_KEY_INTEGER);
        size_t size = k->type == CU_KEY_TIME ? CU_TIME_TEXT
                      : (size_t)k->count * (k->type == CU_KEY_NUMBER ? sizeof(double) : sizeof(int));
        assert_true(k->offset + size <= struct_size);
        assert_true(k->unit != NULL && k->doc != NULL && k->doc[0]);
        assert_true(k->given == 0 || (!repeated && k->given + sizeof(int) <= sizeof(cu_scene)));
    }
}

static void test_table_consistent(void **st)
{
    (void)st;
    check_keys(cu_scene_keys, CU_SCENE_KEY_COUNT, sizeof(cu_scene), 0);
    check_keys(cu_ellipsoid_keys, CU_ELLIPSOID_KEY_COUNT, sizeof(cu_ellipsoid), 1);
    for (int s = 0; s < CU_SCENE_SECTION_COUNT; s++) {
        int n, have = 0;
        const cu_scene_key *keys = cu_scene_section_keys(&cu_scene_sections[s], &n);
        for (int i = 0; i < n; i++)
            have += strcmp(keys[i].section, cu_scene_sections[s].name) == 0;
        if (!have)
            fail_msg("[%s] has no keys", cu_scene_sections[s].name);
        assert_ptr_equal(cu_scene_section_find(cu_scene_sections[s].name), &cu_scene_sections[s]);
    }
    /* the preset key's names are cu_preset's */
    const cu_scene_key *p = cu_scene_key_find("quality", "preset");
    assert_non_null(p);
    int n = 0;
    while (p->values[n])
        n++;
    assert_int_equal(n, CU_PRESET_COUNT);
}

/* Parses a value of k into the scratch scene as the parser would, and checks the multiple-of rule too. */
static int legal(const cu_scene_key *k, const char *value, cu_error *e)
{
    cu_scene_defaults(&scratch);
    char *base = cu_scene_section_find(k->section)->repeated ? (char *)&scratch.ell[0] : (char *)&scratch;
    void *dst = base + k->offset;
    if (cu_scene_key_parse(k, dst, value, "value", e))
        return 0;
    if (k->multiple && *(int *)dst % k->multiple) {
        snprintf(e->msg, sizeof e->msg, "not a multiple of %d", k->multiple);
        return 0;
    }
    return 1;
}

static void test_defaults_legal(void **st)
{
    (void)st;
    cu_error e;
    for (int t = 0; t < 2; t++) {
        const cu_scene_key *keys = t ? cu_ellipsoid_keys : cu_scene_keys;
        int n = t ? CU_ELLIPSOID_KEY_COUNT : CU_SCENE_KEY_COUNT;
        for (int i = 0; i < n; i++)
            if (keys[i].def && !legal(&keys[i], keys[i].def, &e))
                fail_msg("default of %s.%s: %s", keys[i].section, keys[i].name, e.msg);
    }
    /* a key without a default is one the file must give, or one with a "given" flag */
    for (int i = 0; i < CU_SCENE_KEY_COUNT; i++)
        if (!cu_scene_keys[i].def && !cu_scene_keys[i].given)
            fail_msg("%s.%s: no default and no given flag", cu_scene_keys[i].section, cu_scene_keys[i].name);
}

static const char *preset_name(cu_preset p)
{
    return cu_scene_key_find("quality", "preset")->values[p];
}

/* Calls f on every "section.key=value" entry of preset p. */
static void each_entry(cu_preset p, void (*f)(cu_preset, const cu_scene_key *, const char *, const char *))
{
    char list[2048];
    assert_true(strlen(cu_preset_settings(p)) < sizeof list);
    snprintf(list, sizeof list, "%s", cu_preset_settings(p));
    char *save = NULL;
    for (char *item = strtok_r(list, ";", &save); item; item = strtok_r(NULL, ";", &save)) {
        char *eq = strchr(item, '='), *dot = strchr(item, '.');
        if (!eq || !dot || dot > eq)
            fail_msg("preset %s: malformed entry '%s'", preset_name(p), item);
        *eq = *dot = 0;
        const cu_scene_section *sec = cu_scene_section_find(item);
        const cu_scene_key *k = sec && !sec->repeated ? cu_scene_key_find(item, dot + 1) : NULL;
        if (!k)
            fail_msg("preset %s: '%s.%s' is not a key of the table", preset_name(p), item, dot + 1);
        f(p, k, item, eq + 1);
    }
}

static unsigned char listed[CU_PRESET_COUNT][CU_SCENE_KEY_COUNT];

static void check_entry(cu_preset p, const cu_scene_key *k, const char *section, const char *value)
{
    cu_error e;
    if (!legal(k, value, &e))
        fail_msg("preset %s: %s.%s=%s: %s", preset_name(p), section, k->name, value, e.msg);
    if (listed[p][k - cu_scene_keys]++)
        fail_msg("preset %s lists %s.%s twice", preset_name(p), section, k->name);
}

static void test_presets_in_table(void **st)
{
    (void)st;
    memset(listed, 0, sizeof listed);
    for (int p = 0; p < CU_PRESET_COUNT; p++)
        each_entry((cu_preset)p, check_entry);
    /* every preset lists the same keys, so switching presets leaves none of another's values behind */
    for (int p = 1; p < CU_PRESET_COUNT; p++)
        assert_memory_equal(listed[p], listed[0], sizeof listed[0]);
}

static cu_scene applied;

static void apply_entry(cu_preset p, const cu_scene_key *k, const char *section, const char *value)
{
    cu_error e;
    if (cu_scene_key_parse(k, (char *)&applied + k->offset, value, section, &e))
        fail_msg("preset %s: %s", preset_name(p), e.msg);
}

/* high is the defaults: applying it to a default scene changes no byte. */
static void test_high_is_defaults(void **st)
{
    (void)st;
    static cu_scene d;
    cu_scene_defaults(&d);
    cu_scene_defaults(&applied);
    each_entry(CU_PRESET_HIGH, apply_entry);
    assert_memory_equal(&applied, &d, sizeof d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table_consistent), cmocka_unit_test(test_defaults_legal),
        cmocka_unit_test(test_presets_in_table), cmocka_unit_test(test_high_is_defaults),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
