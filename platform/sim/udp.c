/* platform/sim/udp.c: UDP sockets for the simulator links (udp.h). */
#include "udp.h"
#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

int cu_udp_parse(const char *s, uint32_t def_ip, cu_udp_addr *a, char *err, size_t errlen)
{
    char host[256] = "";
    const char *colon = strrchr(s, ':'), *ps = colon ? colon + 1 : s;
    if (colon) {
        size_t n = (size_t)(colon - s);
        if (n == 0 || n >= sizeof host) {
            snprintf(err, errlen, "'%.80s': expected PORT or HOST:PORT", s);
            return -1;
        }
        memcpy(host, s, n);
        host[n] = 0;
    }
    char *end;
    long port = strtol(ps, &end, 10);
    if (end == ps || *end || port < 0 || port > 65535 || ps[0] == '-' || ps[0] == '+') {
        snprintf(err, errlen, "'%.80s': the port must be a number in 0..65535", s);
        return -1;
    }
    a->port = (uint16_t)port;
    a->ip = def_ip;
    if (!host[0])
        return 0;
    struct in_addr in;
    if (inet_pton(AF_INET, host, &in) == 1) {
        a->ip = in.s_addr;
        return 0;
    }
    struct addrinfo hints = { .ai_family = AF_INET, .ai_socktype = SOCK_DGRAM }, *res = NULL;
    int rc = getaddrinfo(host, NULL, &hints, &res);
    if (rc || !res) {
        snprintf(err, errlen, "'%.80s': cannot resolve '%.80s' (%s)", s, host, gai_strerror(rc));
        return -1;
    }
    a->ip = ((struct sockaddr_in *)(void *)res->ai_addr)->sin_addr.s_addr;
    freeaddrinfo(res);
    return 0;
}

static struct sockaddr_in to_sockaddr(const cu_udp_addr *a)
{
    struct sockaddr_in sa;
    memset(&sa, 0, sizeof sa);
    sa.sin_family = AF_INET;
    sa.sin_port = htons(a->port);
    sa.sin_addr.s_addr = a->ip;
    return sa;
}

void cu_udp_format(const cu_udp_addr *a, char *buf, size_t len)
{
    struct in_addr in = { a->ip };
    char ip[INET_ADDRSTRLEN] = "?";
    inet_ntop(AF_INET, &in, ip, sizeof ip);
    snprintf(buf, len, "%s:%u", ip, (unsigned)a->port);
}

int cu_udp_open(const cu_udp_addr *a, char *err, size_t errlen)
{
    int fd = socket(AF_INET, SOCK_DGRAM, 0);
    if (fd < 0) {
        snprintf(err, errlen, "socket: %s", strerror(errno));
        return -1;
    }
    struct sockaddr_in sa = to_sockaddr(a);
    int fl = fcntl(fd, F_GETFL);
    if (fl < 0 || fcntl(fd, F_SETFL, fl | O_NONBLOCK) < 0 || fcntl(fd, F_SETFD, FD_CLOEXEC) < 0 ||
        bind(fd, (struct sockaddr *)&sa, sizeof sa) < 0) {
        char where[64];
        cu_udp_format(a, where, sizeof where);
        snprintf(err, errlen, "cannot listen on UDP %s: %s", where, strerror(errno));
        close(fd);
        return -1;
    }
    return fd;
}

uint16_t cu_udp_local_port(int fd)
{
    struct sockaddr_in sa;
    socklen_t n = sizeof sa;
    if (getsockname(fd, (struct sockaddr *)&sa, &n) < 0)
        return 0;
    return ntohs(sa.sin_port);
}

long cu_udp_recv(int fd, uint8_t *buf, size_t cap, int *truncated, cu_udp_addr *from, char *err, size_t errlen)
{
    struct sockaddr_in sa;
    socklen_t n = sizeof sa;
    /* MSG_TRUNC: the datagram's real length comes back, so an oversized one is seen, not mistaken for a short one */
    ssize_t got = recvfrom(fd, buf, cap, MSG_TRUNC, (struct sockaddr *)&sa, &n);
    if (got < 0) {
        if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)
            return CU_UDP_NONE;
        snprintf(err, errlen, "recvfrom: %s", strerror(errno));
        return -1;
    }
    *truncated = (size_t)got > cap;
    from->ip = sa.sin_addr.s_addr;
    from->port = ntohs(sa.sin_port);
    return (long)((size_t)got > cap ? cap : (size_t)got);
}

int cu_udp_send(int fd, const cu_udp_addr *a, const uint8_t *buf, size_t len, char *err, size_t errlen)
{
    struct sockaddr_in sa = to_sockaddr(a);
    ssize_t sent = sendto(fd, buf, len, 0, (struct sockaddr *)&sa, sizeof sa);
    if (sent < 0 || (size_t)sent != len) {
        char where[64];
        cu_udp_format(a, where, sizeof where);
        snprintf(err, errlen, "sendto %s: %s", where, sent < 0 ? strerror(errno) : "short write");
        return -1;
    }
    return 0;
}
