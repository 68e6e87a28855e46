/* src/image.h: image files for programs and tests: 8-bit sRGB PNG (libpng) and linear float PFM, read and write. */
#ifndef CU_IMAGE_H
#define CU_IMAGE_H
#include <stdint.h>

typedef struct cu_image {
    int width, height, channels; /* channels: 4 for RGBA8 PNG data, 3 for PFM */
    uint8_t *px8;                /* PNG: RGBA, top row first */
    float *pxf;                  /* PFM: RGB, top row first */
} cu_image;

/* Writes RGBA8 pixels (top row first) as PNG. Returns 0 or -1 with a message in err. */
int cu_png_write(const char *path, const uint8_t *rgba, int w, int h, char *err, int errlen);
int cu_png_read(const char *path, cu_image *img, char *err, int errlen);
/* PFM ("PF", little-endian, bottom row first in the file); pixels in memory top row first. */
int cu_pfm_write(const char *path, const float *rgb, int w, int h, char *err, int errlen);
int cu_pfm_read(const char *path, cu_image *img, char *err, int errlen);
void cu_image_free(cu_image *img);
#endif
