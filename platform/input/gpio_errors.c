/* platform/input/gpio_errors.c: what both libgpiod glues (gpio_v1.c, gpio_v2.c) share: the clock the edges are
 * timed against, and the one-line errors for a chip that cannot be opened and a line that is busy. */
#include "gpio.h"
#include "gpio_io.h"
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

uint64_t cu_gpio_now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

int cu_gpio_chip_error(const char *chip, int e, char *err, size_t errlen)
{
    if (e == EACCES || e == EPERM)
        snprintf(err, errlen, "gpio: %s: permission denied: add the user to group 'gpio' (sudo usermod -aG gpio "
                 "$USER, then log in again) or run as root", chip);
    else if (e == ENOENT || e == ENODEV || e == ENXIO)
        snprintf(err, errlen, "gpio: no GPIO chip '%s' on this machine: check chip= in --input (gpiodetect lists "
                 "the chips)", chip);
    else
        snprintf(err, errlen, "gpio: cannot open GPIO chip '%s': %s", chip, strerror(e));
    return 1;
}

int cu_gpio_busy_error(const cu_gpio *g, int i, const char *consumer, char *err, size_t errlen)
{
    snprintf(err, errlen, "gpio: line %s (offset %u) on %s is busy (used by '%s'): stop that program or remove the "
             "dtoverlay claiming it, or pick other lines", g->line_name[i], g->offset[i], g->chip_name,
             consumer && *consumer ? consumer : "the kernel");
    return 1;
}
