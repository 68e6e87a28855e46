/* platform/sim/udp.h: the UDP sockets of `cumulo ig`: bound, non-blocking, IPv4, with the peer's address kept as
 * text so that log lines and tests can name it. */
#ifndef CU_PLATFORM_SIM_UDP_H
#define CU_PLATFORM_SIM_UDP_H
#include <stddef.h>
#include <stdint.h>

typedef struct cu_udp_addr {
    uint32_t ip;     /* network byte order */
    uint16_t port;   /* host byte order */
} cu_udp_addr;

/* "PORT", "ADDR:PORT" or "HOST:PORT" (a dotted quad, "localhost" or a name getaddrinfo resolves) into a; 0, or -1 with a
 * one-line message naming what is wrong. def_ip (network order) is the address when only a port is given. */
int  cu_udp_parse(const char *s, uint32_t def_ip, cu_udp_addr *a, char *err, size_t errlen);
/* A socket bound to a (port 0: any free port), non-blocking; the fd, or -1 with a message. */
int  cu_udp_open(const cu_udp_addr *a, char *err, size_t errlen);
/* The port a socket is bound to (host order), or 0. */
uint16_t cu_udp_local_port(int fd);
/* One datagram into buf without blocking: its length (0 for an empty one; a longer one is cut to cap and *truncated
 * set), CU_UDP_NONE when none is waiting, -1 on an error (message in err). The sender's address goes to from. */
#define CU_UDP_NONE (-2)
long cu_udp_recv(int fd, uint8_t *buf, size_t cap, int *truncated, cu_udp_addr *from, char *err, size_t errlen);
/* Sends len bytes to a: 0, or -1 with a message (a full socket buffer is an error: the caller counts it). */
int  cu_udp_send(int fd, const cu_udp_addr *a, const uint8_t *buf, size_t len, char *err, size_t errlen);
/* "127.0.0.1:8005" */
void cu_udp_format(const cu_udp_addr *a, char *buf, size_t len);

#endif
