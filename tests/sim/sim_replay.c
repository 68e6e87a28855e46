/* tests/sim/sim_replay.c: replays a recorded simulator stream to `cumulo ig` for the tests, printing what it sent:
 *   sim_replay fg HOST:PORT FILE INTERVAL_MS      each line of FILE (FlightGear generic protocol) as one datagram
 *   sim_replay xplane LISTEN_PORT FILE INTERVAL_MS  a stand-in X-Plane: waits for the IG's RREF subscriptions, sends
 *       the datagrams of FILE (hex, one per line, '#' comments: tests/sim/data/xplane_rref.hex) to the subscriber,
 *       then waits for the unsubscriptions (frequency 0) the IG sends when it stops;
 *   sim_replay record PORT FILE COUNT              writes COUNT datagrams received on PORT to FILE, one a line (a
 *       real fgfs's second --generic output, for `make fgcheck`).
 * Lines on stdout: "sent N <line>" (fg), "subscribe index=I freq=F path=P", "sent N index=I value=V ..." (xplane, the
 * records decoded here as little-endian int32 and float32, independently of platform/sim/xplane.c) and
 * "unsubscribe index=I". Exits 0 when everything was sent (xplane: ten subscriptions and ten unsubscriptions seen
 * within 60 s each), 1 otherwise. */
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#define REFS 10 /* the datarefs cumulo subscribes to (platform/sim/xplane.h) */

static void pause_ms(long ms)
{
    struct timespec t = { ms / 1000, (ms % 1000) * 1000000L };
    nanosleep(&t, NULL);
}

static uint32_t le32(const uint8_t *p) { return p[0] | p[1] << 8 | p[2] << 16 | (uint32_t)p[3] << 24; }

static int replay_fg(int fd, struct sockaddr_in *to, FILE *f, long ms)
{
    char line[1024];
    int n = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '\n' || line[0] == '#')
            continue;
        size_t len = strlen(line);
        if (sendto(fd, line, len, 0, (struct sockaddr *)to, sizeof *to) != (ssize_t)len)
            return 1;
        printf("sent %d %s", ++n, line);
        fflush(stdout);
        pause_ms(ms);
    }
    return n ? 0 : 1;
}

/* Requests until `want` of frequency > 0 (subscribe) or == 0 have come; the subscriber's address into from. */
static int await_requests(int fd, int subscribe, struct sockaddr_in *from)
{
    int seen[REFS] = {0}, count = 0;
    while (count < REFS) {
        struct pollfd p = { .fd = fd, .events = POLLIN };
        if (poll(&p, 1, 60000) <= 0)
            return 1;
        uint8_t b[1024];
        socklen_t fl = sizeof *from;
        ssize_t n = recvfrom(fd, b, sizeof b, 0, (struct sockaddr *)from, &fl);
        if (n != 413 || memcmp(b, "RREF", 5)) {
            printf("request of %zd bytes, not RREF\n", n);
            continue;
        }
        int32_t freq = (int32_t)le32(b + 5), index = (int32_t)le32(b + 9);
        if ((freq > 0) != subscribe || index < 0 || index >= REFS || seen[index])
            continue;
        seen[index] = 1;
        count++;
        b[412] = 0;
        if (subscribe)
            printf("subscribe index=%d freq=%d path=%s\n", index, freq, (const char *)b + 13);
        else
            printf("unsubscribe index=%d\n", index);
        fflush(stdout);
    }
    return 0;
}

static int replay_xplane(int fd, FILE *f, long ms)
{
    struct sockaddr_in ig;
    if (await_requests(fd, 1, &ig))
        return 1;
    char line[4096];
    int n = 0;
    while (fgets(line, sizeof line, f)) {
        uint8_t b[1024];
        size_t len = 0;
        for (char *p = line; *p && *p != '#' && len < sizeof b;) {
            unsigned v;
            int used;
            if (sscanf(p, " %2x%n", &v, &used) != 1)
                break;
            b[len++] = (uint8_t)v;
            p += used;
        }
        if (!len)
            continue;
        if (sendto(fd, b, len, 0, (struct sockaddr *)&ig, sizeof ig) != (ssize_t)len)
            return 1;
        printf("sent %d", ++n);
        for (size_t i = 5; i + 8 <= len; i += 8) {
            uint32_t bits = le32(b + i + 4);
            float v;
            memcpy(&v, &bits, sizeof v);
            printf(" index=%d value=%.17g", (int)(int32_t)le32(b + i), (double)v); /* exactly the float */
        }
        printf("\n");
        fflush(stdout);
        pause_ms(ms);
    }
    return n ? await_requests(fd, 0, &ig) : 1;
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: sim_replay fg HOST:PORT FILE INTERVAL_MS | xplane LISTEN_PORT FILE INTERVAL_MS |\n"
                        "                  record PORT FILE COUNT\n");
        return 2;
    }
    FILE *f = fopen(strcmp(argv[1], "record") ? argv[3] : "/dev/null", "r");
    int fd = socket(AF_INET, SOCK_DGRAM, 0);
    if (!f || fd < 0) {
        perror("sim_replay");
        return 1;
    }
    long ms = atol(argv[4]);
    struct sockaddr_in a = { .sin_family = AF_INET };
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (!strcmp(argv[1], "record")) {
        fclose(f);
        f = fopen(argv[3], "w");
        a.sin_port = htons((uint16_t)atoi(argv[2]));
        if (!f || bind(fd, (struct sockaddr *)&a, sizeof a)) {
            perror("sim_replay: record");
            return 1;
        }
        for (long i = 0; i < ms; i++) {
            struct pollfd p = { .fd = fd, .events = POLLIN };
            char b[2048];
            ssize_t n = poll(&p, 1, 300000) > 0 ? recv(fd, b, sizeof b - 1, 0) : -1;
            if (n < 0)
                return 1;
            b[n] = 0;
            fprintf(f, "%s%s", b, n && b[n - 1] == '\n' ? "" : "\n");
            fflush(f);
        }
        return fclose(f) ? 1 : 0;
    }
    if (!strcmp(argv[1], "fg")) {
        const char *colon = strrchr(argv[2], ':');
        a.sin_port = htons((uint16_t)atoi(colon ? colon + 1 : argv[2]));
        return replay_fg(fd, &a, f, ms);
    }
    a.sin_port = htons((uint16_t)atoi(argv[2]));
    if (bind(fd, (struct sockaddr *)&a, sizeof a)) {
        perror("sim_replay: bind");
        return 1;
    }
    return replay_xplane(fd, f, ms);
}
