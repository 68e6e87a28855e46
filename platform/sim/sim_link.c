/* platform/sim/sim_link.c: a host simulation's link to `cumulo ig` (sim_link.h): the --input grammar, the socket,
 * and the protocol on it. */
#include "sim_link.h"
#include "fgfs.h"
#include <arpa/inet.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The option's value after "name=" in a ",name=value" list item, copied into out; 1 when item starts with it. */
static int opt_value(const char *item, size_t len, const char *name, char *out, size_t cap)
{
    size_t nl = strlen(name);
    if (len <= nl || strncmp(item, name, nl) || item[nl] != '=')
        return 0;
    size_t vl = len - nl - 1;
    if (vl >= cap)
        vl = cap - 1;
    memcpy(out, item + nl + 1, vl);
    out[vl] = 0;
    return 1;
}

static int whole(const char *v, long lo, long hi, int *out)
{
    char *end;
    long x = strtol(v, &end, 10);
    if (end == v || *end || x < lo || x > hi)
        return -1;
    *out = (int)x;
    return 0;
}

int cu_sim_link_parse(const char *s, cu_sim_link_spec *out, char *err, size_t n)
{
    cu_sim_link_spec sp;
    memset(&sp, 0, sizeof sp);
    const char *colon = strchr(s, ':');
    size_t kl = colon ? (size_t)(colon - s) : strlen(s);
    if (kl == 4 && !strncmp(s, "cigi", 4))
        sp.proto = CU_SIM_CIGI;
    else if (kl == 2 && !strncmp(s, "fg", 2))
        sp.proto = CU_SIM_FG;
    else if (kl == 6 && !strncmp(s, "xplane", 6))
        sp.proto = CU_SIM_XPLANE;
    else {
        snprintf(err, n, "'%.60s': expected cigi:[ADDR:]PORT, fg:[ADDR:]PORT or xplane:HOST:PORT", s);
        return -1;
    }
    char addr[300] = "";
    const char *rest = colon ? colon + 1 : "";
    const char *comma = strchr(rest, ',');
    size_t al = comma ? (size_t)(comma - rest) : strlen(rest);
    if (al >= sizeof addr) {
        snprintf(err, n, "'%.60s': the address is too long", s);
        return -1;
    }
    memcpy(addr, rest, al);
    addr[al] = 0;
    uint32_t any = htonl(INADDR_ANY);
    if (sp.proto == CU_SIM_XPLANE) {
        if (!addr[0] || !strchr(addr, ':') || cu_udp_parse(addr, any, &sp.peer, err, n)) {
            if (!addr[0] || !strchr(addr, ':'))
                snprintf(err, n, "'%.60s': xplane needs X-Plane's HOST:PORT (its UDP port, 49000 by default)", s);
            return -1;
        }
        sp.has_peer = 1;
        sp.freq = 30;
        cu_udp_parse("0", any, &sp.listen, err, n);
    } else if (!addr[0]) {
        snprintf(err, n, "'%.60s': give the port to listen on (%s)", s,
                 sp.proto == CU_SIM_CIGI ? "cigi:8004" : "fg:5510");
        return -1;
    } else if (cu_udp_parse(addr, any, &sp.listen, err, n)) {
        return -1;
    }
    for (const char *p = comma; p && *p;) {
        p++; /* past the comma */
        const char *next = strchr(p, ',');
        size_t il = next ? (size_t)(next - p) : strlen(p);
        int shown = (int)(il > 40 ? 40 : il);
        char v[300];
        int bad = 0; /* 1: a number out of its range; -1: cu_udp_parse said why */
        if (sp.proto == CU_SIM_CIGI && opt_value(p, il, "host", v, sizeof v)) {
            bad = cu_udp_parse(v, htonl(INADDR_LOOPBACK), &sp.peer, err, n);
            sp.has_peer = 1;
        } else if (sp.proto == CU_SIM_CIGI && opt_value(p, il, "view", v, sizeof v)) {
            bad = whole(v, 0, 65535, &sp.view_id) ? 1 : 0;
        } else if (sp.proto == CU_SIM_CIGI && opt_value(p, il, "entity", v, sizeof v)) {
            bad = whole(v, 0, 65535, &sp.entity_id) ? 1 : 0;
        } else if (sp.proto == CU_SIM_XPLANE && opt_value(p, il, "local", v, sizeof v)) {
            bad = cu_udp_parse(v, any, &sp.listen, err, n);
        } else if (sp.proto == CU_SIM_XPLANE && opt_value(p, il, "freq", v, sizeof v)) {
            bad = whole(v, 1, 1000, &sp.freq) ? 1 : 0;
        } else if (sp.proto == CU_SIM_XPLANE && opt_value(p, il, "year", v, sizeof v)) {
            bad = whole(v, 1900, 2100, &sp.year) ? 1 : 0;
        } else {
            snprintf(err, n, "'%.60s': unknown option '%.*s' (%s)", s, shown, p,
                     sp.proto == CU_SIM_CIGI ? "cigi takes host=, view=, entity=" :
                     sp.proto == CU_SIM_XPLANE ? "xplane takes local=, freq=, year=" : "fg takes none");
            return -1;
        }
        if (bad > 0)
            snprintf(err, n, "'%.60s': '%.*s' is out of range (view, entity: 0..65535; freq: 1..1000; year: "
                     "1900..2100)", s, shown, p);
        if (bad)
            return -1;
        p = next;
    }
    *out = sp;
    return 0;
}

/* The X-Plane subscriptions, at freq (0: stop). */
static int xplane_subscribe(cu_sim_link *l, int freq, char *err, size_t n)
{
    uint8_t req[CU_XPLANE_REQUEST_SIZE];
    for (int i = 0; i < CU_XPLANE_REFS; i++) {
        size_t len = cu_xplane_rref_request(req, sizeof req, freq, i, cu_xplane_dataref(i));
        if (!len || cu_udp_send(l->fd, &l->spec.peer, req, len, err, n))
            return -1;
    }
    return 0;
}

int cu_sim_link_open(cu_sim_link *l, const cu_sim_link_spec *spec, char *err, size_t n)
{
    memset(l, 0, sizeof *l);
    l->spec = *spec;
    cu_cigi_ig_init(&l->cigi, (uint16_t)spec->view_id, (uint16_t)spec->entity_id);
    cu_xplane_rx_init(&l->xp, spec->year);
    l->fd = cu_udp_open(&spec->listen, err, n);
    if (l->fd < 0)
        return -1;
    if (spec->proto == CU_SIM_XPLANE && xplane_subscribe(l, spec->freq, err, n)) {
        cu_sim_link_close(l);
        return -1;
    }
    return 0;
}

/* A horizontal field of view (FlightGear, X-Plane) as the frustum: the vertical from the frame's aspect ratio. */
static void set_hfov(cu_sim_state *st, double hfov)
{
    st->frustum_valid = 1;
    st->fov_left_deg = -0.5 * hfov;
    st->fov_right_deg = 0.5 * hfov;
    st->fov_bottom_deg = st->fov_top_deg = 0;
    st->near_m = st->far_m = 0;
    st->changed |= CU_SIM_FRUSTUM;
}

/* One datagram through the link's protocol: 1 when it opens a frame. */
static int take(cu_sim_link *l, size_t len, cu_sim_state *st)
{
    char err[256] = "";
    double hfov = -1;
    switch (l->spec.proto) {
    case CU_SIM_CIGI: {
        unsigned long bad0 = l->cigi.stats.malformed + l->cigi.stats.wrong_version + l->cigi.stats.untrusted +
                             l->cigi.stats.nonfinite + l->cigi.stats.out_of_range;
        cu_cigi_ig_receive(&l->cigi, l->buf, len, st);
        if (l->cigi.stats.malformed + l->cigi.stats.wrong_version + l->cigi.stats.untrusted +
            l->cigi.stats.nonfinite + l->cigi.stats.out_of_range != bad0) {
            l->rejected++;
            snprintf(l->last_error, sizeof l->last_error, "cigi: %s", l->cigi.last_error);
        }
        if (l->cigi.have_frame) {
            cu_cigi_ig_frame_taken(&l->cigi);
            return 1;
        }
        return 0;
    }
    case CU_SIM_FG:
        if (cu_fgfs_parse((const char *)l->buf, len, st, &hfov, err, sizeof err)) {
            l->rejected++;
            snprintf(l->last_error, sizeof l->last_error, "%s", err);
            return 0;
        }
        break;
    case CU_SIM_XPLANE:
        if (cu_xplane_parse(&l->xp, l->buf, len, st, &hfov, err, sizeof err)) {
            l->rejected++;
            snprintf(l->last_error, sizeof l->last_error, "%s", err);
            return 0;
        }
        break;
    }
    if (hfov > 0)
        set_hfov(st, hfov);
    return 1;
}

int cu_sim_link_poll(cu_sim_link *l, cu_sim_state *st, uint64_t now_ns)
{
    int count = 0;
    for (; count < CU_SIM_POLL_MAX; count++) {
        int trunc = 0;
        cu_udp_addr from;
        char err[256];
        long len = cu_udp_recv(l->fd, l->buf, sizeof l->buf, &trunc, &from, err, sizeof err);
        if (len == CU_UDP_NONE)
            break;
        if (len < 0) {
            snprintf(l->last_error, sizeof l->last_error, "%s", err);
            break;
        }
        l->datagrams++;
        if (trunc) { /* larger than any datagram a host sends: not read at all */
            l->oversized++;
            snprintf(l->last_error, sizeof l->last_error, "a datagram over %d bytes, dropped", CU_SIM_DATAGRAM_MAX);
            continue;
        }
        /* X-Plane replies come from X-Plane; anyone else's are not its */
        if (l->spec.proto == CU_SIM_XPLANE && (from.ip != l->spec.peer.ip || from.port != l->spec.peer.port) &&
            l->spec.peer.ip != htonl(INADDR_ANY)) {
            l->rejected++;
            char who[64];
            cu_udp_format(&from, who, sizeof who);
            snprintf(l->last_error, sizeof l->last_error, "xplane: a datagram from %s, not X-Plane, dropped", who);
            continue;
        }
        if (take(l, (size_t)len, st)) {
            if (!l->frame_ready)
                l->frame_rx_ns = now_ns;
            l->frame_ready = 1;
            l->host = from; /* the sender of the last good frame: where Start of Frame goes */
            l->have_host = 1;
        }
    }
    return count;
}

int cu_sim_link_start_frame(cu_sim_link *l, uint32_t ig_frame, uint32_t timestamp_10us)
{
    if (l->spec.proto != CU_SIM_CIGI || (!l->spec.has_peer && !l->have_host))
        return 0;
    uint8_t sof[CU_CIGI_SIZE_START_OF_FRAME];
    size_t len = cu_cigi_start_of_frame(&l->cigi, ig_frame, timestamp_10us, 0, sof, sizeof sof);
    char err[200];
    if (cu_udp_send(l->fd, l->spec.has_peer ? &l->spec.peer : &l->host, sof, len, err, sizeof err)) {
        l->send_errors++;
        snprintf(l->last_error, sizeof l->last_error, "cigi: Start of Frame: %s", err);
        return -1;
    }
    return 0;
}

void cu_sim_link_describe(const cu_sim_link *l, char *buf, size_t n)
{
    char listen[64], peer[64];
    cu_udp_addr at = l->spec.listen;
    at.port = l->fd >= 0 ? cu_udp_local_port(l->fd) : at.port;
    cu_udp_format(&at, listen, sizeof listen);
    cu_udp_format(&l->spec.peer, peer, sizeof peer);
    if (l->spec.proto == CU_SIM_CIGI)
        snprintf(buf, n, "cigi 3.3 listen=%s view=%d entity=%d start-of-frame=%s", listen, l->spec.view_id,
                 l->spec.entity_id, l->spec.has_peer ? peer : "sender");
    else if (l->spec.proto == CU_SIM_FG)
        snprintf(buf, n, "fg listen=%s (data/flightgear/cumulo.xml)", listen);
    else
        snprintf(buf, n, "xplane %s listen=%s freq=%d year=%d", peer, listen, l->spec.freq, l->spec.year);
}

void cu_sim_link_close(cu_sim_link *l)
{
    if (l->fd > 0) {
        char err[200];
        if (l->spec.proto == CU_SIM_XPLANE)
            xplane_subscribe(l, 0, err, sizeof err); /* X-Plane would go on sending to a closed port */
        close(l->fd);
    }
    l->fd = -1;
}
