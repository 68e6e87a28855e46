/* tests/sim/cigi_encode.c: host-side CIGI 3.3 encoders (either byte order) and the Start of Frame decoder, written
 * from the ICD's layouts independently of platform/sim/cigi.c so that a test of one checks the other. */
#include "cigi_encode.h"
#include <string.h>

/* A packet under construction: its bytes and the byte order to write them in. */
typedef struct wr {
    uint8_t *b;
    int swap;
} wr;

static void w16(const wr *w, size_t off, uint16_t v)
{
    w->b[off + (w->swap ? 1 : 0)] = (uint8_t)(v >> 8);
    w->b[off + (w->swap ? 0 : 1)] = (uint8_t)v;
}

static void w32(const wr *w, size_t off, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        w->b[off + (size_t)(w->swap ? i : 3 - i)] = (uint8_t)(v >> 8 * i);
}

static void w64(const wr *w, size_t off, uint64_t v)
{
    for (int i = 0; i < 8; i++)
        w->b[off + (size_t)(w->swap ? i : 7 - i)] = (uint8_t)(v >> 8 * i);
}

static void wf(const wr *w, size_t off, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    w32(w, off, u);
}

static void wd(const wr *w, size_t off, double d)
{
    uint64_t u;
    memcpy(&u, &d, sizeof u);
    w64(w, off, u);
}

/* Starts a packet of `len` bytes (zeroed) with its id and size field; 0 when it does not fit. */
static int begin(wr *w, uint8_t *out, size_t cap, int swap, uint8_t id, size_t len, uint8_t size)
{
    if (cap < len)
        return 0;
    memset(out, 0, len);
    out[0] = id;
    out[1] = size ? size : (uint8_t)len;
    w->b = out, w->swap = swap;
    return 1;
}

size_t cu_cigi_enc_ig_control_put(const cu_cigi_enc_ig_control *f, int swap, uint8_t *out, size_t cap)
{
    wr w;
    if (!begin(&w, out, cap, swap, 1, 24, f->size))
        return 0;
    out[2] = f->major ? f->major : 3;
    out[3] = (uint8_t)f->database;
    out[4] = (uint8_t)((f->ig_mode & 3) | (f->timestamp_valid ? 4 : 0) | (f->extrapolation ? 8 : 0) |
                       (f->minor ? f->minor : 3) << 4);
    w16(&w, 6, f->magic ? f->magic : 0x8000);
    w32(&w, 8, f->host_frame);
    w32(&w, 12, f->timestamp);
    w32(&w, 16, f->last_ig_frame);
    return 24;
}

size_t cu_cigi_enc_entity_put(const cu_cigi_enc_entity *f, int swap, uint8_t *out, size_t cap)
{
    wr w;
    if (!begin(&w, out, cap, swap, 2, 48, f->size))
        return 0;
    w16(&w, 2, f->entity_id);
    out[4] = (uint8_t)((f->state & 3) | (f->attached ? 4 : 0));
    out[6] = f->alpha;
    w16(&w, 8, f->entity_type);
    w16(&w, 10, f->parent_id);
    wf(&w, 12, f->roll);
    wf(&w, 16, f->pitch);
    wf(&w, 20, f->yaw);
    wd(&w, 24, f->lat);
    wd(&w, 32, f->lon);
    wd(&w, 40, f->alt);
    return 48;
}

size_t cu_cigi_enc_view_control_put(const cu_cigi_enc_view_control *f, int swap, uint8_t *out, size_t cap)
{
    wr w;
    if (!begin(&w, out, cap, swap, 16, 32, f->size))
        return 0;
    w16(&w, 2, f->view_id);
    out[4] = f->group_id;
    out[5] = f->enable & 0x3f;
    w16(&w, 6, f->entity_id);
    const float v[6] = {f->x, f->y, f->z, f->roll, f->pitch, f->yaw};
    for (size_t i = 0; i < 6; i++)
        wf(&w, 8 + 4 * i, v[i]);
    return 32;
}

size_t cu_cigi_enc_view_def_put(const cu_cigi_enc_view_def *f, int swap, uint8_t *out, size_t cap)
{
    wr w;
    if (!begin(&w, out, cap, swap, 21, 32, f->size))
        return 0;
    w16(&w, 2, f->view_id);
    out[4] = f->group_id;
    out[5] = (uint8_t)((f->enable & 0x3f) | (f->mirror & 3) << 6);
    out[6] = (uint8_t)((f->pixel_replication & 7) | (f->orthographic ? 8 : 0) | (f->reorder ? 16 : 0) |
                       (f->view_type & 7) << 5);
    const float v[6] = {f->near_m, f->far_m, f->left, f->right, f->top, f->bottom};
    for (size_t i = 0; i < 6; i++)
        wf(&w, 8 + 4 * i, v[i]);
    return 32;
}

size_t cu_cigi_enc_celestial_put(const cu_cigi_enc_celestial *f, int swap, uint8_t *out, size_t cap)
{
    wr w;
    if (!begin(&w, out, cap, swap, 9, 16, f->size))
        return 0;
    out[2] = f->hour;
    out[3] = f->minute;
    out[4] = (uint8_t)((f->ephemeris ? 1 : 0) | (f->sun ? 2 : 0) | (f->moon ? 4 : 0) | (f->stars ? 8 : 0) |
                       (f->date_valid ? 16 : 0));
    w32(&w, 8, f->date);
    wf(&w, 12, f->star_intensity);
    return 16;
}

size_t cu_cigi_enc_atmosphere_put(const cu_cigi_enc_atmosphere *f, int swap, uint8_t *out, size_t cap)
{
    wr w;
    if (!begin(&w, out, cap, swap, 10, 32, f->size))
        return 0;
    out[2] = f->model_enable ? 1 : 0;
    out[3] = f->humidity;
    const float v[6] = {f->air_temp, f->visibility, f->wind_speed, f->vertical_wind, f->wind_dir, f->pressure};
    for (size_t i = 0; i < 6; i++)
        wf(&w, 4 + 4 * i, v[i]);
    return 32;
}

size_t cu_cigi_enc_weather_put(const cu_cigi_enc_weather *f, int swap, uint8_t *out, size_t cap)
{
    wr w;
    if (!begin(&w, out, cap, swap, 12, 56, f->size))
        return 0;
    w16(&w, 2, f->region_id);
    out[4] = f->layer_id;
    out[5] = f->humidity;
    out[6] = (uint8_t)((f->enable ? 1 : 0) | (f->scud ? 2 : 0) | (f->random_winds ? 4 : 0) |
                       (f->random_lightning ? 8 : 0) | (f->cloud_type & 15) << 4);
    out[7] = (uint8_t)((f->scope & 3) | (f->severity & 7) << 2);
    const float v[12] = {f->air_temp, f->visibility, f->scud_frequency, f->coverage, f->base, f->thickness,
                         f->transition, f->wind_speed, f->vertical_wind, f->wind_dir, f->pressure, f->aerosol};
    for (size_t i = 0; i < 12; i++)
        wf(&w, 8 + 4 * i, v[i]);
    return 56;
}

static uint32_t r32(const uint8_t *b, int swap)
{
    uint32_t v = 0;
    for (int i = 0; i < 4; i++)
        v = v << 8 | b[swap ? 3 - i : i];
    return v;
}

int cu_cigi_dec_sof_get(const uint8_t *b, size_t len, cu_cigi_dec_sof *f)
{
    if (len < 24 || b[0] != 101 || b[1] != 24)
        return -1;
    unsigned magic = (unsigned)b[6] << 8 | b[7];
    if (magic != 0x8000 && magic != 0x0080)
        return -1;
    memset(f, 0, sizeof *f);
    f->swap = magic == 0x0080;
    f->major = b[2];
    f->database = (int8_t)(b[3] > 127 ? (int)b[3] - 256 : (int)b[3]);
    f->status = b[4];
    f->ig_mode = b[5] & 3;
    f->timestamp_valid = b[5] >> 2 & 1;
    f->earth_model = b[5] >> 3 & 1;
    f->minor = b[5] >> 4;
    f->ig_frame = r32(b + 8, f->swap);
    f->timestamp = r32(b + 12, f->swap);
    f->last_host_frame = r32(b + 16, f->swap);
    return 0;
}
