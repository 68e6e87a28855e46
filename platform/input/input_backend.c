/* platform/input/input_backend.c: the table of inputs compiled into this binary, and lookup by --input kind. */
#include "input_backend.h"
#include "config.h"

extern const cu_input_backend cu_input_stdin;
extern const cu_input_backend cu_input_evdev;
#if CU_HAVE_GPIOD
extern const cu_input_backend cu_input_gpio;
#endif

const cu_input_backend *const cu_input_backends[] = {
    &cu_input_stdin,
    &cu_input_evdev,
#if CU_HAVE_GPIOD
    &cu_input_gpio,
#endif
    NULL,
};

const cu_input_backend *cu_input_find(cu_input_kind kind)
{
    for (int i = 0; cu_input_backends[i]; i++)
        if (cu_input_backends[i]->kind == kind)
            return cu_input_backends[i];
    return NULL;
}

const char *cu_input_missing(cu_input_kind kind)
{
    /* stdin and evdev need only the kernel's headers, so every build has them. */
    if (kind == CU_INPUT_GPIO)
        return "gpio: this cumulo was built without libgpiod (install libgpiod-dev and rebuild)";
    return "input: this cumulo was built without it";
}
