/* platform/sim/fgfs.h: decodes the lines FlightGear's generic protocol sends with data/flightgear/cumulo.xml. */
#ifndef CU_PLATFORM_SIM_FGFS_H
#define CU_PLATFORM_SIM_FGFS_H
#include <stddef.h>
#include "sim_state.h"

/* The fields of one line, in the order of the <chunk>s of data/flightgear/cumulo.xml (whose <name>s are these; the
 * test reads the XML and compares). Run FlightGear with the file in $FG_ROOT/Protocol/ and
 *   fgfs --generic=socket,out,30,127.0.0.1,5510,udp,cumulo
 * to get one line per datagram, 30 times a second: comma-separated numbers ending in a newline. */
enum {
    CU_FGFS_LAT, CU_FGFS_LON, CU_FGFS_ALT, CU_FGFS_HEADING, CU_FGFS_PITCH, CU_FGFS_ROLL,
    CU_FGFS_YEAR, CU_FGFS_MONTH, CU_FGFS_DAY, CU_FGFS_HOUR, CU_FGFS_MINUTE, CU_FGFS_SECOND, CU_FGFS_FOV,
    CU_FGFS_FIELDS
};
/* The field's name as the XML and the messages give it ("altitude-m"); NULL outside 0..CU_FGFS_FIELDS-1. */
const char *cu_fgfs_field_name(int field);

/* A line longer than this is rejected unread (13 numbers printed as the XML prints them take about 130 bytes). */
#define CU_FGFS_LINE_MAX 512

/* Decodes one datagram of len bytes (not NUL-terminated). It holds one line, usually ending in "\n" (or "\r\n"); of
 * several lines the last one counts (a datagram arrives whole, so the text after the last newline, if any, is a line
 * too). Strict: exactly CU_FGFS_FIELDS fields, each a decimal number (blanks around it allowed, "nan", "inf" and hex
 * not), in range: latitude -90..90, longitude -180..180, altitude -1e4..1e6 m, heading, pitch and roll |x| <= 1e4
 * degrees, a real date (month 1..12, the day within the month, leap years Gregorian, year 1..9999), hour 0..23,
 * minute 0..59, second 0 <= s < 61 (a leap second), the field of view 1..179 degrees; the calendar fields whole.
 *
 * On success returns 0 and sets st's pose (yaw = the true heading) and time (UTC), pose_valid and time_valid, and
 * CU_SIM_POSE | CU_SIM_TIME in st->changed; nothing else of st. FlightGear's field of view is the full horizontal
 * angle of a landscape window (its viewer scales the larger dimension), which the frustum's four half-angles cannot
 * say without the window's aspect ratio: it goes to *hfov_deg (when hfov_deg is not NULL) for the IG to apply with
 * its own aspect ratio, and the frustum is left alone.
 * On failure returns -1, leaves st and *hfov_deg unchanged and writes a one-line message naming the field, e.g.
 * "fgfs: field 3 (altitude-m): 'abc' is not a number"; bytes of the datagram in it are escaped (\xHH), so no control
 * byte reaches a log. */
int cu_fgfs_parse(const char *buf, size_t len, cu_sim_state *st, double *hfov_deg, char *err, size_t errlen);

#endif
