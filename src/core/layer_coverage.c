/* src/core/layer_coverage.c: how much of a layer's square its clouds cover seen from straight above (layer.h), on a
 * raster, wrapped periodically. */
#include "layer.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

double cu_layer_coverage(const cu_layer *l, const cu_layer_spec *spec, int grid)
{
    if (!l || !spec || grid < 1 || grid > 8192 || !isfinite(spec->extent) || !(spec->extent > 0) ||
        !isfinite(spec->margin) || spec->margin < 0)
        return -1.0;
    const double L = spec->extent, cs = L / grid, m = spec->margin;
    unsigned char *mask = calloc((size_t)grid * (size_t)grid, 1);
    if (!mask)
        return -1.0;
    for (int e = 0; e < l->n_ell; e++) {
        const cu_layer_ellipsoid *el = &l->ell[e];
        double a = el->radii[0] - m, c = el->radii[2] - m;
        if (a <= 0 || c <= 0)
            continue;
        double cx = el->center[0], cz = el->center[2];
        long j0 = (long)ceil((cz - c + 0.5 * L) / cs - 0.5), j1 = (long)floor((cz + c + 0.5 * L) / cs - 0.5);
        for (long j = j0; j <= j1; j++) {
            double t = (-0.5 * L + (j + 0.5) * cs - cz) / c;
            if (t * t > 1.0)
                continue;
            double w = a * sqrt(1.0 - t * t);
            long i0 = (long)ceil((cx - w + 0.5 * L) / cs - 0.5), i1 = (long)floor((cx + w + 0.5 * L) / cs - 0.5);
            if (i1 - i0 + 1 >= grid) {
                i0 = 0;
                i1 = grid - 1;
            }
            unsigned char *row = mask + (size_t)(((j % grid) + grid) % grid) * (size_t)grid;
            for (long i = i0; i <= i1; i++)
                row[((i % grid) + grid) % grid] = 1;
        }
    }
    size_t n = 0;
    for (size_t i = 0; i < (size_t)grid * (size_t)grid; i++)
        n += mask[i];
    free(mask);
    return (double)n / ((double)grid * (double)grid);
}
