/* platform/input/input_set.h: the inputs of one run together: each --input opened through its back end, all polled at
 * once and each one with something pending read, and what is left of them when some go away. */
#ifndef CU_PLATFORM_INPUT_SET_H
#define CU_PLATFORM_INPUT_SET_H
#include "input_backend.h"

#define CU_INPUT_SET_MAX 8
#define CU_INPUT_FDS_MAX 3      /* file descriptors one input polls (gpio v1: one per line) */

typedef struct cu_input_slot {
    cu_input_spec spec;
    int required;               /* asked for with --input (stdin read by default is not) */
    const cu_input_backend *be;
    cu_input *in;               /* NULL when not open: it failed to open, or went away */
    int ended;                  /* its stream ended normally (a script finished): not a failure */
} cu_input_slot;

/* Zero is an empty set. */
typedef struct cu_input_set {
    cu_input_slot slot[CU_INPUT_SET_MAX];
    int n, nrequired;
    cu_input_opts opts;         /* its log gets every message of the set and of its inputs, one line each */
} cu_input_set;

/* Adds one --input value, required; non-zero with one line in err when it is wrong or the set is full. */
int  cu_input_set_add(cu_input_set *s, const char *spec, char *err, size_t errlen);
/* Adds stdin, not required, unless an --input already names it or the set is full. */
void cu_input_set_add_stdin(cu_input_set *s);
/* Opens every input; one that fails is logged ("...; continuing without it") and left closed. Returns how many of
 * the required ones opened. */
int  cu_input_set_open(cu_input_set *s, const cu_input_opts *opts);
/* Waits up to timeout_ms (0: just looks) for the open inputs and reads each that has something: returns the count
 * of actions (at most max) and, in source, the name of the input each came from. An input that is gone or ended is
 * closed (a gone one with a logged line). */
int  cu_input_set_poll(cu_input_set *s, int timeout_ms, cu_action *acts, const char **source, int max);
/* The open inputs, e.g. "gpio gpiochip0 a=17 b=27, stdin", or "" when none. */
void cu_input_set_describe(const cu_input_set *s, char *buf, size_t len);
/* How many required inputs are still there (open, or ended normally); *open and *ended: any open, any ended. */
int  cu_input_set_left(const cu_input_set *s, int *open, int *ended);
void cu_input_set_close(cu_input_set *s);

#endif
