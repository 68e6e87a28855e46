/* Analytic colour matching functions and their linear-sRGB transform, used as spectral channel weights. */
#include "colour.h"

#include <math.h>

/* Piecewise Gaussian: different widths left and right of the peak (Wyman et al. 2013, eq. 2). */
static double lobe(double l, double mu, double s1, double s2)
{
    double t = (l - mu) / (l < mu ? s1 : s2);
    return exp(-0.5 * t * t);
}

void cie_xyz(double l, double xyz[3])
{
    xyz[0] = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
             0.065 * lobe(l, 501.1, 20.4, 26.2);
    xyz[1] = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
    xyz[2] = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
}

void srgb_response(double l, double rgb[3])
{
    /* IEC 61966-2-1 XYZ -> linear sRGB. The negative lobes (e.g. red below 550 nm) are clipped: they are
     * not physical sensor responses and would make spectral weights, and so phase functions, negative. */
    static const double M[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                   {-0.9692660, 1.8760108, 0.0415560},
                                   {0.0556434, -0.2040259, 1.0572252}};
    double xyz[3];
    cie_xyz(l, xyz);
    for (int c = 0; c < 3; c++) {
        double v = M[c][0] * xyz[0] + M[c][1] * xyz[1] + M[c][2] * xyz[2];
        rgb[c] = v > 0.0 ? v : 0.0;
    }
}
