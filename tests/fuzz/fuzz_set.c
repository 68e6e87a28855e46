/* tests/fuzz/fuzz_set.c: libFuzzer target for --set assignments (cu_scene_set) on a parsed scene, one per line. */
#include "fuzz.h"
#include "scene_check.h"

/* Two ellipsoids, so that ellipsoid.N.key has more than one N to reach. */
static const char base_scene[] =
    "[output]\nsize = 64 48\n[camera]\nposition = 0 150 -1200\nlook_at = 0 330 0\n[sun]\nelevation = 30\n"
    "[cloud]\nphase = hg\n[ellipsoid]\ncenter = 0 250 0\nradii = 200 120 160\n[ellipsoid]\ncenter = 150 230 40\n"
    "radii = 140 100 120\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 8192)
        return 0;
    cu_scene *s;
    cu_error err = {""};
    FUZZ_CHECK(!cu_scene_parse(&s, "base", base_scene, sizeof base_scene - 1, &err), "base scene: %s", err.msg);
    char *text = malloc(size + 1), *save = NULL;
    cu_scene *before = malloc(sizeof *before);
    FUZZ_CHECK(text && before, "out of memory");
    memcpy(text, data, size);
    text[size] = 0;
    int n = 0, accepted = 0;
    for (char *line = strtok_r(text, "\n", &save); line && n < 32; line = strtok_r(NULL, "\n", &save), n++) {
        memcpy(before, s, sizeof *s);
        memset(&err, 0x55, sizeof err);
        if (cu_scene_set(s, line, &err)) {
            FUZZ_CHECK_MESSAGE(err.msg, "--set");
            FUZZ_CHECK(!memcmp(before, s, sizeof *s), "a refused '%s' changed the scene", line);
            continue;
        }
        fuzz_scene_check(s);
        accepted++;
    }
    /* One validation path: what --set accepts, the same scene as a file must be accepted too (once per input: a
     * parse of the whole scene costs more than all the assignments). */
    char why[sizeof err.msg];
    FUZZ_CHECK(!accepted || fuzz_scene_roundtrip(s, why, sizeof why),
               "after the --set lines the scene as a file is refused: %s", why);
    free(before);
    free(text);
    cu_scene_free(s);
    return 0;
}
