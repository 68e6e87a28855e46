/* platform/sim/cigi.h: CIGI 3.3 (SISO-STD-013) for the image generator's side: decodes the packets a host sends into
 * cu_sim_state and encodes the Start of Frame the IG answers with. Pure code: no sockets, no allocation, no globals.
 * Layouts follow Wireshark's CIGI dissector (epan/dissectors/packet-cigi.c, the 3.3 definitions). */
#ifndef CU_PLATFORM_CIGI_H
#define CU_PLATFORM_CIGI_H

#include <stddef.h>
#include <stdint.h>
#include "sim_state.h"

/* Packet ids and sizes (bytes) of the packets this IG reads or writes. Every one of them has a fixed size in 3.3: a
 * size field that differs from it is malformed. */
enum {
    CU_CIGI_ID_IG_CONTROL = 1, CU_CIGI_ID_ENTITY_CONTROL = 2, CU_CIGI_ID_CELESTIAL = 9, CU_CIGI_ID_ATMOSPHERE = 10,
    CU_CIGI_ID_WEATHER = 12, CU_CIGI_ID_VIEW_CONTROL = 16, CU_CIGI_ID_VIEW_DEFINITION = 21,
    CU_CIGI_ID_START_OF_FRAME = 101
};
enum {
    CU_CIGI_SIZE_IG_CONTROL = 24, CU_CIGI_SIZE_ENTITY_CONTROL = 48, CU_CIGI_SIZE_CELESTIAL = 16,
    CU_CIGI_SIZE_ATMOSPHERE = 32, CU_CIGI_SIZE_WEATHER = 56, CU_CIGI_SIZE_VIEW_CONTROL = 32,
    CU_CIGI_SIZE_VIEW_DEFINITION = 32, CU_CIGI_SIZE_START_OF_FRAME = 24
};
#define CU_CIGI_MAJOR 3          /* Major Version, byte 2 of IG Control and Start of Frame */
#define CU_CIGI_MINOR 3          /* Minor Version (high nibble of byte 4 in IG Control, of byte 5 in SOF): 3 = 3.3 */
#define CU_CIGI_MAGIC 0x8000u    /* Byte Swap Magic Number, bytes 6..7: read as 0x0080 the sender is little-endian */

/* The limits a decoded value must keep, else its packet is rejected (the ICD's ranges, where it gives one; a bound
 * the renderer can take where it gives none). */
#define CU_CIGI_ALT_MAX_M 1e6           /* |altitude| */
#define CU_CIGI_OFFSET_MAX_M 1e5        /* |view offset| */
#define CU_CIGI_FAR_MAX_M 1e9           /* far plane */
#define CU_CIGI_LAYER_MAX_M 1e5         /* |base elevation|, thickness, transition band */
#define CU_CIGI_WIND_MAX_MS 300.0       /* horizontal wind speed */

/* The frustum the IG renders before a View Definition has set one (CIGI leaves the default to the IG): the fields a
 * first View Definition does not enable come from here. */
#define CU_CIGI_DEFAULT_HALF_H_DEG 30.0
#define CU_CIGI_DEFAULT_HALF_V_DEG 20.0
#define CU_CIGI_DEFAULT_NEAR_M 1.0
#define CU_CIGI_DEFAULT_FAR_M 1e6

/* What happened to every packet: each packet counted in `packets` is counted in exactly one of the others (a datagram
 * dropped for its version counts its IG Control in wrong_version and reads nothing after it). */
typedef struct cu_cigi_stats {
    unsigned long datagrams;        /* calls of cu_cigi_ig_receive */
    unsigned long packets;          /* packet headers met (a lone trailing byte counts as one, malformed) */
    unsigned long applied;          /* changed cu_sim_state (or, IG Control, the IG's frame) */
    unsigned long skipped;          /* known and sound, but not for this IG (other entity, view, layer, scope) */
    unsigned long skipped_unknown;  /* an id this IG does not read, passed over by its size field */
    unsigned long malformed;        /* size field 0, 1, past the end or not the packet's size; bad magic number */
    unsigned long wrong_version;    /* IG Control not of CIGI 3.2/3.3: its datagram is dropped */
    unsigned long untrusted;        /* before a valid IG Control in its datagram */
    unsigned long nonfinite;        /* a NaN or infinity in a field the IG uses */
    unsigned long out_of_range;     /* a finite value outside its range (latitude 91, hour 24, 31 February...) */
} cu_cigi_stats;

typedef struct cu_cigi_ig {
    uint16_t view_id;        /* the view this IG renders (View Control/Definition for other views are skipped) */
    uint8_t view_group;      /* its view group (0: none), as the last View Definition for view_id assigned it */
    uint16_t entity_id;      /* the ownship whose Entity Control moves the eyepoint, default 0 */
    int swap;                /* 1: the host writes little-endian (its magic number read 0x0080), 0: big-endian */
    int8_t database;         /* IG Control's database number, echoed in Start of Frame */
    uint32_t host_frame;     /* last IG Control's host frame number */
    uint32_t last_ig_frame;  /* the IG frame number the host last saw (IG Control) */
    int have_frame;          /* an IG Control has arrived since the last cu_cigi_ig_frame_taken */
    int ig_mode;             /* from IG Control: 0 standby, 1 operate, 2 debug */
    uint32_t timestamp;      /* IG Control's timestamp, 10 us ticks */
    int timestamp_valid;
    cu_cigi_stats stats;
    char last_error[160];    /* the latest problem, one line naming the packet and the field, for the log */
} cu_cigi_ig;

/* Starts an IG that renders view `view_id` from entity `entity_id`: no frame yet, big-endian, standby, stats zero. */
void cu_cigi_ig_init(cu_cigi_ig *ig, uint16_t view_id, uint16_t entity_id);

/* Decodes one datagram from the host into st and returns the number of packets applied (>= 0). Sets st->changed bits
 * (CU_SIM_*) for what it set and leaves every other field as it was; a rejected packet changes nothing. The datagram
 * must open with an IG Control (its magic number sets the byte order of what follows); packets before a valid one
 * are untrusted, a wrong major version drops the datagram, a broken size field ends it. Never reads outside
 * buf[0..len), never allocates, and takes time linear in len whatever the bytes are. */
int cu_cigi_ig_receive(cu_cigi_ig *ig, const uint8_t *buf, size_t len, cu_sim_state *st);

/* Marks the IG Control of this frame as used: have_frame = 0 until the next one arrives. */
void cu_cigi_ig_frame_taken(cu_cigi_ig *ig);

/* Writes Start of Frame into out (24 bytes, big-endian): version 3.3, the database number of the last IG Control,
 * `status` (IG Status Code, 0 = normal), the IG mode the host asked for, timestamp valid, WGS 84, `ig_frame`,
 * `timestamp_10us` and the last host frame number. Returns 24, or 0 (writing nothing) when cap < 24. */
size_t cu_cigi_start_of_frame(const cu_cigi_ig *ig, uint32_t ig_frame, uint32_t timestamp_10us, uint8_t status,
                              uint8_t *out, size_t cap);

#endif
