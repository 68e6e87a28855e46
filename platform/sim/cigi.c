/* platform/sim/cigi.c: the IG side of CIGI 3.3: walks a host datagram packet by packet, checks every field it uses
 * and fills cu_sim_state; encodes Start of Frame. Offsets are those of Wireshark's 3.3 dissector (packet-cigi.c). */
#include "cigi.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Floats arrive as IEEE 754 bit patterns: reading them through memcpy of the integer needs the sizes to match. */
typedef char cu_cigi_float_is_32_bits[sizeof(float) == 4 ? 1 : -1];
typedef char cu_cigi_double_is_64_bits[sizeof(double) == 8 ? 1 : -1];

/* How one packet ended, counted in the matching cu_cigi_stats field. */
enum { R_APPLIED, R_SKIPPED, R_MALFORMED, R_VERSION, R_NONFINITE, R_RANGE };

/* A packet being read: its bytes (its whole defined size is there), the sender's byte order and its name. */
typedef struct pkt {
    const uint8_t *p;
    int swap;
    const char *name;
} pkt;

static uint16_t u16(const pkt *k, size_t off)
{
    const uint8_t *b = k->p + off;
    return k->swap ? (uint16_t)(b[0] | b[1] << 8) : (uint16_t)(b[0] << 8 | b[1]);
}

static uint32_t u32(const pkt *k, size_t off)
{
    const uint8_t *b = k->p + off;
    uint32_t v = 0;
    for (int i = 0; i < 4; i++)
        v = v << 8 | b[k->swap ? 3 - i : i];
    return v;
}

static uint64_t u64(const pkt *k, size_t off)
{
    const uint8_t *b = k->p + off;
    uint64_t v = 0;
    for (int i = 0; i < 8; i++)
        v = v << 8 | b[k->swap ? 7 - i : i];
    return v;
}

static double f32(const pkt *k, size_t off)
{
    uint32_t u = u32(k, off);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static double f64(const pkt *k, size_t off)
{
    uint64_t u = u64(k, off);
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

static int say(cu_cigi_ig *ig, int r, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(ig->last_error, sizeof ig->last_error, fmt, ap);
    va_end(ap);
    return r;
}

/* A field's value against [lo, hi] (open = 1: the open interval): 0 when inside, else the rejection. */
static int check(cu_cigi_ig *ig, const pkt *k, const char *field, double v, double lo, double hi, int open)
{
    if (!isfinite(v))
        return say(ig, R_NONFINITE, "%s: %s is %g", k->name, field, v);
    if (open ? v <= lo || v >= hi : v < lo || v > hi)
        return say(ig, R_RANGE, "%s: %s %g outside %g..%g%s", k->name, field, v, lo, hi, open ? " (open)" : "");
    return 0;
}
#define CHECK(field, v, lo, hi, open)                                                                                 \
    do {                                                                                                              \
        int r_ = check(ig, k, field, v, lo, hi, open);                                                                \
        if (r_)                                                                                                       \
            return r_;                                                                                                \
    } while (0)

/* Degrees into [0, 360): a tiny negative angle plus 360 rounds to 360 itself, which is 0. */
static double wrap360(double deg)
{
    double d = fmod(deg, 360.0);
    if (d < 0)
        d += 360.0;
    return d < 360.0 && d != 0 ? d : 0.0; /* and -0 is 0 */
}

/* Entity Control (id 2): bytes 2-3 entity id, 4 entity state (bits 0-1) and attach state (bit 2), 12/16/20 roll,
 * pitch, yaw (float deg), 24/32/40 latitude, longitude, altitude (double deg, deg, m). */
static int entity_control(cu_cigi_ig *ig, const pkt *k, cu_sim_state *st)
{
    if (u16(k, 2) != ig->entity_id)
        return R_SKIPPED; /* another entity: the eyepoint rides on the ownship only */
    unsigned state = k->p[4] & 3u;
    if (state != 1) /* 0 inactive/standby, 2 destroyed: where it is does not move the eyepoint */
        return say(ig, R_SKIPPED, "%s: entity %u state %u is not active (1)", k->name, ig->entity_id, state);
    if (k->p[4] & 4u) /* attached: the three doubles are offsets from a parent this IG does not track */
        return say(ig, R_SKIPPED, "%s: entity %u is attached to parent %u; only a free ownship is followed",
                   k->name, ig->entity_id, u16(k, 10));
    double roll = f32(k, 12), pitch = f32(k, 16), yaw = f32(k, 20);
    double lat = f64(k, 24), lon = f64(k, 32), alt = f64(k, 40);
    CHECK("roll", roll, -180, 180, 0);
    CHECK("pitch", pitch, -90, 90, 0);
    CHECK("yaw", yaw, -180, 360, 0); /* the ICD says 0..360; hosts that send -180..180 are taken too */
    CHECK("latitude", lat, -90, 90, 0);
    CHECK("longitude", lon, -180, 180, 0);
    CHECK("altitude", alt, -CU_CIGI_ALT_MAX_M, CU_CIGI_ALT_MAX_M, 0);
    st->lat_deg = lat, st->lon_deg = lon, st->alt_m = alt;
    st->yaw_deg = yaw, st->pitch_deg = pitch, st->roll_deg = roll;
    st->pose_valid = 1;
    st->changed |= CU_SIM_POSE;
    return R_APPLIED;
}

/* View Control (id 16): 2-3 view id, 4 group id, 5 enables (bit 0 x, 1 y, 2 z, 3 roll, 4 pitch, 5 yaw), 6-7 entity
 * id, 8..28 x, y, z (float m, body frame), roll, pitch, yaw (float deg). Group 0 names one view, else a group. */
static int view_control(cu_cigi_ig *ig, const pkt *k, cu_sim_state *st)
{
    unsigned group = k->p[4];
    if (group ? group != ig->view_group : u16(k, 2) != ig->view_id)
        return R_SKIPPED;
    if (u16(k, 6) != ig->entity_id)
        return say(ig, R_SKIPPED, "%s: view attached to entity %u, this IG follows entity %u", k->name, u16(k, 6),
                   ig->entity_id);
    static const char *const names[6] = {"x offset", "y offset", "z offset", "roll", "pitch", "yaw"};
    static const double lo[6] = {-CU_CIGI_OFFSET_MAX_M, -CU_CIGI_OFFSET_MAX_M, -CU_CIGI_OFFSET_MAX_M, -180, -90, -180};
    static const double hi[6] = {CU_CIGI_OFFSET_MAX_M, CU_CIGI_OFFSET_MAX_M, CU_CIGI_OFFSET_MAX_M, 180, 90, 360};
    unsigned en = k->p[5] & 0x3fu;
    double v[6];
    for (int i = 0; i < 6; i++) {
        v[i] = f32(k, 8 + 4 * (size_t)i);
        if (en & 1u << i) /* a disabled field may hold anything: it is not read */
            CHECK(names[i], v[i], lo[i], hi[i], 0);
    }
    double *dst[6] = {&st->view_xyz[0], &st->view_xyz[1], &st->view_xyz[2], &st->view_roll_deg, &st->view_pitch_deg,
                      &st->view_yaw_deg};
    for (int i = 0; i < 6; i++)
        if (en & 1u << i)
            *dst[i] = v[i];
    if (en)
        st->changed |= CU_SIM_VIEW;
    return R_APPLIED;
}

/* View Definition (id 21): 2-3 view id, 4 group id, 5 enables (bit 0 near, 1 far, 2 left, 3 right, 4 top, 5 bottom;
 * 6-7 mirror), 6 pixel replication (0-2), projection (3: orthographic), reorder, view type; 8..28 near, far (m),
 * left, right, top, bottom (float, half-angles in degrees from the view axis). */
static int view_definition(cu_cigi_ig *ig, const pkt *k, cu_sim_state *st)
{
    if (u16(k, 2) != ig->view_id)
        return R_SKIPPED;
    if (k->p[6] & 8u)
        return say(ig, R_SKIPPED, "%s: view %u asks for an orthographic projection; this IG renders perspective",
                   k->name, ig->view_id);
    static const char *const names[6] = {"near", "far", "left", "right", "top", "bottom"};
    double c[6];
    if (st->frustum_valid) {
        c[0] = st->near_m, c[1] = st->far_m, c[2] = st->fov_left_deg, c[3] = st->fov_right_deg;
        c[4] = st->fov_top_deg, c[5] = st->fov_bottom_deg;
    } else {
        c[0] = CU_CIGI_DEFAULT_NEAR_M, c[1] = CU_CIGI_DEFAULT_FAR_M, c[2] = -CU_CIGI_DEFAULT_HALF_H_DEG;
        c[3] = CU_CIGI_DEFAULT_HALF_H_DEG, c[4] = CU_CIGI_DEFAULT_HALF_V_DEG, c[5] = -CU_CIGI_DEFAULT_HALF_V_DEG;
    }
    unsigned en = k->p[5] & 0x3fu;
    for (int i = 0; i < 6; i++) {
        if (!(en & 1u << i))
            continue;
        double v = f32(k, 8 + 4 * (size_t)i);
        if (i < 2)
            CHECK(names[i], v, 0, CU_CIGI_FAR_MAX_M, 1);
        else
            CHECK(names[i], v, -90, 90, 1);
        c[i] = v;
    }
    if (c[0] >= c[1])
        return say(ig, R_RANGE, "%s: near %g not nearer than far %g", k->name, c[0], c[1]);
    if (c[2] >= c[3])
        return say(ig, R_RANGE, "%s: left %g not left of right %g", k->name, c[2], c[3]);
    if (c[5] >= c[4])
        return say(ig, R_RANGE, "%s: bottom %g not below top %g", k->name, c[5], c[4]);
    st->near_m = c[0], st->far_m = c[1], st->fov_left_deg = c[2], st->fov_right_deg = c[3];
    st->fov_top_deg = c[4], st->fov_bottom_deg = c[5];
    st->frustum_valid = 1;
    ig->view_group = k->p[4];
    st->changed |= CU_SIM_FRUSTUM;
    return R_APPLIED;
}

/* Celestial Sphere Control (id 9): 2 hour, 3 minute, 4 enables (bit 4: date/time valid), 8 date as the decimal
 * number MMDDYYYY (uint32). Without date/time valid it carries nothing this IG uses. */
static int celestial(cu_cigi_ig *ig, const pkt *k, cu_sim_state *st)
{
    if (!(k->p[4] & 0x10u))
        return R_SKIPPED;
    unsigned hour = k->p[2], minute = k->p[3];
    uint32_t date = u32(k, 8);
    unsigned month = date / 1000000u, day = date / 10000u % 100u, year = date % 10000u;
    if (hour > 23)
        return say(ig, R_RANGE, "%s: hour %u outside 0..23", k->name, hour);
    if (minute > 59)
        return say(ig, R_RANGE, "%s: minute %u outside 0..59", k->name, minute);
    static const unsigned mdays[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    int leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    if (year < 1 || month < 1 || month > 12 || day < 1 || day > mdays[month - 1] || (month == 2 && day == 29 && !leap))
        return say(ig, R_RANGE, "%s: date %08lu is not a date (MMDDYYYY)", k->name, (unsigned long)date);
    st->year = (int)year, st->month = (int)month, st->day = (int)day;
    st->hour = (int)hour, st->minute = (int)minute, st->second = 0;
    st->time_valid = 1;
    st->changed |= CU_SIM_TIME;
    return R_APPLIED;
}

/* Atmosphere Control (id 10): 12 horizontal wind speed (float m/s), 20 wind direction (float deg from true north;
 * the ICD: "the direction from which the wind is blowing", as cu_sim_state keeps it). */
static int atmosphere(cu_cigi_ig *ig, const pkt *k, cu_sim_state *st)
{
    double speed = f32(k, 12), dir = f32(k, 20);
    CHECK("horizontal wind speed", speed, 0, CU_CIGI_WIND_MAX_MS, 0);
    CHECK("wind direction", dir, -360, 360, 0);
    st->wind_speed = speed;
    st->wind_from_deg = wrap360(dir);
    st->wind_valid = 1;
    st->changed |= CU_SIM_WIND;
    return R_APPLIED;
}

/* Weather Control (id 12): 4 layer id, 6 weather enable (bit 0), scud enable (1), cloud type (4-7), 7 scope (0-1:
 * 0 global), 16 scud frequency (%), 20 coverage (%), 24 base elevation, 28 thickness, 32 transition band (m),
 * 36 horizontal wind speed (m/s), 44 wind direction (deg, from). Layers 1..3 of global scope are cloud layers. */
static int weather(cu_cigi_ig *ig, const pkt *k, cu_sim_state *st)
{
    unsigned layer = k->p[4], flags = k->p[6], scope = k->p[7] & 3u;
    if (scope != 0 || layer < 1 || layer > CU_SIM_LAYERS_MAX)
        return R_SKIPPED; /* fog, rain, regional or entity weather: not clouds this IG draws */
    double scudf = f32(k, 16), cov = f32(k, 20), base = f32(k, 24), thick = f32(k, 28), trans = f32(k, 32);
    double wind = f32(k, 36), dir = f32(k, 44);
    CHECK("scud frequency", scudf, 0, 100, 0);
    CHECK("coverage", cov, 0, 100, 0);
    CHECK("base elevation", base, -CU_CIGI_LAYER_MAX_M, CU_CIGI_LAYER_MAX_M, 0);
    CHECK("thickness", thick, 0, CU_CIGI_LAYER_MAX_M, 0);
    CHECK("transition band", trans, 0, CU_CIGI_LAYER_MAX_M, 0);
    CHECK("horizontal wind speed", wind, 0, CU_CIGI_WIND_MAX_MS, 0);
    CHECK("wind direction", dir, -360, 360, 0);
    cu_sim_layer *l = &st->layers[layer - 1];
    l->enabled = (int)(flags & 1u);
    l->scud = (int)(flags >> 1 & 1u);
    l->type = (int)(flags >> 4);
    l->coverage = cov / 100.0;
    l->scud_frequency = scudf / 100.0;
    l->base_m = base, l->thickness_m = thick, l->transition_m = trans;
    l->wind_speed = wind;
    l->wind_from_deg = wrap360(dir);
    st->changed |= CU_SIM_LAYERS;
    return R_APPLIED;
}

typedef struct kind {
    uint8_t id, size;
    const char *name;
    int (*read)(cu_cigi_ig *ig, const pkt *k, cu_sim_state *st);
} kind;

static const kind kinds[] = {
    {CU_CIGI_ID_IG_CONTROL, CU_CIGI_SIZE_IG_CONTROL, "IG Control", NULL},
    {CU_CIGI_ID_ENTITY_CONTROL, CU_CIGI_SIZE_ENTITY_CONTROL, "Entity Control", entity_control},
    {CU_CIGI_ID_CELESTIAL, CU_CIGI_SIZE_CELESTIAL, "Celestial Sphere Control", celestial},
    {CU_CIGI_ID_ATMOSPHERE, CU_CIGI_SIZE_ATMOSPHERE, "Atmosphere Control", atmosphere},
    {CU_CIGI_ID_WEATHER, CU_CIGI_SIZE_WEATHER, "Weather Control", weather},
    {CU_CIGI_ID_VIEW_CONTROL, CU_CIGI_SIZE_VIEW_CONTROL, "View Control", view_control},
    {CU_CIGI_ID_VIEW_DEFINITION, CU_CIGI_SIZE_VIEW_DEFINITION, "View Definition", view_definition},
};

static const kind *find_kind(unsigned id)
{
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++)
        if (kinds[i].id == id)
            return &kinds[i];
    return NULL;
}

/* IG Control (id 1, 24 bytes in 3.2 and 3.3): 2 major version, 3 database number, 4 IG mode (bits 0-1), timestamp
 * valid (2), minor version (4-7), 6-7 magic number (sets the byte order), 8 host frame, 12 timestamp (10 us ticks),
 * 16 last IG frame. */
static int ig_control(cu_cigi_ig *ig, const uint8_t *p, unsigned size)
{
    if (size < 3)
        return say(ig, R_MALFORMED, "IG Control: %u bytes, too short for its version", size);
    if (p[2] != CU_CIGI_MAJOR)
        return say(ig, R_VERSION, "IG Control: CIGI major version %u; this IG speaks 3.3", p[2]);
    if (size == 16) /* the 3.0 and 3.1 layout: no minor version, no frame numbers */
        return say(ig, R_VERSION, "IG Control: 16 bytes is CIGI 3.0/3.1; this IG speaks 3.3");
    if (size != CU_CIGI_SIZE_IG_CONTROL)
        return say(ig, R_MALFORMED, "IG Control: size field %u, the packet has %u bytes", size,
                   CU_CIGI_SIZE_IG_CONTROL);
    unsigned minor = p[4] >> 4;
    if (minor != 2 && minor != CU_CIGI_MINOR) /* 3.2 lays out IG Control and what this IG reads as 3.3 does */
        return say(ig, R_VERSION, "IG Control: CIGI minor version %u; this IG speaks 3.3 (and 3.2)", minor);
    unsigned magic = (unsigned)p[6] << 8 | p[7];
    if (magic != CU_CIGI_MAGIC && magic != 0x0080u)
        return say(ig, R_MALFORMED, "IG Control: byte swap magic number 0x%04x, not 0x8000", magic);
    if ((p[4] & 3u) == 3)
        return say(ig, R_RANGE, "IG Control: IG mode 3 (0 standby, 1 operate, 2 debug)");
    pkt k = {p, magic == 0x0080u, "IG Control"};
    ig->swap = k.swap;
    ig->database = (int8_t)(p[3] > 127 ? (int)p[3] - 256 : (int)p[3]);
    ig->ig_mode = p[4] & 3;
    ig->timestamp_valid = p[4] >> 2 & 1;
    ig->host_frame = u32(&k, 8);
    ig->timestamp = u32(&k, 12);
    ig->last_ig_frame = u32(&k, 16);
    ig->have_frame = 1;
    return R_APPLIED;
}

static void count(cu_cigi_ig *ig, int r)
{
    cu_cigi_stats *s = &ig->stats;
    unsigned long *c[] = {&s->applied, &s->skipped, &s->malformed, &s->wrong_version, &s->nonfinite,
                          &s->out_of_range};
    ++*c[r];
}

void cu_cigi_ig_init(cu_cigi_ig *ig, uint16_t view_id, uint16_t entity_id)
{
    memset(ig, 0, sizeof *ig);
    ig->view_id = view_id;
    ig->entity_id = entity_id;
}

void cu_cigi_ig_frame_taken(cu_cigi_ig *ig)
{
    ig->have_frame = 0;
}

int cu_cigi_ig_receive(cu_cigi_ig *ig, const uint8_t *buf, size_t len, cu_sim_state *st)
{
    ig->stats.datagrams++;
    int applied = 0, trusted = 0, told_untrusted = 0;
    size_t off = 0;
    if (!buf)
        len = 0;
    while (off < len) {
        ig->stats.packets++;
        if (len - off < 2) {
            count(ig, say(ig, R_MALFORMED, "CIGI: a lone byte at offset %zu, not a packet", off));
            break;
        }
        unsigned id = buf[off], size = buf[off + 1];
        const kind *kd = find_kind(id);
        const char *name = kd ? kd->name : "packet";
        /* The size field is the only framing: when it cannot be trusted nothing after it can be found. */
        if (size < 2) {
            count(ig, say(ig, R_MALFORMED, "%s (id %u) at offset %zu: size field %u ends the datagram", name, id,
                          off, size));
            break;
        }
        if (size > len - off) {
            count(ig, say(ig, R_MALFORMED, "%s (id %u) at offset %zu: size %u runs past the end (%zu bytes left)",
                          name, id, off, size, len - off));
            break;
        }
        const uint8_t *p = buf + off;
        off += size;
        if (id == CU_CIGI_ID_IG_CONTROL) {
            int r = ig_control(ig, p, size);
            count(ig, r);
            if (r == R_VERSION)
                return applied; /* a datagram of another version: nothing in it is read as 3.3 */
            trusted = r == R_APPLIED;
            applied += trusted;
            continue;
        }
        if (!trusted) { /* before an IG Control even the byte order is unknown */
            ig->stats.untrusted++;
            if (!told_untrusted++)
                say(ig, 0, "%s (id %u) at offset %zu before a valid IG Control: not trusted", name, id, off - size);
            continue;
        }
        if (!kd) {
            ig->stats.skipped_unknown++;
            continue;
        }
        if (size != kd->size) {
            count(ig, say(ig, R_MALFORMED, "%s: size field %u, the packet has %u bytes", name, size, kd->size));
            continue;
        }
        pkt k = {p, ig->swap, name};
        int r = kd->read(ig, &k, st);
        count(ig, r);
        applied += r == R_APPLIED;
    }
    return applied;
}

static void put32(uint8_t *b, uint32_t v)
{
    b[0] = (uint8_t)(v >> 24), b[1] = (uint8_t)(v >> 16), b[2] = (uint8_t)(v >> 8), b[3] = (uint8_t)v;
}

/* Start of Frame (id 101, 24 bytes): 2 major version, 3 database number, 4 IG status, 5 IG mode (bits 0-1),
 * timestamp valid (2), earth reference model (3: 0 WGS 84), minor version (4-7), 6-7 magic number, 8 IG frame,
 * 12 timestamp, 16 last host frame, 20-23 reserved. */
size_t cu_cigi_start_of_frame(const cu_cigi_ig *ig, uint32_t ig_frame, uint32_t timestamp_10us, uint8_t status,
                              uint8_t *out, size_t cap)
{
    if (cap < CU_CIGI_SIZE_START_OF_FRAME)
        return 0;
    memset(out, 0, CU_CIGI_SIZE_START_OF_FRAME);
    out[0] = CU_CIGI_ID_START_OF_FRAME;
    out[1] = CU_CIGI_SIZE_START_OF_FRAME;
    out[2] = CU_CIGI_MAJOR;
    out[3] = (uint8_t)ig->database;
    out[4] = status;
    out[5] = (uint8_t)((ig->ig_mode & 3) | 1 << 2 | CU_CIGI_MINOR << 4);
    out[6] = CU_CIGI_MAGIC >> 8, out[7] = CU_CIGI_MAGIC & 0xff;
    put32(out + 8, ig_frame);
    put32(out + 12, timestamp_10us);
    put32(out + 16, ig->host_frame);
    return CU_CIGI_SIZE_START_OF_FRAME;
}
