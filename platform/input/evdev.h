/* platform/input/evdev.h: Linux input devices (/dev/input/event*) as sun controls: keyboards (arrows, +/-), relative
 * dials (USB knobs, mouse wheels, the Raspberry Pi rotary-encoder overlay). Decoding is pure; opening is thin. */
#ifndef CU_PLATFORM_EVDEV_H
#define CU_PLATFORM_EVDEV_H
#include "input.h"
#include <linux/input.h>

typedef struct cu_evdev_decoder {
    int rel_x_is_knob;  /* REL_X from a device without mouse buttons is a rotary encoder (rotary-encoder driver) */
    int dropping;       /* after SYN_DROPPED: ignore events up to the next SYN_REPORT (the kernel lost some) */
} cu_evdev_decoder;

/* Decodes one event; returns 1 and fills *out when it is an action, 0 otherwise. Mapping: REL_DIAL, REL_WHEEL,
 * REL_HWHEEL (and REL_X of a non-mouse) turn the knob; left/right arrows turn azimuth, up/down elevation; '+' '='
 * keypad +, volume up turn the knob clockwise, '-' and volume down counter-clockwise (auto-repeat included);
 * Enter, Space, mute, BTN_0 (PowerMate press) toggle the knob's axis; q and Esc quit. */
int cu_evdev_decode(cu_evdev_decoder *d, const struct input_event *ev, cu_action *out);

/* From the device's capability bits: 1 if REL_X should count as a knob (no BTN_LEFT, so not a mouse). */
int cu_evdev_rel_x_is_knob(const unsigned char *key_bits, size_t key_len, const unsigned char *rel_bits,
                           size_t rel_len);

typedef struct cu_evdev cu_evdev;
/* Opens by path or by name (exact name first, then the first name containing it). grab: take the device for
 * ourselves (on a bare console the keys would otherwise also reach the login prompt). */
int  cu_evdev_open(cu_evdev **out, const cu_input_spec *spec, int grab, char *err, size_t errlen);
int  cu_evdev_fd(const cu_evdev *e);
const char *cu_evdev_name(const cu_evdev *e);
/* Reads what is pending into acts (at most max); *n gets the count. Returns 0, or 1 when the device is gone
 * (unplugged) with a one-line message. */
int  cu_evdev_read(cu_evdev *e, cu_action *acts, int max, int *n, char *err, size_t errlen);
void cu_evdev_close(cu_evdev *e);

#endif
