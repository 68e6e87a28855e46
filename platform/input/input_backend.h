/* platform/input/input_backend.h: the boundary between `cumulo run` and its inputs, drawn like display.h: each kind of
 * --input (stdin, evdev, gpio) is a table of functions in its own file, and input_backend.c lists those built. */
#ifndef CU_PLATFORM_INPUT_BACKEND_H
#define CU_PLATFORM_INPUT_BACKEND_H
#include "input.h"
#include <stddef.h>

typedef struct cu_input cu_input;   /* one opened input; each back end defines it */

typedef struct cu_input_opts {
    int grab;   /* evdev: take the device for ourselves (on a bare console the keys would also reach the login) */
    /* Lines worth telling the user that do not stop the input (a bad stdin command); NULL drops them. */
    void (*log)(void *user, const char *msg);
    void *log_user;
} cu_input_opts;

typedef enum cu_input_status {
    CU_INPUT_READ_OK = 0,
    CU_INPUT_READ_GONE,   /* the device went away or failed; err says so */
    CU_INPUT_READ_ENDED   /* the stream ended normally (a script finished, no terminal): not a failure */
} cu_input_status;

typedef struct cu_input_backend {
    const char *name;       /* "stdin", "evdev", "gpio": the source= of the sun log lines */
    cu_input_kind kind;     /* the --input specs it opens */
    const char *lib;        /* the library it was built against, for --help ("libgpiod v1"), or NULL */
    /* Opens what spec names. On success msg gets the lines to print once (may be ""), on failure one line. */
    int (*open)(cu_input **out, const cu_input_spec *spec, const cu_input_opts *opts, char *msg, size_t len);
    /* The file descriptors whose readability means read() has something; returns the count (at most max). */
    int (*fds)(cu_input *in, int *fds, int max);
    /* Reads what is pending without blocking: at most max actions into acts, *n of them. */
    cu_input_status (*read)(cu_input *in, cu_action *acts, int max, int *n, char *err, size_t errlen);
    void (*close)(cu_input *in);
} cu_input_backend;

/* The inputs compiled into this binary, NULL-terminated. */
extern const cu_input_backend *const cu_input_backends[];
/* The back end for this kind of --input, or NULL when this build lacks it (cu_input_missing says why). */
const cu_input_backend *cu_input_find(cu_input_kind kind);
/* One line on what a build without this kind lacks, e.g. "gpio: this cumulo was built without libgpiod (...)". */
const char *cu_input_missing(cu_input_kind kind);

#endif
