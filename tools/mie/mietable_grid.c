/* tools/mie/mietable_grid.c: the table's default parameters and its grids: scattering angles (fine near the forward
 * peak, coarse elsewhere, or a given list) and the wavelength weights of the RGB channels. */
#include "mietable.h"
#include "colour.h"
#include "mie.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

mt_params mt_params_default(void)
{
    mt_params p;
    memset(&p, 0, sizeof p);
    p.reff_um = 6.0;
    p.veff = 0.1;
    p.radius_um = 6.0;
    /* With the narrow resonances corrected as poles (resonance.h) the radius quadrature converges
     * exponentially, so a coarse step suffices; the cost is one extra Mie evaluation per corrected pole, which
     * grows with dx. 0.05 is near the cheapest step at the table's accuracy (tools/mie/README.md). */
    p.dx = 0.05;
    p.lambda_min_nm = 400.0;
    p.lambda_max_nm = 700.0;
    /* Cubic product integration over wavelength (band_weights) converges fast enough for 20 nm steps
     * (tools/mie/README.md). */
    p.dlambda_nm = 20.0;
    p.tail_stretch = 4.0;
    p.threads = 2;
    p.poles = 1;
    return p;
}

/* ---- angle sets ---------------------------------------------------------------------------------------------- */

static int angles_alloc(mt_angles *a, int nhalf, int nang)
{
    a->nhalf = nhalf;
    a->nhalf_pad = (nhalf + MIE_JBLOCK - 1) / MIE_JBLOCK * MIE_JBLOCK;
    a->nang = nang;
    a->mu = calloc((size_t)a->nhalf_pad, sizeof *a->mu);
    a->theta_deg = calloc((size_t)nang, sizeof *a->theta_deg);
    a->src = calloc((size_t)nang, sizeof *a->src);
    if (!a->mu || !a->theta_deg || !a->src) {
        mt_angles_free(a);
        return -1;
    }
    return 0;
}

void mt_angles_free(mt_angles *a)
{
    free(a->mu);
    free(a->theta_deg);
    free(a->src);
    memset(a, 0, sizeof *a);
}

int mt_angles_table(mt_angles *a, double fine_deg, double fine_until_deg, double coarse_deg)
{
    /* Steps are given as counts so that every node is an exact multiple and 8 deg (the chop) is a node. */
    int nfine = (int)lround(fine_until_deg / fine_deg);
    int ncoarse = (int)lround((90.0 - fine_until_deg) / coarse_deg);
    if (nfine < 1 || ncoarse < 1 || fabs(nfine * fine_deg - fine_until_deg) > 1e-9 ||
        fabs(fine_until_deg + ncoarse * coarse_deg - 90.0) > 1e-9)
        return -1;
    int nhalf = nfine + ncoarse + 1; /* 0 .. 90 inclusive */
    if (angles_alloc(a, nhalf, 2 * nhalf - 1) != 0)
        return -1;
    for (int h = 0; h < nhalf; h++) {
        double t = h <= nfine ? h * fine_deg : fine_until_deg + (h - nfine) * coarse_deg;
        a->mu[h] = cos(t * PI / 180.0);
        a->theta_deg[h] = t;
        a->src[h] = h << 1;
        if (h < nhalf - 1) {
            int i = 2 * nhalf - 2 - h;
            a->theta_deg[i] = 180.0 - t;
            a->src[i] = (h << 1) | 1;
        }
    }
    a->mu[nhalf - 1] = 0.0; /* cos(90 deg) exactly, so both hemispheres give the same value there */
    for (int h = nhalf; h < a->nhalf_pad; h++)
        a->mu[h] = 1.0;
    return 0;
}

int mt_angles_list(mt_angles *a, const double *theta_deg, int n)
{
    if (n < 1 || angles_alloc(a, n, n) != 0)
        return -1;
    for (int i = 0; i < n; i++) {
        a->mu[i] = cos(theta_deg[i] * PI / 180.0);
        a->theta_deg[i] = theta_deg[i];
        a->src[i] = i << 1;
    }
    for (int h = n; h < a->nhalf_pad; h++)
        a->mu[h] = 1.0;
    return 0;
}

/* Weights of the band's nodes lo + i step (i < ns) for each channel: int w_c(lambda) X(lambda) dlambda over
 * [lo, lo + (ns-1) step] ~ sum_i bw[c][i] X_i, with X interpolated by local cubics through four neighbouring nodes
 * (linear below four nodes) and the product with the response integrated by composite Simpson at step/200.
 * The responses have kinks where clipped lobes cross zero; integrating them exactly instead of sampling them
 * with the trapezoid rule leaves only the interpolation error of the smooth X, so a coarse wavelength step
 * converges (data/mie_cloud.md). */
void mt_band_weights(double lo, double step, int ns, double *bw[3])
{
    enum { M = 200 };
    for (int i = 0; i + 1 < ns; i++)
        for (int q = 0; q <= M; q++) {
            double sw = (q == 0 || q == M) ? 1.0 : (q & 1) ? 4.0 : 2.0;
            sw *= step / (3.0 * M);
            double t = i + (double)q / M, l[4], rgb[3];
            int first;
            if (ns >= 4) {
                int k = i - 1 < 0 ? 0 : i - 1 > ns - 4 ? ns - 4 : i - 1;
                for (int j = 0; j < 4; j++) {
                    l[j] = 1.0;
                    for (int m = 0; m < 4; m++)
                        if (m != j)
                            l[j] *= (t - (k + m)) / (double)(j - m);
                }
                first = k;
            } else {
                l[0] = i + 1 - t;
                l[1] = t - i;
                l[2] = l[3] = 0.0;
                first = i;
            }
            srgb_response(lo + t * step, rgb);
            for (int c = 0; c < 3; c++)
                for (int j = 0; j < 4 && first + j < ns; j++)
                    bw[c][first + j] += sw * rgb[c] * l[j];
        }
}
