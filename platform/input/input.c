/* platform/input/input.c: parsing of `--input` specifications (gpio:, evdev:, stdin) into cu_input_spec; pure. */
#include "input.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int copy_value(char *dst, size_t cap, const char *v, size_t n, const char *key, const char *spec,
                      char *err, size_t errlen)
{
    if (n == 0) {
        snprintf(err, errlen, "--input '%s': '%s=' needs a value", spec, key);
        return 1;
    }
    if (n >= cap) {
        snprintf(err, errlen, "--input '%s': value of '%s' is longer than %zu characters", spec, key, cap - 1);
        return 1;
    }
    memcpy(dst, v, n);
    dst[n] = '\0';
    return 0;
}

/* The n characters at v as a decimal integer in [lo, hi] (lo >= 0): 0, or 1 for anything else. Digits only, since
 * strtol takes a sign and leading blanks; its ERANGE is an error. Every number of the --input grammar reads here. */
static int parse_int(const char *v, size_t n, long lo, long hi, long *out)
{
    char buf[32];
    char *end;
    if (n == 0 || n >= sizeof buf || *v < '0' || *v > '9')
        return 1;
    memcpy(buf, v, n);
    buf[n] = '\0';
    errno = 0;
    long x = strtol(buf, &end, 10);
    if (*end || errno == ERANGE || x < lo || x > hi)
        return 1;
    *out = x;
    return 0;
}

void cu_input_escape(char *dst, size_t n, const char *src, const char *keep)
{
    if (!n)
        return;
    size_t o = 0;
    for (const unsigned char *p = (const unsigned char *)src; *p; p++) {
        int plain = (*p >= 32 && *p != 127) || strchr(keep, *p);
        size_t need = plain ? 1 : 4;
        if (o + need >= n)
            break;
        if (plain)
            dst[o] = (char)*p;
        else
            snprintf(dst + o, 5, "\\x%02x", *p);
        o += need;
    }
    dst[o] = 0;
}

int cu_input_line_offset(const char *s)
{
    long x;
    return s && !parse_int(s, strlen(s), 0, 65535, &x) ? (int)x : -1;
}

static int parse_gpio(const char *spec, const char *p, cu_input_spec *o, char *err, size_t errlen)
{
    strcpy(o->chip, "gpiochip0");
    o->debounce_us = -1;
    while (*p) {
        const char *comma = strchr(p, ',');
        size_t len = comma ? (size_t)(comma - p) : strlen(p);
        const char *eq = memchr(p, '=', len);
        if (!eq) {
            snprintf(err, errlen, "--input '%s': expected key=value, got '%.*s' (keys: chip, a, b, button, steps, "
                     "debounce)", spec, (int)len, p);
            return 1;
        }
        size_t klen = (size_t)(eq - p);
        const char *v = eq + 1;
        size_t vlen = len - klen - 1;
        char key[16];
        snprintf(key, sizeof key, "%.*s", (int)(klen < 15 ? klen : 15), p);
        long x;
        if (klen == 4 && !strncmp(p, "chip", 4)) {
            if (copy_value(o->chip, sizeof o->chip, v, vlen, key, spec, err, errlen)) return 1;
        } else if (klen == 1 && *p == 'a') {
            if (copy_value(o->a, sizeof o->a, v, vlen, key, spec, err, errlen)) return 1;
        } else if (klen == 1 && *p == 'b') {
            if (copy_value(o->b, sizeof o->b, v, vlen, key, spec, err, errlen)) return 1;
        } else if (klen == 6 && !strncmp(p, "button", 6)) {
            if (copy_value(o->button, sizeof o->button, v, vlen, key, spec, err, errlen)) return 1;
        } else if (klen == 5 && !strncmp(p, "steps", 5)) {
            if (parse_int(v, vlen, 1, 4, &x) || x == 3) {
                snprintf(err, errlen, "--input '%s': 'steps' must be 1, 2 or 4 (quadrature steps per detent), got "
                         "'%.*s'", spec, (int)vlen, v);
                return 1;
            }
            o->steps_per_detent = (int)x;
        } else if (klen == 8 && !strncmp(p, "debounce", 8)) {
            if (parse_int(v, vlen, 0, 1000000, &x)) {
                snprintf(err, errlen, "--input '%s': 'debounce' must be microseconds 0..1000000, got '%.*s'",
                         spec, (int)vlen, v);
                return 1;
            }
            o->debounce_us = (int)x;
        } else {
            snprintf(err, errlen, "--input '%s': unknown key '%.*s' (keys: chip, a, b, button, steps, debounce)",
                     spec, (int)klen, p);
            return 1;
        }
        p = comma ? comma + 1 : p + len;
        if (comma && !*p) {
            snprintf(err, errlen, "--input '%s': trailing ','", spec);
            return 1;
        }
    }
    if (!o->a[0] || !o->b[0]) {
        snprintf(err, errlen, "--input '%s': a rotary encoder needs both 'a=' and 'b=' lines (offsets or names)",
                 spec);
        return 1;
    }
    if (!strcmp(o->a, o->b) || (o->button[0] && (!strcmp(o->a, o->button) || !strcmp(o->b, o->button)))) {
        snprintf(err, errlen, "--input '%s': lines a, b and button must be different", spec);
        return 1;
    }
    return 0;
}

int cu_input_parse(const char *s, cu_input_spec *o, char *err, size_t errlen)
{
    cu_input_spec z = {0};
    *o = z;
    if (!s || !*s) {
        snprintf(err, errlen, "--input: empty value (use gpio:..., evdev:... or stdin)");
        return 1;
    }
    if (!strcmp(s, "stdin")) {
        o->kind = CU_INPUT_STDIN;
        return 0;
    }
    if (!strncmp(s, "gpio:", 5)) {
        o->kind = CU_INPUT_GPIO;
        return parse_gpio(s, s + 5, o, err, errlen);
    }
    if (!strncmp(s, "evdev:", 6)) {
        const char *p = s + 6;
        o->kind = CU_INPUT_EVDEV;
        if (!strncmp(p, "name=", 5))
            return copy_value(o->name, sizeof o->name, p + 5, strlen(p + 5), "name", s, err, errlen);
        if (!strncmp(p, "path=", 5))
            p += 5;
        if (*p != '/') {
            snprintf(err, errlen, "--input '%s': give a device path (evdev:/dev/input/event3) or a name "
                     "(evdev:name=...)", s);
            return 1;
        }
        return copy_value(o->path, sizeof o->path, p, strlen(p), "path", s, err, errlen);
    }
    snprintf(err, errlen, "--input '%s': unknown input kind (use gpio:chip=gpiochip0,a=17,b=27,button=22, "
             "evdev:/dev/input/eventN, evdev:name=NAME or stdin)", s);
    return 1;
}

void cu_input_describe(const cu_input_spec *s, char *buf, size_t len)
{
    switch (s->kind) {
    case CU_INPUT_GPIO:
        snprintf(buf, len, "gpio %s a=%s b=%s%s%s", s->chip, s->a, s->b, s->button[0] ? " button=" : "",
                 s->button);
        break;
    case CU_INPUT_EVDEV:
        if (s->path[0])
            snprintf(buf, len, "evdev %s", s->path);
        else
            snprintf(buf, len, "evdev name='%s'", s->name);
        break;
    case CU_INPUT_STDIN:
        snprintf(buf, len, "stdin");
        break;
    default:
        snprintf(buf, len, "(none)");
    }
}
