/* platform/input/stdin_input.h: line commands on standard input (for SSH sessions and scripts): parsing is pure, the
 * reader is a non-blocking line splitter over a file descriptor. */
#ifndef CU_PLATFORM_STDIN_INPUT_H
#define CU_PLATFORM_STDIN_INPUT_H
#include "input.h"

/* Commands (one per line, '#' starts a comment):
 *   sun EL AZ        set elevation and azimuth (degrees)
 *   elevation EL     (or: el EL)      azimuth AZ (or: az AZ)
 *   turn N           N detents of the knob (negative: counter-clockwise)
 *   toggle           the knob's button: switch between azimuth and elevation (--clock: reset the offset)
 *   offset MINUTES   --clock: show the clock plus MINUTES (-1440..1440; 0: the clock itself)
 *   status           print the current sun          quit (or: exit)   stop the program
 * Returns 0 with out->kind (CU_ACT_NONE for a blank line), or non-zero with a one-line message. */
int cu_stdin_parse(const char *line, cu_action *out, char *err, size_t errlen);

#define CU_STDIN_LINE_MAX 256
typedef struct cu_stdin {
    int fd;
    char buf[CU_STDIN_LINE_MAX];
    size_t len;
    int overlong;   /* discarding the rest of a line longer than the buffer */
    int eof;
} cu_stdin;

void cu_stdin_init(cu_stdin *s, int fd);
/* Appends bytes and extracts complete lines; calls fn(user, line) for each (line without the newline). A line too
 * long for the buffer is dropped whole and reported once as the line CU_STDIN_OVERLONG. Pure. */
#define CU_STDIN_OVERLONG "\001overlong"
void cu_stdin_feed(cu_stdin *s, const char *data, size_t n, void (*fn)(void *user, const char *line), void *user);
/* One read() (call it when poll() says the fd is readable) and hands out lines as cu_stdin_feed does.
 * Returns 0, or 1 at end of file / read error (s->eof is set). */
int  cu_stdin_read(cu_stdin *s, void (*fn)(void *user, const char *line), void *user);

#endif
