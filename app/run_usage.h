/* app/run_usage.h: the help text of `cumulo run` (app/run_usage.c). */
#ifndef CU_APP_RUN_USAGE_H
#define CU_APP_RUN_USAGE_H
#include <stdio.h>

/* " headless egl osmesa drm ... (headless = egl)": the display back ends of this build, on one line. */
void run_list_display_backends(FILE *f);
/* The usage of `cumulo run`: its options, the back ends and the inputs of this build. */
void run_usage(FILE *f);
#endif
