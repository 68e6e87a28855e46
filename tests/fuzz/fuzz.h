/* tests/fuzz/fuzz.h: what every libFuzzer target of tests/fuzz shares: invariant checks that abort with a message. */
#ifndef CU_FUZZ_H
#define CU_FUZZ_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* An invariant: when it does not hold the target aborts, and libFuzzer saves the input as a crash. */
#define FUZZ_CHECK(cond, ...)                                                                                         \
    do {                                                                                                              \
        if (!(cond)) {                                                                                                \
            fprintf(stderr, "%s:%d: invariant '%s' does not hold: ", __FILE__, __LINE__, #cond);                      \
            fprintf(stderr, __VA_ARGS__);                                                                             \
            fputc('\n', stderr);                                                                                      \
            abort();                                                                                                  \
        }                                                                                                             \
    } while (0)

/* An invariant that fails today in code another change owns (its reproducer is in tests/fuzz/pending/): checked only
 * in `make fuzz-pending` (-DFUZZ_PENDING), so that `make fuzz` stays green until the fix lands. When it does, make it
 * a FUZZ_CHECK and move the reproducer to tests/fuzz/regressions/. */
#ifdef FUZZ_PENDING
#define FUZZ_CHECK_PENDING(cond, ...) FUZZ_CHECK(cond, __VA_ARGS__)
#else
#define FUZZ_CHECK_PENDING(cond, ...) ((void)0)
#endif

/* A failed call's message: non-empty, NUL-terminated inside its buffer, and starting with what it names. */
#define FUZZ_CHECK_MESSAGE(msg, prefix)                                                                               \
    do {                                                                                                              \
        FUZZ_CHECK(memchr((msg), 0, sizeof(msg)) != NULL, "message not terminated");                                  \
        FUZZ_CHECK((msg)[0] != 0, "a failure with an empty message");                                                 \
        FUZZ_CHECK(strncmp((msg), (prefix), strlen(prefix)) == 0, "message '%s' does not start with '%s'", (msg),    \
                   (prefix));                                                                                         \
    } while (0)
#endif
