/* Linear-sRGB channel responses over wavelength, for averaging spectral Mie results into R, G, B. */
#ifndef CUMULO_MIE_COLOUR_H
#define CUMULO_MIE_COLOUR_H

/* CIE 1931 2-degree matching functions, Wyman, Sloan & Shirley (JCGT 2, 2013) multi-lobe Gaussian fit. */
void cie_xyz(double lambda_nm, double xyz[3]);
/* Linear sRGB (D65 primaries) response at lambda: the XYZ->sRGB matrix applied to the matching functions,
 * negative lobes clipped to zero so each channel is a non-negative weight. */
void srgb_response(double lambda_nm, double rgb[3]);

#endif
