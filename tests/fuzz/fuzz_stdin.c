/* tests/fuzz/fuzz_stdin.c: libFuzzer target for `cumulo run`'s stdin commands: the line splitter and the parser. */
#include "fuzz.h"
#include "stdin_input.h"
#include <math.h>

static void on_line(void *user, const char *line)
{
    (void)user;
    size_t len = strlen(line);
    FUZZ_CHECK(len < CU_STDIN_LINE_MAX, "a line of %zu bytes", len);
    FUZZ_CHECK(!strchr(line, '\n'), "a line with its newline");
    if (!strcmp(line, CU_STDIN_OVERLONG))
        return;
    cu_action a;
    char err[256] = "";
    if (cu_stdin_parse(line, &a, err, sizeof err)) {
        FUZZ_CHECK_MESSAGE(err, "stdin: ");
        /* what the user typed comes back in the message: no byte of it may reach the terminal as a control */
        for (const char *p = err; *p; p++)
            FUZZ_CHECK((unsigned char)*p >= 0x20 && (unsigned char)*p < 0x7f, "byte 0x%02x in '%s'",
                       (unsigned char)*p, err);
        return;
    }
    switch (a.kind) {
    case CU_ACT_NONE:
        FUZZ_CHECK(line[strspn(line, " \t\r")] == 0 || line[strspn(line, " \t\r")] == '#', "no action from '%s'", line);
        break;
    case CU_ACT_SET_SUN: case CU_ACT_SET_EL: case CU_ACT_SET_AZ:
        FUZZ_CHECK(isfinite(a.el) && a.el >= -90 && a.el <= 90, "elevation %.17g", a.el);
        FUZZ_CHECK(isfinite(a.az) && fabs(a.az) <= 1e6, "azimuth %.17g", a.az);
        break;
    case CU_ACT_TURN:
        FUZZ_CHECK(a.detents >= -10000 && a.detents <= 10000, "%d detents", a.detents);
        break;
    case CU_ACT_SET_OFFSET: /* --clock's `offset MINUTES` */
        FUZZ_CHECK(isfinite(a.minutes) && fabs(a.minutes) <= CU_OFFSET_MAX_MIN, "offset %.17g min", a.minutes);
        break;
    case CU_ACT_TOGGLE: case CU_ACT_STATUS: case CU_ACT_QUIT:
        break;
    default:
        FUZZ_CHECK(0, "action kind %d from '%s'", (int)a.kind, line);
    }
}

/* The first byte sets how the rest arrives in read()s (1 to 64 bytes at a time): a line split across reads must
 * parse as the whole line does. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    size_t chunk = data[0] % 64 + 1;
    data++, size--;
    cu_stdin s;
    cu_stdin_init(&s, -1);
    for (size_t i = 0; i < size; i += chunk)
        cu_stdin_feed(&s, (const char *)data + i, size - i < chunk ? size - i : chunk, on_line, NULL);
    FUZZ_CHECK(s.len < CU_STDIN_LINE_MAX, "buffered %zu bytes", s.len);
    if (s.len && !s.overlong) { /* the last line without a newline, as cu_stdin_read hands it out at end of file */
        s.buf[s.len] = 0;
        on_line(NULL, s.buf);
    }
    return 0;
}
