/* tests/fuzz/fuzz_scene.c: libFuzzer target for the scene file parser (cu_scene_parse): a clear error or a scene
 * whose every value is legal and that reads back the same when written out. */
#include "fuzz.h"
#include "scene_check.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cu_scene *s = (cu_scene *)1;
    cu_error err;
    memset(&err, 0x55, sizeof err); /* a parser that forgets the message leaves no NUL to find */
    if (cu_scene_parse(&s, "fuzz.scene", (const char *)data, size, &err)) {
        FUZZ_CHECK(s == NULL, "a failed parse left a scene");
        FUZZ_CHECK_MESSAGE(err.msg, "fuzz.scene");
        return 0;
    }
    FUZZ_CHECK(s != NULL, "no scene and no error");
    fuzz_scene_check(s);
    char why[sizeof err.msg];
    FUZZ_CHECK(fuzz_scene_roundtrip(s, why, sizeof why), "the scene written out is refused: %s", why);
    cu_scene_free(s);
    return 0;
}
