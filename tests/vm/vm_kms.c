/* tests/vm/vm_kms.c: the DRM test's own eyes on the display, independent of cumulo's code (plain libdrm):
 *   vm_kms info [CARD]              connector, its modes and whether the driver takes atomic commits
 *   vm_kms hold [CARD]              shows a test pattern on the connected connector (like a console would), drops
 *                                   DRM master so a kiosk can take the screen, and when stdin ends checks that the
 *                                   CRTC shows the pattern again with the same mode: prints "restored" or why not
 *   vm_kms snap OUT.ppm [CARD]      reads the buffer the CRTC scans out now (root may map another client's
 *                                   framebuffer) and writes it as a binary PPM, top row first
 *   vm_kms compare A.ppm B.png MEAN MAXFRAC   mean absolute difference per channel (0..255) and the fraction of
 *                                   pixels off by more than 24 in some channel; exit 0 when mean <= MEAN and
 *                                   fraction <= MAXFRAC */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <png.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>
#include <drm_fourcc.h>

static int open_card(const char *path)
{
    int fd = open(path, O_RDWR | O_CLOEXEC);
    if (fd < 0) {
        fprintf(stderr, "vm_kms: %s: %s\n", path, strerror(errno));
        exit(2);
    }
    return fd;
}

/* The first connected connector and the CRTC its encoder drives (or the first one it can). */
static drmModeConnector *connected(int fd, uint32_t *crtc)
{
    drmModeRes *res = drmModeGetResources(fd);
    if (!res) {
        fprintf(stderr, "vm_kms: no KMS resources\n");
        exit(2);
    }
    drmModeConnector *conn = NULL;
    for (int i = 0; i < res->count_connectors && !conn; i++) {
        drmModeConnector *c = drmModeGetConnector(fd, res->connectors[i]);
        if (c && c->connection == DRM_MODE_CONNECTED && c->count_modes)
            conn = c;
        else
            drmModeFreeConnector(c);
    }
    if (!conn) {
        fprintf(stderr, "vm_kms: no connected connector\n");
        exit(2);
    }
    *crtc = 0;
    if (conn->encoder_id) {
        drmModeEncoder *e = drmModeGetEncoder(fd, conn->encoder_id);
        if (e) {
            *crtc = e->crtc_id;
            drmModeFreeEncoder(e);
        }
    }
    for (int k = 0; k < conn->count_encoders && !*crtc; k++) {
        drmModeEncoder *e = drmModeGetEncoder(fd, conn->encoders[k]);
        for (int c = 0; e && c < res->count_crtcs && !*crtc; c++)
            if (e->possible_crtcs & (1u << c))
                *crtc = res->crtcs[c];
        drmModeFreeEncoder(e);
    }
    drmModeFreeResources(res);
    return conn;
}

static int cmd_info(const char *card)
{
    int fd = open_card(card);
    uint32_t crtc;
    drmModeConnector *c = connected(fd, &crtc);
    drmVersionPtr v = drmGetVersion(fd);
    printf("driver=%s connector=%u type=%u modes=%d crtc=%u atomic=%s\n", v ? v->name : "?", c->connector_id,
           c->connector_type, c->count_modes, crtc, drmSetClientCap(fd, DRM_CLIENT_CAP_ATOMIC, 1) ? "no" : "yes");
    for (int i = 0; i < c->count_modes && i < 8; i++)
        printf("mode %dx%d@%u%s\n", c->modes[i].hdisplay, c->modes[i].vdisplay, c->modes[i].vrefresh,
               c->modes[i].type & DRM_MODE_TYPE_PREFERRED ? " preferred" : "");
    return 0;
}

static int cmd_hold(const char *card)
{
    int fd = open_card(card);
    uint32_t crtc;
    drmModeConnector *c = connected(fd, &crtc);
    drmModeModeInfo mode = c->modes[0];
    for (int i = 0; i < c->count_modes; i++)
        if (c->modes[i].type & DRM_MODE_TYPE_PREFERRED) {
            mode = c->modes[i];
            break;
        }
    struct drm_mode_create_dumb cd = { .width = mode.hdisplay, .height = mode.vdisplay, .bpp = 32 };
    if (drmIoctl(fd, DRM_IOCTL_MODE_CREATE_DUMB, &cd)) {
        fprintf(stderr, "vm_kms: create dumb: %s\n", strerror(errno));
        return 2;
    }
    struct drm_mode_map_dumb md = { .handle = cd.handle };
    drmIoctl(fd, DRM_IOCTL_MODE_MAP_DUMB, &md);
    uint8_t *px = mmap(NULL, cd.size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, (off_t)md.offset);
    if (px == MAP_FAILED) {
        fprintf(stderr, "vm_kms: mmap: %s\n", strerror(errno));
        return 2;
    }
    for (uint32_t y = 0; y < cd.height; y++)
        for (uint32_t x = 0; x < cd.width; x++)
            ((uint32_t *)(px + y * cd.pitch))[x] = ((x / 32 + y / 32) & 1) ? 0x00203040u : 0x00c0c0c0u;
    uint32_t fb;
    if (drmModeAddFB(fd, cd.width, cd.height, 24, 32, cd.pitch, cd.handle, &fb) ||
        drmModeSetCrtc(fd, crtc, fb, 0, 0, &c->connector_id, 1, &mode)) {
        fprintf(stderr, "vm_kms: showing the pattern failed: %s\n", strerror(errno));
        return 2;
    }
    /* Give the screen away as a console switching to a kiosk would; keep the fd so the pattern's FB stays. */
    if (drmDropMaster(fd))
        fprintf(stderr, "vm_kms: drop master: %s\n", strerror(errno));
    printf("holding crtc=%u fb=%u mode=%dx%d\n", crtc, fb, mode.hdisplay, mode.vdisplay);
    fflush(stdout);
    char buf[64];
    while (fgets(buf, sizeof buf, stdin))
        ;
    drmModeCrtc *now = drmModeGetCrtc(fd, crtc);
    int ok = now && now->buffer_id == fb && now->mode_valid && now->mode.hdisplay == mode.hdisplay &&
             now->mode.vdisplay == mode.vdisplay && now->mode.clock == mode.clock;
    if (ok)
        printf("restored crtc=%u fb=%u mode=%dx%d\n", crtc, fb, mode.hdisplay, mode.vdisplay);
    else
        printf("not restored: crtc=%u shows fb=%u mode=%dx%d (valid %d), expected fb=%u mode=%dx%d\n", crtc,
               now ? now->buffer_id : 0, now ? now->mode.hdisplay : 0, now ? now->mode.vdisplay : 0,
               now ? now->mode_valid : 0, fb, mode.hdisplay, mode.vdisplay);
    return ok ? 0 : 1;
}

static int cmd_snap(const char *out, const char *card)
{
    int fd = open_card(card);
    uint32_t crtc;
    connected(fd, &crtc);
    drmModeCrtc *cr = drmModeGetCrtc(fd, crtc);
    if (!cr || !cr->buffer_id) {
        fprintf(stderr, "vm_kms: crtc %u scans out nothing\n", crtc);
        return 1;
    }
    drmModeFB2 *fb = drmModeGetFB2(fd, cr->buffer_id);
    if (!fb || !fb->handles[0]) {
        fprintf(stderr, "vm_kms: framebuffer %u: no handle (%s; root needed)\n", cr->buffer_id, strerror(errno));
        return 1;
    }
    if (fb->pixel_format != DRM_FORMAT_XRGB8888 && fb->pixel_format != DRM_FORMAT_ARGB8888) {
        fprintf(stderr, "vm_kms: framebuffer format %.4s not handled\n", (char *)&fb->pixel_format);
        return 1;
    }
    if (fb->modifier != DRM_FORMAT_MOD_LINEAR && fb->modifier != DRM_FORMAT_MOD_INVALID && (fb->flags & DRM_MODE_FB_MODIFIERS)) {
        fprintf(stderr, "vm_kms: framebuffer modifier 0x%llx is not linear\n", (unsigned long long)fb->modifier);
        return 1;
    }
    struct drm_mode_map_dumb md = { .handle = fb->handles[0] };
    if (drmIoctl(fd, DRM_IOCTL_MODE_MAP_DUMB, &md)) {
        fprintf(stderr, "vm_kms: map framebuffer: %s\n", strerror(errno));
        return 1;
    }
    size_t size = (size_t)fb->pitches[0] * fb->height + fb->offsets[0];
    uint8_t *px = mmap(NULL, size, PROT_READ, MAP_SHARED, fd, (off_t)md.offset);
    if (px == MAP_FAILED) {
        fprintf(stderr, "vm_kms: mmap: %s\n", strerror(errno));
        return 1;
    }
    FILE *f = fopen(out, "wb");
    if (!f) {
        fprintf(stderr, "vm_kms: %s: %s\n", out, strerror(errno));
        return 1;
    }
    fprintf(f, "P6\n%u %u\n255\n", fb->width, fb->height);
    for (uint32_t y = 0; y < fb->height; y++)
        for (uint32_t x = 0; x < fb->width; x++) {
            uint32_t v = ((uint32_t *)(px + fb->offsets[0] + (size_t)y * fb->pitches[0]))[x];
            uint8_t rgb[3] = { (uint8_t)(v >> 16), (uint8_t)(v >> 8), (uint8_t)v };
            fwrite(rgb, 1, 3, f);
        }
    fclose(f);
    printf("snap crtc=%u fb=%u %ux%u pitch=%u -> %s\n", crtc, cr->buffer_id, fb->width, fb->height, fb->pitches[0],
           out);
    return 0;
}

static uint8_t *read_ppm(const char *path, int *w, int *h)
{
    FILE *f = fopen(path, "rb");
    int max;
    if (!f || fscanf(f, "P6 %d %d %d", w, h, &max) != 3 || max != 255 || fgetc(f) == EOF) {
        fprintf(stderr, "vm_kms: %s: not a binary PPM\n", path);
        exit(2);
    }
    uint8_t *p = malloc((size_t)*w * *h * 3);
    if (fread(p, 3, (size_t)*w * *h, f) != (size_t)*w * *h) {
        fprintf(stderr, "vm_kms: %s: short\n", path);
        exit(2);
    }
    fclose(f);
    return p;
}

static uint8_t *read_png(const char *path, int *w, int *h)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path)) {
        fprintf(stderr, "vm_kms: %s: %s\n", path, img.message);
        exit(2);
    }
    img.format = PNG_FORMAT_RGB;
    uint8_t *p = malloc(PNG_IMAGE_SIZE(img));
    if (!png_image_finish_read(&img, NULL, p, 0, NULL)) {
        fprintf(stderr, "vm_kms: %s: %s\n", path, img.message);
        exit(2);
    }
    *w = (int)img.width;
    *h = (int)img.height;
    return p;
}

static int cmd_compare(const char *a, const char *b, double max_mean, double max_frac)
{
    int wa, ha, wb, hb;
    uint8_t *pa = read_ppm(a, &wa, &ha), *pb = read_png(b, &wb, &hb);
    if (wa != wb || ha != hb) {
        printf("compare: sizes differ: %dx%d vs %dx%d\n", wa, ha, wb, hb);
        return 1;
    }
    double sum = 0.0, flipped = 0.0;
    long off = 0;
    size_t n = (size_t)wa * ha;
    for (size_t i = 0; i < n; i++) {
        int big = 0;
        size_t y = i / wa, x = i % wa, j = ((ha - 1 - y) * wa + x) * 3;
        for (int c = 0; c < 3; c++) {
            int d = abs((int)pa[i * 3 + c] - (int)pb[i * 3 + c]);
            sum += d;
            big |= d > 24;
            flipped += abs((int)pa[i * 3 + c] - (int)pb[j + c]);
        }
        off += big;
    }
    double mean = sum / (3.0 * n), frac = (double)off / n;
    printf("compare %s vs %s: %dx%d mean abs diff %.3f/255, %.4f%% of pixels off by > 24 (upside down: mean %.3f)\n",
           a, b, wa, ha, mean, 100.0 * frac, flipped / (3.0 * n));
    return mean <= max_mean && frac <= max_frac ? 0 : 1;
}

int main(int argc, char **argv)
{
    const char *cmd = argc > 1 ? argv[1] : "";
    if (!strcmp(cmd, "info"))
        return cmd_info(argc > 2 ? argv[2] : "/dev/dri/card0");
    if (!strcmp(cmd, "hold"))
        return cmd_hold(argc > 2 ? argv[2] : "/dev/dri/card0");
    if (!strcmp(cmd, "snap") && argc > 2)
        return cmd_snap(argv[2], argc > 3 ? argv[3] : "/dev/dri/card0");
    if (!strcmp(cmd, "compare") && argc == 6)
        return cmd_compare(argv[2], argv[3], atof(argv[4]), atof(argv[5]));
    fprintf(stderr, "usage: vm_kms info|hold [CARD] | snap OUT.ppm [CARD] | compare A.ppm B.png MEAN MAXFRAC\n");
    return 2;
}
