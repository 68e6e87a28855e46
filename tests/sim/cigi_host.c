/* tests/sim/cigi_host.c: a small CIGI 3.3 host for the tests of `cumulo ig`: it plays a fixed script of frames in
 * synchronous mode (each frame's datagram goes out once the IG's Start of Frame says it drew the one before), checks
 * every Start of Frame, sends hostile datagrams between frames, and logs what it sent, one line a frame, for the test
 * to compare with what the IG drew.
 *
 *   cigi_host IG_ADDR:PORT LISTEN_PORT WIDTH HEIGHT VFOV LAT0 LON0 ALT0 > host.log
 *
 * The script, by host frame number (the IG's trace lines carry it):
 *   1-4    "move": the ownship flies north, east, climbs and turns (heading 0, 90, 180, 270; pitch 5; roll 0, 10);
 *   5-12   "day": the ownship at the origin + 300 m, 21 June 2026 every three hours from 00:30;
 *   13-19  "cover": a cumulus layer (layer 1, base ALT0 + 1200 m, 1500 m thick) at coverage 0, 20, 40, 60 % then
 *          held at 60 % for three frames, with a global west wind of 10 m/s (Atmosphere Control); the eye at the
 *          origin + 300 m looking north, 15 degrees up;
 *   20-24  "hostile": before each frame a burst of bad datagrams (see hostile()), then a valid frame as in "cover";
 *          when a burst opens with a sound IG Control the IG draws the frame before again (logged "repeat before
 *          host frame K"), and it is waited for (3 s at most), so that the repeat is a frame of its own.
 * The frustum is the symmetric one of VFOV (vertical, degrees) at WIDTH x HEIGHT, so a scene file with the same
 * [camera] fov draws the same picture. Every frame also defines view 1 (the same frustum, turned right by its full
 * width: a second channel edge to edge with view 0), and frame 4 moves view 0 off the entity (10 m forward, 2 m up,
 * 30 degrees right); the log's view0= and view1= say so (x, y, z, yaw). Every frame's IG Control is big-endian except frames 3 and 16 (little-endian).
 * Exits 0 when every Start of Frame was right and arrived in time (60 s a frame), 1 otherwise. */
#include "cigi_encode.h"
#include <arpa/inet.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#define FRAMES 24
#define DEG (3.14159265358979323846 / 180.0)

static int fd;
static struct sockaddr_in ig;
static double lat0, lon0, alt0, hfov, vfov;
static int failures;

static void send_buf(const uint8_t *b, size_t n)
{
    if (sendto(fd, b, n, 0, (struct sockaddr *)&ig, sizeof ig) != (ssize_t)n) {
        perror("cigi_host: sendto");
        failures++;
    }
}

typedef struct frame_plan {
    const char *phase;
    double lat, lon, alt, yaw, pitch, roll;
    int hour, minute;
    double coverage;       /* < 0: no weather packet */
} frame_plan;

static frame_plan plan(int k)
{
    frame_plan p = { "move", lat0, lon0, alt0 + 500, 0, 5, 0, 12, 0, -1 };
    if (k <= 4) {
        p.lat = lat0 + 0.01 * (k >= 2);
        p.lon = lon0 + 0.01 * (k >= 3);
        p.alt = alt0 + 500 + 250 * (k - 1);
        p.yaw = 90 * (k - 1);
        p.roll = k % 2 ? 0 : 10;
    } else if (k <= 12) {
        p.phase = "day";
        p.alt = alt0 + 300;
        p.hour = 3 * (k - 5);
        p.minute = 30;
    } else {
        static const double cover[] = { 0, 0.2, 0.4, 0.6, 0.6, 0.6, 0.6 };
        p.phase = k <= 19 ? "cover" : "hostile";
        p.alt = alt0 + 300;
        p.pitch = 15;
        p.coverage = k <= 19 ? cover[k - 13] : 0.6;
    }
    return p;
}

static size_t frame_datagram(int k, uint8_t *b, size_t cap)
{
    frame_plan p = plan(k);
    int swap = k == 3 || k == 16;
    size_t n = 0;
    cu_cigi_enc_ig_control igc = { .ig_mode = 1, .timestamp_valid = 1, .host_frame = (uint32_t)k,
                                   .timestamp = 0 /* the clouds hold still: the pictures compare */ };
    n += cu_cigi_enc_ig_control_put(&igc, swap, b + n, cap - n);
    cu_cigi_enc_entity e = { .entity_id = 0, .state = 1, .roll = (float)p.roll, .pitch = (float)p.pitch,
                             .yaw = (float)p.yaw, .lat = p.lat, .lon = p.lon, .alt = p.alt };
    n += cu_cigi_enc_entity_put(&e, swap, b + n, cap - n);
    cu_cigi_enc_view_def vd = { .view_id = 0, .enable = 0x3f, .near_m = 1, .far_m = 100000,
                                .left = (float)-hfov, .right = (float)hfov, .top = (float)vfov,
                                .bottom = (float)-vfov };
    n += cu_cigi_enc_view_def_put(&vd, swap, b + n, cap - n);
    vd.view_id = 1; /* the second channel: the same frustum ... */
    n += cu_cigi_enc_view_def_put(&vd, swap, b + n, cap - n);
    /* ... turned right by its full width, so its left edge meets view 0's right edge */
    cu_cigi_enc_view_control vc1 = { .view_id = 1, .enable = CU_CIGI_EN_YAW, .yaw = (float)(2 * hfov) };
    n += cu_cigi_enc_view_control_put(&vc1, swap, b + n, cap - n);
    /* frame 4 moves view 0 off the entity: 10 m forward, 2 m up, looking 30 degrees right; the others put it back
     * (a View Control holds until the next one says otherwise) */
    double vx = k == 4 ? 10 : 0, vz = k == 4 ? -2 : 0, vyaw = k == 4 ? 30 : 0;
    cu_cigi_enc_view_control vc0 = { .view_id = 0, .enable = 0x3f, .x = (float)vx, .z = (float)vz,
                                     .yaw = (float)vyaw };
    n += cu_cigi_enc_view_control_put(&vc0, swap, b + n, cap - n);
    cu_cigi_enc_celestial c = { .hour = (uint8_t)p.hour, .minute = (uint8_t)p.minute, .sun = 1, .date_valid = 1,
                                .date = 6212026 };
    n += cu_cigi_enc_celestial_put(&c, swap, b + n, cap - n);
    if (p.coverage >= 0) { /* a west wind of 10 m/s; the layer gives none of its own, so it takes this one */
        cu_cigi_enc_atmosphere atm = { .model_enable = 0, .wind_speed = 10, .wind_dir = 270, .visibility = 50000 };
        n += cu_cigi_enc_atmosphere_put(&atm, swap, b + n, cap - n);
        cu_cigi_enc_weather w = { .layer_id = 1, .enable = 1, .cloud_type = 7, .scope = 0,
                                  .coverage = (float)(100 * p.coverage), .base = (float)(alt0 + 1200),
                                  .thickness = 1500, .visibility = 50000 };
        n += cu_cigi_enc_weather_put(&w, swap, b + n, cap - n);
    }
    printf("host frame=%d phase=%s lat=%.9f lon=%.9f alt=%.3f yaw=%.3f pitch=%.3f roll=%.3f "
           "utc=2026-06-21T%02d:%02d:00Z coverage=%.2f view0=%g,0,%g,%g view1=0,0,0,%.9f\n", k, p.phase, p.lat, p.lon,
           p.alt, p.yaw, p.pitch, p.roll, p.hour, p.minute, p.coverage, vx, vz, vyaw, (double)(float)(2 * hfov));
    fflush(stdout);
    return n;
}

/* The bad datagrams sent before frame k (20..24); each must be counted and skipped by the IG. */
static void hostile(int k)
{
    uint8_t b[2048];
    /* their IG Controls are sound and repeat the frame drawn last: the IG may draw it again, never a frame to come */
    cu_cigi_enc_ig_control igc = { .ig_mode = 1, .host_frame = (uint32_t)(k - 1) };
    size_t n = cu_cigi_enc_ig_control_put(&igc, 0, b, sizeof b);
    switch (k) {
    case 20: { /* truncated: an Entity Control cut in half; a size field of 0; a lone byte */
        cu_cigi_enc_entity e = { .state = 1, .lat = 10, .lon = 10, .alt = 10 };
        size_t m = cu_cigi_enc_entity_put(&e, 0, b + n, sizeof b - n);
        send_buf(b, n + m / 2);
        b[n] = 2;
        b[n + 1] = 0;
        send_buf(b, n + 48);
        send_buf(b, 1);
        break;
    }
    case 21: { /* oversized size fields and unknown packet ids */
        cu_cigi_enc_entity e = { .state = 1, .lat = 10, .lon = 10, .alt = 10, .size = 255 };
        size_t m = cu_cigi_enc_entity_put(&e, 0, b + n, sizeof b - n);
        send_buf(b, n + m);
        b[n] = 200;     /* an id nobody defines, skipped by its size */
        b[n + 1] = 16;
        memset(b + n + 2, 0xee, 14);
        send_buf(b, n + 16);
        break;
    }
    case 22: { /* wrong major version; a wrong magic number */
        cu_cigi_enc_ig_control bad = { .major = 2, .ig_mode = 1, .host_frame = 9998 } /* dropped */;
        send_buf(b, cu_cigi_enc_ig_control_put(&bad, 0, b, sizeof b));
        cu_cigi_enc_ig_control mag = { .magic = 0x1234, .ig_mode = 1, .host_frame = 9997 }; /* dropped */
        send_buf(b, cu_cigi_enc_ig_control_put(&mag, 0, b, sizeof b));
        break;
    }
    case 23: { /* NaN and huge values */
        cu_cigi_enc_entity e = { .state = 1, .lat = NAN, .lon = 10, .alt = 10 };
        send_buf(b, n + cu_cigi_enc_entity_put(&e, 0, b + n, sizeof b - n));
        cu_cigi_enc_entity h = { .state = 1, .lat = 10, .lon = 10, .alt = 1e300 };
        send_buf(b, n + cu_cigi_enc_entity_put(&h, 0, b + n, sizeof b - n));
        cu_cigi_enc_view_def v = { .enable = 0x3f, .left = 89.9f, .right = -89.9f, .top = INFINITY, .bottom = 0 };
        send_buf(b, n + cu_cigi_enc_view_def_put(&v, 0, b + n, sizeof b - n));
        cu_cigi_enc_weather w = { .layer_id = 1, .enable = 1, .cloud_type = 7, .coverage = 1e30f, .thickness = 1 };
        send_buf(b, n + cu_cigi_enc_weather_put(&w, 0, b + n, sizeof b - n));
        break;
    }
    case 24: /* a flood: 2000 datagrams of packets before any IG Control */
        for (int i = 0; i < 2000; i++) {
            cu_cigi_enc_entity e = { .state = 1, .lat = 10, .lon = 10, .alt = 10 };
            send_buf(b, cu_cigi_enc_entity_put(&e, 0, b, sizeof b));
        }
        { /* the IG drains them; the kernel has dropped what overflowed its buffer, not our frame */
            struct timespec pause = { 0, 500000000 };
            nanosleep(&pause, NULL);
        }
        break;
    }
}

/* Waits for the Start of Frame that says the IG drew host frame k (or, with `any`, for whichever comes first: a
 * frame drawn again); checks every one that comes. Returns 0, or -1 when none came within timeout_ms. */
static int await_sof(int k, uint32_t *last_ig, int timeout_ms, int any)
{
    for (;;) {
        struct pollfd p = { .fd = fd, .events = POLLIN };
        if (poll(&p, 1, timeout_ms) <= 0) {
            if (!any)
                fprintf(stderr, "cigi_host: no Start of Frame for host frame %d within %d ms\n", k, timeout_ms);
            return -1;
        }
        uint8_t b[512];
        ssize_t n = recv(fd, b, sizeof b, 0);
        cu_cigi_dec_sof s;
        if (n < 0 || cu_cigi_dec_sof_get(b, (size_t)n, &s) || s.major != 3 || s.minor != 3 || s.swap ||
            s.last_host_frame > (uint32_t)k || (*last_ig != UINT32_MAX && s.ig_frame != *last_ig + 1)) {
            fprintf(stderr, "cigi_host: a wrong Start of Frame (%zd bytes) before host frame %d\n", n, k);
            failures++;
            if (n < 0)
                return -1;
            continue;
        }
        *last_ig = s.ig_frame;
        printf("sof ig_frame=%u last_host_frame=%u ig_mode=%u status=%u\n", s.ig_frame, s.last_host_frame,
               s.ig_mode, s.status);
        fflush(stdout);
        if (any || s.last_host_frame == (uint32_t)k)
            return 0;
    }
}

int main(int argc, char **argv)
{
    if (argc != 9) {
        fprintf(stderr, "usage: cigi_host IG_ADDR:PORT LISTEN_PORT WIDTH HEIGHT VFOV LAT0 LON0 ALT0\n");
        return 2;
    }
    char host[64];
    snprintf(host, sizeof host, "%s", argv[1]);
    char *colon = strrchr(host, ':');
    if (!colon)
        return 2;
    *colon = 0;
    memset(&ig, 0, sizeof ig);
    ig.sin_family = AF_INET;
    ig.sin_port = htons((uint16_t)atoi(colon + 1));
    inet_pton(AF_INET, host, &ig.sin_addr);
    double w = atof(argv[3]), h = atof(argv[4]);
    vfov = 0.5 * atof(argv[5]);
    hfov = atan(tan(vfov * DEG) * w / h) / DEG;
    lat0 = atof(argv[6]);
    lon0 = atof(argv[7]);
    alt0 = atof(argv[8]);
    fd = socket(AF_INET, SOCK_DGRAM, 0);
    struct sockaddr_in me = { .sin_family = AF_INET, .sin_port = htons((uint16_t)atoi(argv[2])) };
    me.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd < 0 || bind(fd, (struct sockaddr *)&me, sizeof me)) {
        perror("cigi_host: bind");
        return 1;
    }
    uint32_t last_ig = UINT32_MAX;
    uint8_t b[1024];
    for (int k = 1; k <= FRAMES; k++) {
        if (k >= 20)
            hostile(k);
        /* the bursts before frames 20, 21 and 23 open with a sound IG Control (the frame before, without a
         * timestamp): the IG draws that frame again, on its own when we wait for it, then the next */
        if ((k == 20 || k == 21 || k == 23) && await_sof(k - 1, &last_ig, 3000, 1) == 0)
            printf("repeat before host frame %d\n", k);
        send_buf(b, frame_datagram(k, b, sizeof b));
        if (await_sof(k, &last_ig, 60000, 0))
            return 1;
    }
    close(fd);
    return failures ? 1 : 0;
}
