/* platform/input/gpio.h: a rotary encoder (lines A, B) and optional push button on GPIO through libgpiod (v1 or v2 API,
 * gpio_v1.c or gpio_v2.c, chosen at build time), turned into sun actions by the quadrature decoder. */
#ifndef CU_PLATFORM_GPIO_H
#define CU_PLATFORM_GPIO_H
#include "input.h"

typedef struct cu_gpio cu_gpio;

/* Requests the lines as inputs with both edges, pull-up bias and consumer "cumulo" (v2: kernel debounce too).
 * On failure: non-zero and one line naming the chip/line and what to do. */
int  cu_gpio_open(cu_gpio **out, const cu_input_spec *spec, char *err, size_t errlen);
/* A note worth printing once after a successful open (e.g. "bias not supported by this kernel"), or "". */
const char *cu_gpio_note(const cu_gpio *g);
/* The file descriptors to poll for readability (v1: the reader thread's wake-up pipe, v2: the line request's).
 * Returns the count. */
int  cu_gpio_fds(const cu_gpio *g, int *fds, int max);
/* Reads pending edges (never blocks), decodes them; *n actions written. Returns 1 when the chip is gone. */
int  cu_gpio_read(cu_gpio *g, cu_action *acts, int max, int *n, char *err, size_t errlen);
void cu_gpio_close(cu_gpio *g);
/* "libgpiod v1" or "libgpiod v2": which API this binary was built against. */
const char *cu_gpio_api(void);

#endif
