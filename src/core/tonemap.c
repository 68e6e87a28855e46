/* src/core/tonemap.c: the display transform on the CPU, the twin of shaders_gles/tonemap.frag (see tonemap.h). */
#include "tonemap.h"
#include <math.h>

double cu_tonemap_aces(double x)
{
    double t = x * (CU_TONEMAP_A * x + CU_TONEMAP_B) / (x * (CU_TONEMAP_C * x + CU_TONEMAP_D) + CU_TONEMAP_E);
    return t < 0 ? 0 : t > 1 ? 1 : t;
}

double cu_tonemap_srgb(double c)
{
    if (c < CU_SRGB_KNEE)
        return CU_SRGB_LINEAR * c;
    double s1 = sqrt(c), s2 = sqrt(s1), s3 = sqrt(s2);
    return CU_SRGB_R1 * s1 + CU_SRGB_R2 * s2 - CU_SRGB_R3 * s3 - CU_SRGB_R4 * c;
}

double cu_tonemap_channel(double radiance, double exposure, double white)
{
    double x = radiance * exposure / white;
    return cu_tonemap_srgb(cu_tonemap_aces(x > 0 ? x : 0)); /* x > 0 is false for NaN: 0, as max(x, 0.0) */
}

int cu_tonemap_quantize8(double v)
{
    int q = (int)floor(v * 255.0 + 0.5);
    return q < 0 ? 0 : q > 255 ? 255 : q;
}

int cu_tonemap8(double radiance, double exposure, double white)
{
    return cu_tonemap_quantize8(cu_tonemap_channel(radiance, exposure, white));
}

void cu_tonemap_rgb8(const float rgb[3], double exposure, const double white[3], unsigned char out[3])
{
    for (int c = 0; c < 3; c++)
        out[c] = (unsigned char)cu_tonemap8(rgb[c], exposure, white[c]);
}
