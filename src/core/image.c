/* src/core/image.c: PNG (libpng) and PFM reading and writing (see image.h). */
#include "image.h"
#include "error.h"
#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cu_write_png(const char *path, const unsigned char *rgba, int w, int h, cu_error *err)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = (png_uint_32)w;
    img.height = (png_uint_32)h;
    img.format = PNG_FORMAT_RGBA;
    if (!png_image_write_to_file(&img, path, 0, rgba, 0, NULL)) {
        cu_fail(err, "%s: cannot write PNG: %s", path, img.message);
        return 1;
    }
    return 0;
}

int cu_png_read(const char *path, cu_image *out, cu_error *err)
{
    memset(out, 0, sizeof *out);
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path)) {
        cu_fail(err, "%s: cannot read PNG: %s", path, img.message);
        return 1;
    }
    img.format = PNG_FORMAT_RGBA;
    out->px8 = malloc(PNG_IMAGE_SIZE(img));
    if (!out->px8 || !png_image_finish_read(&img, NULL, out->px8, 0, NULL)) {
        cu_fail(err, "%s: cannot decode PNG: %s", path, img.message);
        png_image_free(&img);
        free(out->px8);
        out->px8 = NULL;
        return 1;
    }
    out->width = (int)img.width;
    out->height = (int)img.height;
    out->channels = 4;
    return 0;
}

int cu_write_pfm(const char *path, const float *rgb, int w, int h, cu_error *err)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        cu_fail(err, "%s: cannot write: %s", path, strerror(errno));
        return 1;
    }
    int ok = fprintf(f, "PF\n%d %d\n-1.0\n", w, h) > 0;
    for (int y = h - 1; y >= 0 && ok; y--)
        ok = fwrite(rgb + (size_t)y * w * 3, sizeof(float), (size_t)w * 3, f) == (size_t)w * 3;
    ok = fflush(f) == 0 && ok;
    if (fclose(f) != 0 || !ok) {
        cu_fail(err, "%s: write failed", path);
        return 1;
    }
    return 0;
}

int cu_pfm_read(const char *path, cu_image *out, cu_error *err)
{
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path, "rb");
    if (!f) {
        cu_fail(err, "%s: cannot open: %s", path, strerror(errno));
        return 1;
    }
    char magic[3] = "";
    int w = 0, h = 0;
    double scale = 0;
    if (fscanf(f, "%2s %d %d %lf", magic, &w, &h, &scale) != 4 || strcmp(magic, "PF") != 0 || w < 1 || h < 1 ||
        w > 65536 || h > 65536 || scale >= 0) {
        cu_fail(err, "%s: not a little-endian RGB PFM", path);
        fclose(f);
        return 1;
    }
    fgetc(f); /* the single whitespace after the scale */
    out->pxf = malloc(sizeof(float) * 3 * (size_t)w * h);
    if (!out->pxf) {
        fclose(f);
        cu_fail(err, "%s: out of memory", path);
        return 1;
    }
    for (int y = h - 1; y >= 0; y--)
        if (fread(out->pxf + (size_t)y * w * 3, sizeof(float), (size_t)w * 3, f) != (size_t)w * 3) {
            cu_fail(err, "%s: truncated PFM", path);
            free(out->pxf);
            out->pxf = NULL;
            fclose(f);
            return 1;
        }
    fclose(f);
    out->width = w;
    out->height = h;
    out->channels = 3;
    return 0;
}

void cu_image_free(cu_image *img)
{
    free(img->px8);
    free(img->pxf);
    img->px8 = NULL;
    img->pxf = NULL;
}

