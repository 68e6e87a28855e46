/* Complex refractive index of liquid water in the visible (Daimon & Masumura 2007; Hale & Querry 1973). */
#ifndef CUMULO_MIE_WATER_H
#define CUMULO_MIE_WATER_H

#include <complex.h>

/* Real part at 20 degC from Daimon & Masumura's four-term Sellmeier fit; valid 182-1129 nm. */
double water_n(double lambda_nm);
/* Imaginary part (absorption index) from Hale & Querry's table, log-interpolated; valid 400-700 nm
 * (clamped outside). */
double water_k(double lambda_nm);
/* m = n - ik in Wiscombe's sign convention. */
double complex water_m(double lambda_nm);

#endif
