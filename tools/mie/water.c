/* Water refractive index: Sellmeier dispersion for n, tabulated absorption for k. */
#include "water.h"

#include <math.h>

double water_n(double lambda_nm)
{
    /* Daimon & Masumura, Appl. Opt. 46 (2007) 3811, 20.0 degC fit: n^2 - 1 = sum A_i l^2/(l^2 - B_i), l in um.
     * Reproduces VALIDATION.md's 1.34029 / 1.33468 / 1.33096 at 440 / 550 / 680 nm within 5e-6. */
    static const double A[4] = {5.684027565e-1, 1.726177391e-1, 2.086189578e-2, 1.130748688e-1};
    static const double B[4] = {5.101829712e-3, 1.821153936e-2, 2.620722293e-2, 1.069792721e1};
    double l2 = (lambda_nm * 1e-3) * (lambda_nm * 1e-3);
    double s = 1.0;
    for (int i = 0; i < 4; i++)
        s += A[i] * l2 / (l2 - B[i]);
    return sqrt(s);
}

double water_k(double lambda_nm)
{
    /* Hale & Querry, Appl. Opt. 12 (1973) 555, Table 1, 400-700 nm every 25 nm. The values matter only for
     * resonance widths: for 6 um droplets Q_abs ~ 1e-6 (VALIDATION.md), far below the table's precision. */
    static const double k[13] = {1.86e-9, 1.30e-9, 1.02e-9, 9.35e-10, 1.00e-9, 1.32e-9, 1.96e-9,
                                 3.60e-9, 1.09e-8, 1.39e-8, 1.64e-8, 2.23e-8, 3.35e-8};
    double t = (lambda_nm - 400.0) / 25.0;
    if (t <= 0.0)
        return k[0];
    if (t >= 12.0)
        return k[12];
    int i = (int)t;
    double u = t - i;
    return exp((1.0 - u) * log(k[i]) + u * log(k[i + 1]));
}

double complex water_m(double lambda_nm)
{
    return water_n(lambda_nm) - I * water_k(lambda_nm);
}
