/* src/core/tonemap.h: the display transform on the CPU, the C twin of shaders_gles/tonemap.frag (its non-LINEAR_OUTPUT
 * branch): radiance times the exposure, divided by the white balance, clamped at zero, the ACES filmic curve
 * (Narkowicz's fit), the sRGB transfer function, and the 8-bit value an RGBA8 target stores. Whatever on the CPU
 * needs the tone-mapped image (the sweep's "visible" metric, tests) calls these instead of copying the curve; change
 * the two together (tests/core/test_tonemap.c checks that the shader's source carries these constants). */
#ifndef CU_TONEMAP_H
#define CU_TONEMAP_H

/* ACES fit t(x) = x (A x + B) / (x (C x + D) + E), clamped to [0, 1]; the text is tonemap.frag's. */
#define CU_TONEMAP_A 2.51
#define CU_TONEMAP_B 0.03
#define CU_TONEMAP_C 2.43
#define CU_TONEMAP_D 0.59
#define CU_TONEMAP_E 0.14
/* sRGB: 12.92 c below the knee, 1.055 c^(1/2.4) - 0.055 from it on, which the display transform takes as
 * R1 c^(1/2) + R2 c^(1/4) - R3 c^(1/8) - R4 c (Taylor 2012): within 0.25/255 of it, three square roots instead of a
 * power per channel on the GPU. */
#define CU_SRGB_KNEE 0.0031308
#define CU_SRGB_LINEAR 12.92
#define CU_SRGB_SCALE 1.055
#define CU_SRGB_OFFSET 0.055
#define CU_SRGB_GAMMA 2.4
#define CU_SRGB_R1 0.662002687
#define CU_SRGB_R2 0.68412206
#define CU_SRGB_R3 0.323583601
#define CU_SRGB_R4 0.022541147

/* The filmic curve of a non-negative exposed value x, in [0, 1]. */
double cu_tonemap_aces(double x);
/* The sRGB encoding of a linear value c in [0, 1], as the display transform makes it (the roots' form). */
double cu_tonemap_srgb(double c);
/* The shader's output for one channel, in [0, 1]: srgb(aces(max(radiance * exposure / white, 0))). A NaN radiance
 * gives 0, as max() does on the GPUs we run on. */
double cu_tonemap_channel(double radiance, double exposure, double white);
/* The 8-bit value an RGBA8 target stores for the shader's output v (round to nearest, clamped to 0..255). */
int cu_tonemap_quantize8(double v);
/* cu_tonemap_quantize8(cu_tonemap_channel(...)): one channel of a tone-mapped 8-bit frame. */
int cu_tonemap8(double radiance, double exposure, double white);
/* A whole RGB pixel: out[c] = cu_tonemap8(rgb[c], exposure, white[c]). */
void cu_tonemap_rgb8(const float rgb[3], double exposure, const double white[3], unsigned char out[3]);
#endif
