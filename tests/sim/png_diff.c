/* tests/sim/png_diff.c: compares two PNGs of one size for the shell tests: prints "max=M mean=A differ=N" (M the
 * largest channel difference in 1/255, A the mean over every channel, N the pixels whose largest difference exceeds
 * the threshold) and exits 0 when max <= LIMIT, 1 when not, 2 when a file cannot be read or the sizes differ.
 *   png_diff A.png B.png LIMIT [THRESHOLD]   (THRESHOLD defaults to LIMIT)
 * or the mean difference (1/255) between column CA of A and column CB of B, printed "mean=M":
 *   png_diff --columns A.png CA B.png CB */
#include "image.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int columns(char **argv)
{
    cu_image a = {0}, b = {0};
    cu_error e;
    if (cu_png_read(argv[2], &a, &e) || cu_png_read(argv[4], &b, &e)) {
        fprintf(stderr, "png_diff: %s\n", e.msg);
        return 2;
    }
    int ca = atoi(argv[3]), cb = atoi(argv[5]);
    if (a.height != b.height || ca < 0 || ca >= a.width || cb < 0 || cb >= b.width) {
        fprintf(stderr, "png_diff: columns %d of %d and %d of %d, heights %d and %d\n", ca, a.width, cb, b.width,
                a.height, b.height);
        return 2;
    }
    double sum = 0;
    for (int y = 0; y < a.height; y++)
        for (int c = 0; c < 3; c++)
            sum += fabs((double)a.px8[((size_t)y * a.width + ca) * 4 + c] -
                        (double)b.px8[((size_t)y * b.width + cb) * 4 + c]);
    printf("mean=%.4f\n", sum / (3.0 * a.height));
    cu_image_free(&a);
    cu_image_free(&b);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 6 && !strcmp(argv[1], "--columns"))
        return columns(argv);
    if (argc != 4 && argc != 5) {
        fprintf(stderr, "usage: png_diff A.png B.png LIMIT [THRESHOLD]\n");
        return 2;
    }
    cu_image a = {0}, b = {0};
    cu_error e;
    if (cu_png_read(argv[1], &a, &e) || cu_png_read(argv[2], &b, &e)) {
        fprintf(stderr, "png_diff: %s\n", e.msg);
        return 2;
    }
    if (a.width != b.width || a.height != b.height || a.channels != b.channels) {
        fprintf(stderr, "png_diff: %dx%d against %dx%d\n", a.width, a.height, b.width, b.height);
        return 2;
    }
    double limit = atof(argv[3]), thr = argc == 5 ? atof(argv[4]) : limit, sum = 0, mx = 0;
    long differ = 0, n = (long)a.width * a.height;
    for (long p = 0; p < n; p++) {
        double m = 0;
        for (int c = 0; c < a.channels; c++) {
            double d = fabs((double)a.px8[p * 4 + c] - (double)b.px8[p * 4 + c]);
            sum += d;
            m = fmax(m, d);
        }
        mx = fmax(mx, m);
        differ += m > thr + 1e-6;
    }
    printf("max=%.0f mean=%.4f differ=%ld\n", mx, sum / ((double)n * a.channels), differ);
    cu_image_free(&a);
    cu_image_free(&b);
    return mx <= limit + 1e-6 ? 0 : 1;
}
