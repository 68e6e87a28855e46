/* platform/input/gpio_io.h: what the knob logic in gpio.c (decoding, level resync, the input back end) asks of the
 * libgpiod glue of one API version, gpio_v1.c or gpio_v2.c; platform.mk builds the one ./configure found.
 * Private to those files and gpio_errors.c; it names the struct without gpio.h so that it depends on nothing here. */
#ifndef CU_PLATFORM_GPIO_IO_H
#define CU_PLATFORM_GPIO_IO_H
#include "input.h"
#include "quadrature.h"
#include <stdint.h>


#define CU_GPIO_CONSUMER "cumulo"
#define CU_GPIO_MAX_EDGES 256   /* edges one cu_gpio_read decodes */

enum { CU_GPIO_A, CU_GPIO_B, CU_GPIO_BUTTON, CU_GPIO_LINES };

typedef struct cu_gpio_io cu_gpio_io;   /* the chip, lines and event queues of one API version */

struct cu_gpio {
    char chip_name[CU_INPUT_NAME_MAX];
    char line_name[CU_GPIO_LINES][CU_INPUT_NAME_MAX];
    unsigned offset[CU_GPIO_LINES];
    int nlines;             /* 2 without a button, 3 with */
    cu_quad quad;
    cu_button button;
    uint64_t t_last;        /* last edge timestamp, so a resync sample never goes back in time */
    char note[256];
    cu_gpio_io *io;
};

/* Opens the chip, resolves the spec's lines into g->offset and g->line_name, requests them (consumer, both edges,
 * pull-up, retried without on old kernels, with a note) and starts whatever delivers their edges. On failure: one
 * line in err; cu_gpio_io_close then frees what was made. */
int  cu_gpio_io_open(struct cu_gpio *g, const cu_input_spec *spec, char *err, size_t errlen);
/* The level of line CU_GPIO_A, _B or _BUTTON now (1 = high). */
int  cu_gpio_io_level(struct cu_gpio *g, int line);
/* Up to CU_GPIO_MAX_EDGES pending edges, without blocking; non-zero with one line when the chip is gone. */
int  cu_gpio_io_read(struct cu_gpio *g, cu_quad_edge *edges, size_t *n, char *err, size_t errlen);
void cu_gpio_io_close(struct cu_gpio *g);

/* "libgpiod v1" or "libgpiod v2", in gpio_v1.c or gpio_v2.c (an array, so that tables can point at it). */
extern const char cu_gpio_api_name[];

/* Shared by both versions, in gpio_errors.c. */
uint64_t cu_gpio_now_ns(void);
int cu_gpio_chip_error(const char *chip, int e, char *err, size_t errlen);
int cu_gpio_busy_error(const struct cu_gpio *g, int line, const char *consumer, char *err, size_t errlen);

#endif
