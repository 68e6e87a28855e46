/* platform/sim/sim_link.h: one link from a host simulation to `cumulo ig`: the --input grammar (cigi, fg, xplane), its
 * UDP socket, the protocol's decoder filling a cu_sim_state, and what the IG sends back (CIGI Start of Frame, X-Plane's
 * RREF subscriptions). */
#ifndef CU_PLATFORM_SIM_LINK_H
#define CU_PLATFORM_SIM_LINK_H
#include "cigi.h"
#include "sim_state.h"
#include "udp.h"
#include "xplane.h"
#include <stddef.h>
#include <stdint.h>

typedef enum cu_sim_proto { CU_SIM_CIGI = 1, CU_SIM_FG, CU_SIM_XPLANE } cu_sim_proto;

typedef struct cu_sim_link_spec {
    cu_sim_proto proto;
    cu_udp_addr listen;     /* where we receive */
    cu_udp_addr peer;       /* cigi: where Start of Frame goes (has_peer 0: the sender of the host's datagrams);
                               xplane: X-Plane's UDP port, where the subscriptions go */
    int has_peer;
    int view_id, entity_id; /* cigi: the view this IG draws and the ownship */
    int freq;               /* xplane: RREF replies a second */
    int year;               /* xplane: the year (X-Plane sends the day of the year only; 0: the caller's) */
} cu_sim_link_spec;

/* The most datagrams read in one cu_sim_link_poll: a flood waits in the socket (and the kernel drops the overflow)
 * while the IG goes on drawing frames. */
#define CU_SIM_POLL_MAX 256
#define CU_SIM_DATAGRAM_MAX 65536

typedef struct cu_sim_link {
    cu_sim_link_spec spec;
    int fd;
    cu_udp_addr host;       /* the last sender (cigi's Start of Frame goes there without a peer) */
    int have_host;
    cu_cigi_ig cigi;
    cu_xplane_rx xp;
    unsigned long datagrams, rejected, oversized, send_errors;
    int frame_ready;        /* a new frame's data arrived (cigi: an IG Control; fg, xplane: an accepted datagram) */
    uint64_t frame_rx_ns;   /* when the datagram that made it ready arrived (CLOCK_MONOTONIC) */
    char last_error[256];   /* the latest problem, for the log; "" when read */
    uint8_t buf[CU_SIM_DATAGRAM_MAX];
} cu_sim_link;

/*   cigi:[ADDR:]PORT[,host=HOST:PORT][,view=N][,entity=N]   (default port 8004)
 *   fg:[ADDR:]PORT
 *   xplane:HOST:PORT[,local=PORT][,freq=HZ][,year=Y]       (X-Plane listens on 49000)
 * 0, or -1 with a one-line message naming the field. */
int  cu_sim_link_parse(const char *s, cu_sim_link_spec *out, char *err, size_t n);
/* Opens the socket (xplane: and subscribes): 0, or -1 with a message. */
int  cu_sim_link_open(cu_sim_link *l, const cu_sim_link_spec *spec, char *err, size_t n);
/* Reads up to CU_SIM_POLL_MAX waiting datagrams into st (now_ns: their arrival time); returns how many were read. */
int  cu_sim_link_poll(cu_sim_link *l, cu_sim_state *st, uint64_t now_ns);
/* cigi: sends Start of Frame for ig_frame (echoing the host's frame number) when a host is known; 0 when sent or
 * nothing to send, -1 on a send error (counted, message in last_error). */
int  cu_sim_link_start_frame(cu_sim_link *l, uint32_t ig_frame, uint32_t timestamp_10us);
/* "cigi listen=0.0.0.0:8004 view=0 entity=0" */
void cu_sim_link_describe(const cu_sim_link *l, char *buf, size_t n);
/* xplane: unsubscribes (freq 0); closes the socket. */
void cu_sim_link_close(cu_sim_link *l);

#endif
