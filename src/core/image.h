/* src/core/image.h: image files for programs and tests: 8-bit sRGB PNG (libpng) and linear float PFM. The writers
 * are public (cu_write_png, cu_write_pfm in cumulo.h); the readers are for the tests and tools. */
#ifndef CU_IMAGE_H
#define CU_IMAGE_H
#include "cumulo.h"
#include <stdint.h>

typedef struct cu_image {
    int width, height, channels; /* channels: 4 for RGBA8 PNG data, 3 for PFM */
    uint8_t *px8;                /* PNG: RGBA, top row first */
    float *pxf;                  /* PFM: RGB, top row first */
} cu_image;

/* Return 0, or 1 with a message naming the file in *err. */
int cu_png_read(const char *path, cu_image *img, cu_error *err);
/* PFM ("PF", little-endian, bottom row first in the file); pixels in memory top row first. */
int cu_pfm_read(const char *path, cu_image *img, cu_error *err);
void cu_image_free(cu_image *img);
#endif
