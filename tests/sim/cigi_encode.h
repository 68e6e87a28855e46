/* tests/sim/cigi_encode.h: the host side of CIGI 3.3 for tests and test hosts: one encoder per packet a host sends
 * (in either byte order) and a decoder of the IG's Start of Frame. Field values in, bytes out; a zero field means the
 * ICD's value where one is fixed (version 3.3, magic 0x8000, the packet's size). */
#ifndef CU_TESTS_CIGI_ENCODE_H
#define CU_TESTS_CIGI_ENCODE_H

#include <stddef.h>
#include <stdint.h>

/* Every encoder writes its packet into out and returns the bytes written, or 0 (writing nothing) when cap is short.
 * swap = 0 writes big-endian, 1 little-endian (a little-endian host, for the IG to detect). `size`, where a struct
 * has it, overrides the size field only (the encoder still writes the packet's real length): for hostile tests. */

typedef struct cu_cigi_enc_ig_control {
    uint8_t major, minor;        /* 0: 3 and 3 */
    int8_t database;
    uint8_t ig_mode;             /* 0 standby, 1 operate, 2 debug */
    int timestamp_valid, extrapolation;
    uint16_t magic;              /* 0: 0x8000 (written in the chosen byte order) */
    uint32_t host_frame, timestamp, last_ig_frame;
    uint8_t size;
} cu_cigi_enc_ig_control;
size_t cu_cigi_enc_ig_control_put(const cu_cigi_enc_ig_control *f, int swap, uint8_t *out, size_t cap);

typedef struct cu_cigi_enc_entity {
    uint16_t entity_id, entity_type, parent_id;
    uint8_t state;               /* 0 inactive, 1 active, 2 destroyed */
    int attached;
    uint8_t alpha;
    float roll, pitch, yaw;      /* degrees */
    double lat, lon, alt;        /* degrees, degrees, metres */
    uint8_t size;
} cu_cigi_enc_entity;
size_t cu_cigi_enc_entity_put(const cu_cigi_enc_entity *f, int swap, uint8_t *out, size_t cap);

enum { CU_CIGI_EN_X = 1, CU_CIGI_EN_Y = 2, CU_CIGI_EN_Z = 4, CU_CIGI_EN_ROLL = 8, CU_CIGI_EN_PITCH = 16,
       CU_CIGI_EN_YAW = 32 };
typedef struct cu_cigi_enc_view_control {
    uint16_t view_id, entity_id;
    uint8_t group_id;
    uint8_t enable;              /* CU_CIGI_EN_* */
    float x, y, z;               /* metres, body frame */
    float roll, pitch, yaw;      /* degrees */
    uint8_t size;
} cu_cigi_enc_view_control;
size_t cu_cigi_enc_view_control_put(const cu_cigi_enc_view_control *f, int swap, uint8_t *out, size_t cap);

enum { CU_CIGI_EN_NEAR = 1, CU_CIGI_EN_FAR = 2, CU_CIGI_EN_LEFT = 4, CU_CIGI_EN_RIGHT = 8, CU_CIGI_EN_TOP = 16,
       CU_CIGI_EN_BOTTOM = 32 };
typedef struct cu_cigi_enc_view_def {
    uint16_t view_id;
    uint8_t group_id;
    uint8_t enable;              /* CU_CIGI_EN_NEAR.. */
    uint8_t mirror, pixel_replication, view_type;
    int orthographic, reorder;
    float near_m, far_m, left, right, top, bottom; /* half-angles in degrees */
    uint8_t size;
} cu_cigi_enc_view_def;
size_t cu_cigi_enc_view_def_put(const cu_cigi_enc_view_def *f, int swap, uint8_t *out, size_t cap);

typedef struct cu_cigi_enc_celestial {
    uint8_t hour, minute;
    int ephemeris, sun, moon, stars, date_valid;
    uint32_t date;               /* MMDDYYYY as a number: 6212024 for 21 June 2024 */
    float star_intensity;        /* percent */
    uint8_t size;
} cu_cigi_enc_celestial;
size_t cu_cigi_enc_celestial_put(const cu_cigi_enc_celestial *f, int swap, uint8_t *out, size_t cap);

typedef struct cu_cigi_enc_atmosphere {
    int model_enable;
    uint8_t humidity;            /* percent */
    float air_temp, visibility, wind_speed, vertical_wind, wind_dir, pressure; /* C, m, m/s, m/s, deg from, hPa */
    uint8_t size;
} cu_cigi_enc_atmosphere;
size_t cu_cigi_enc_atmosphere_put(const cu_cigi_enc_atmosphere *f, int swap, uint8_t *out, size_t cap);

typedef struct cu_cigi_enc_weather {
    uint16_t region_id;
    uint8_t layer_id, humidity;
    int enable, scud, random_winds, random_lightning;
    uint8_t cloud_type;          /* 0..15 */
    uint8_t scope;               /* 0 global, 1 regional, 2 entity */
    uint8_t severity;            /* 0..5 */
    float air_temp, visibility, scud_frequency, coverage; /* C, m, %, % */
    float base, thickness, transition;                     /* m */
    float wind_speed, vertical_wind, wind_dir, pressure, aerosol;
    uint8_t size;
} cu_cigi_enc_weather;
size_t cu_cigi_enc_weather_put(const cu_cigi_enc_weather *f, int swap, uint8_t *out, size_t cap);

/* Start of Frame as the host reads it. */
typedef struct cu_cigi_dec_sof {
    uint8_t major, minor;
    int8_t database;
    uint8_t status, ig_mode;
    int timestamp_valid, earth_model;
    int swap;                    /* the IG wrote little-endian */
    uint32_t ig_frame, timestamp, last_host_frame;
} cu_cigi_dec_sof;
/* Decodes a Start of Frame at buf: 0 on success, -1 when it is short, not id 101 of 24 bytes, or its magic number is
 * neither 0x8000 nor 0x0080. */
int cu_cigi_dec_sof_get(const uint8_t *buf, size_t len, cu_cigi_dec_sof *f);

#endif
