/* platform/sim/xplane.h: X-Plane's UDP dataref interface (RREF, X-Plane 10.40 to 12): requests and reply decoding. */
#ifndef CU_PLATFORM_SIM_XPLANE_H
#define CU_PLATFORM_SIM_XPLANE_H
#include <stddef.h>
#include <stdint.h>
#include "sim_state.h"

/* The wire format (all little-endian), as the sources named in xplane.c give it:
 *   request, to X-Plane's port (49000 by default): "RREF" NUL, int32 frequency (sends per second, 0 stops), int32
 *     index (the client's id for the dataref), char[400] the dataref's path padded with NULs: 413 bytes;
 *   reply, from X-Plane to the port the request came from: "RREF" and one byte (',' from X-Plane 11 on, 'O' in
 *     X-Plane 10), then records of int32 index and float32 value, 8 bytes each, as many as fit in a datagram.
 *
 * The datarefs cumulo subscribes to; the enum value is the index each is requested with. The attitude is the
 * true_* set, relative to the earth below the aircraft (psi, theta and phi are relative to X-Plane's local OpenGL
 * frame, whose north is that of its reference point, not of the aircraft). Elevation is metres above mean sea level.
 * X-Plane has no year dataref and its date is local: the day of year is local_date_days (0 = January 1st), moved to
 * the UTC date by the difference between local_time_sec and zulu_time_sec when both came (across New Year too);
 * the year is the caller's, that of X-Plane's local date (cu_xplane_rx_init: the IG passes the current year, or the
 * one a --set gives, as X-Plane's date follows the computer's clock unless the user moved it).
 *
 * Precision: every value travels as a float32 (24 significant bits), whatever the dataref's type (latitude and
 * longitude are doubles in X-Plane). A latitude between 32 and 64 degrees moves in steps of 2^-18 degree, about
 * 0.4 m; a longitude beyond 128 degrees in steps of 2^-16 degree, up to 1.7 m at the equator; altitude in steps under
 * 1 mm below 16 km; zulu seconds after 18:12 in steps of 1/128 s. That is X-Plane's limit, not ours. */
enum {
    CU_XPLANE_LAT, CU_XPLANE_LON, CU_XPLANE_ELEV, CU_XPLANE_HEADING, CU_XPLANE_PITCH, CU_XPLANE_ROLL,
    CU_XPLANE_ZULU_SEC, CU_XPLANE_LOCAL_SEC, CU_XPLANE_DATE_DAYS, CU_XPLANE_FOV,
    CU_XPLANE_REFS
};
/* The dataref's path ("sim/flightmodel/position/latitude"); NULL outside 0..CU_XPLANE_REFS-1. */
const char *cu_xplane_dataref(int index);

#define CU_XPLANE_REQUEST_SIZE 413
#define CU_XPLANE_PATH_MAX 400      /* the path's field, its NUL included */

/* Writes the 413-byte request for `dataref` (a path of 1..399 printable ASCII bytes) at `freq` sends per second
 * (0..1000; 0 unsubscribes) under `index` into out. Returns 413, or 0 (out untouched) when cap is too small or an
 * argument is out of range. */
size_t cu_xplane_rref_request(uint8_t *out, size_t cap, int freq, int index, const char *dataref);

/* What the decoder has seen: the latest value of each dataref (have: bit i for val[i]), the year the date goes in,
 * and counts for the IG's status line. Plain data; zeroed by cu_xplane_rx_init. */
typedef struct cu_xplane_rx {
    int year;
    unsigned have;
    double val[CU_XPLANE_REFS];
    unsigned long datagrams;      /* accepted */
    unsigned long rejected;       /* refused whole: bad header, length or value */
    unsigned long unknown;        /* records with an index we never asked for (skipped) */
    unsigned long bad_values;     /* records with a NaN, infinite or out-of-range value */
} cu_xplane_rx;
void cu_xplane_rx_init(cu_xplane_rx *rx, int year);

/* Decodes one reply datagram of len bytes. A datagram is taken whole or not at all: a wrong header, a length that is
 * not 5 + 8n, or a value of a known index that is not finite, out of its range or (the day of year) not whole refuses
 * it, counted, with st, *hfov_deg and rx's values unchanged and a one-line message naming the record and the dataref,
 * e.g. "xplane: record 3 (index 2, sim/flightmodel/position/elevation): nan is not a finite number". Records of
 * unknown indices are counted and skipped. Ranges: latitude -90..90, longitude -180..180, elevation -1e4..1e6 m,
 * attitude |x| <= 1e4 degrees, seconds 0..86400, day of year 0..365, field of view 1..179 degrees.
 *
 * Returns 0 on an accepted datagram. Its values join rx's; then, once rx holds position and attitude (all six),
 * a datagram that brought any of them sets st's pose, pose_valid and CU_SIM_POSE, and once rx holds zulu seconds and
 * the day of year (and a year in 1..9999), one that brought either sets st's time, time_valid and CU_SIM_TIME. The
 * horizontal field of view (X-Plane's field_of_view_deg is the full horizontal angle) goes to *hfov_deg (hfov_deg
 * may be NULL) when the datagram carried it, for the IG to apply with its aspect ratio; the frustum is left alone.
 * Returns -1 on a refused one. Never reads outside buf[0..len), allocates nothing. */
int cu_xplane_parse(cu_xplane_rx *rx, const uint8_t *buf, size_t len, cu_sim_state *st, double *hfov_deg, char *err,
                    size_t errlen);

#endif
