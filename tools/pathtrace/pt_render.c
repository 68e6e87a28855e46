/* tools/pathtrace/pt_render.c: the path tracer's render driver (image rows shared out to threads, progress on
 * stderr, mean and standard error per pixel) and the density dump for comparisons with the renderer's CPU twin. */
#include "pt.h"
#include "error.h"
#include "../tool_cli.h"
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---------------------------------------------------------------- rendering */

typedef struct job {
    const pt_ctx *c;
    const pt_render_opts *o;
    float *mean, *se;
    pthread_mutex_t lock;
    int next_row, rows_done;
    double t0, last_print;
    pt_counters total;
} job;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void progress(job *j, int final)
{
    double t = now_s(), el = t - j->t0;
    if (!final && t - j->last_print < 0.5)
        return;
    j->last_print = t;
    int H = j->o->height, done = j->rows_done, bar = 30, fill = (int)((double)bar * done / H);
    char b[64];
    for (int i = 0; i < bar; i++)
        b[i] = i < fill ? '#' : '.';
    b[bar] = 0;
    double eta = done > 0 ? el * (H - done) / done : 0;
    fprintf(stderr, "\rcumulo-pt [%s] %3d%% %d/%d rows, %.0f s elapsed, ETA %.0f s   %s", b, 100 * done / H, done, H,
            el, eta, final ? "\n" : "");
    fflush(stderr);
}

static void render_row(job *j, int y, pt_counters *k)
{
    const pt_ctx *c = j->c;
    const pt_render_opts *o = j->o;
    for (int x = 0; x < o->width; x++) {
        pt_rng rng;
        pt_rng_seed(&rng, o->seed, (uint64_t)y * (uint64_t)o->width + (uint64_t)x);
        double mean[3] = {0, 0, 0}, m2[3] = {0, 0, 0};
        for (int s = 0; s < o->spp; s++) {
            double jx = 0.5, jy = 0.5;
            if (o->aa) {
                jx = pt_rng_uniform(&rng);
                jy = pt_rng_uniform(&rng);
            }
            vec3 ro, rd;
            pt_camera_ray(c, x + jx, y + jy, &ro, &rd);
            double L[3];
            if (o->mode == PT_MODE_TRANSMITTANCE) {
                L[0] = L[1] = L[2] = pt_transmittance(c, ro, rd, &rng, k);
                k->paths++;
            } else {
                pt_radiance(c, ro, rd, &rng, L, k);
            }
            for (int i = 0; i < 3; i++) { /* Welford: stable even with the sun disk's 1e6 radiance */
                double dl = L[i] - mean[i];
                mean[i] += dl / (s + 1);
                m2[i] += dl * (L[i] - mean[i]);
            }
        }
        size_t idx = 3 * ((size_t)y * o->width + x);
        for (int i = 0; i < 3; i++) {
            j->mean[idx + i] = (float)mean[i];
            if (j->se)
                j->se[idx + i] = o->spp > 1 ? (float)sqrt(m2[i] / (o->spp - 1) / o->spp) : 0.0f;
        }
    }
}

static void *worker(void *arg)
{
    job *j = arg;
    pt_counters k = {0};
    for (;;) {
        pthread_mutex_lock(&j->lock);
        int y = j->next_row < j->o->height ? j->next_row++ : -1;
        pthread_mutex_unlock(&j->lock);
        if (y < 0)
            break;
        render_row(j, y, &k);
        pthread_mutex_lock(&j->lock);
        j->rows_done++;
        if (j->o->progress)
            progress(j, 0);
        pthread_mutex_unlock(&j->lock);
    }
    pthread_mutex_lock(&j->lock);
    j->total.paths += k.paths;
    j->total.scatters += k.scatters;
    j->total.truncated += k.truncated;
    j->total.density_evals += k.density_evals;
    j->total.step_capped += k.step_capped;
    pthread_mutex_unlock(&j->lock);
    return NULL;
}

int pt_render(const pt_ctx *c, const pt_render_opts *o, float *mean, float *se, pt_counters *k, cu_error *err)
{
    if (o->width != c->width || o->height != c->height)
        return cu_fail(err, "%s", "path tracer: render size differs from the context's camera (set it before init)");
    job j;
    memset(&j, 0, sizeof j);
    j.c = c;
    j.o = o;
    j.mean = mean;
    j.se = se;
    j.t0 = now_s();
    pthread_mutex_init(&j.lock, NULL);
    int nt = o->threads < 1 ? 1 : o->threads > 256 ? 256 : o->threads;
    pthread_t th[256];
    int started = 0;
    for (int i = 1; i < nt; i++) {
        if (pthread_create(&th[i], NULL, worker, &j) != 0)
            break;
        started = i;
    }
    worker(&j); /* the calling thread works too */
    for (int i = 1; i <= started; i++)
        pthread_join(th[i], NULL);
    if (o->progress)
        progress(&j, 1);
    pthread_mutex_destroy(&j.lock);
    if (k)
        *k = j.total;
    return 0;
}

int pt_render_scene(const cu_scene *s, const char *data_dir, const pt_render_opts *o, float *mean, float *se,
                    pt_counters *k, cu_error *err)
{
    cu_scene *sc = malloc(sizeof *sc);
    pt_ctx *c = malloc(sizeof *c);
    int rc = 1;
    if (!sc || !c) {
        cu_fail(err, "%s", "path tracer: out of memory");
    } else {
        *sc = *s;
        sc->width = o->width;
        sc->height = o->height;
        if (pt_ctx_init(c, sc, data_dir, err) == 0) {
            rc = pt_render(c, o, mean, se, k, err);
            pt_ctx_free(c);
        }
    }
    free(c);
    free(sc);
    return rc;
}

/* ---------------------------------------------------------------- density dump */

int pt_dump_density(const pt_ctx *c, const char *path, int nx, int ny, int nz, uint32_t noise_seed, cu_error *err)
{
    const cu_cloud *cl = &c->cloud;
    if (cl->n < 1)
        return cu_fail(err, "%s", "--dump-density: the scene has no ellipsoids");
    vec3 lo = cl->bounds_min, hi = cl->bounds_max;
    double vx = (hi.x - lo.x) / nx, vy = (hi.y - lo.y) / ny, vz = (hi.z - lo.z) / nz;
    FILE *fp = fopen(path, "wb");
    if (!fp) {
        snprintf(err->msg, sizeof err->msg, "%s: cannot write density grid: %s", path, strerror(errno));
        return 1;
    }
    unsigned char *row = malloc(4 * (size_t)nx);
    if (!row) {
        fclose(fp);
        return cu_fail(err, "%s", "--dump-density: out of memory");
    }
    int ok = 1;
    for (int z = 0; z < nz && ok; z++)
        for (int y = 0; y < ny && ok; y++) {
            for (int x = 0; x < nx; x++) {
                vec3 p = v3(lo.x + (x + 0.5) * vx, lo.y + (y + 0.5) * vy, lo.z + (z + 0.5) * vz);
                float v = (float)cu_cloud_extinction(cl, p);
                uint32_t u;
                memcpy(&u, &v, 4);
                for (int b = 0; b < 4; b++) /* little-endian on any host */
                    row[4 * x + b] = (unsigned char)(u >> (8 * b));
            }
            ok = fwrite(row, 4, (size_t)nx, fp) == (size_t)nx;
        }
    free(row);
    if (tool_close_output(fp) || !ok) {
        snprintf(err->msg, sizeof err->msg, "%s: write failed", path);
        return 1;
    }
    char hp[1200];
    snprintf(hp, sizeof hp, "%s.txt", path);
    fp = fopen(hp, "w");
    if (!fp) {
        snprintf(err->msg, sizeof err->msg, "%.400s: cannot write density header: %s", hp, strerror(errno));
        return 1;
    }
    const cu_scene *s = &c->scene;
    const char *base = strrchr(path, '/');
    fprintf(fp, "# cumulo-pt density grid: extinction k_e the path tracer used, sampled at voxel centres\n");
    fprintf(fp, "# voxel (i,j,k) centre, world metres = origin + ((i+0.5)*voxel_x, (j+0.5)*voxel_y, (k+0.5)*voxel_z)\n");
    fprintf(fp, "file %s\n", base ? base + 1 : path);
    fprintf(fp, "format float32 little-endian raw, x fastest, then y, then z\n");
    fprintf(fp, "dims %d %d %d\n", nx, ny, nz);
    fprintf(fp, "origin_m %.9g %.9g %.9g\n", lo.x + cl->origin.x, lo.y + cl->origin.y, lo.z + cl->origin.z);
    fprintf(fp, "voxel_m %.9g %.9g %.9g\n", vx, vy, vz);
    fprintf(fp, "units k_e m^-1\n");
    fprintf(fp, "scene %s\n", s->name);
    fprintf(fp, "noise_seed %u\n", (unsigned)noise_seed);
    fprintf(fp, "core_extinction_m-1 %.9g\n", cl->ke);
    fprintf(fp, "cloud_origin_m %.9g %.9g %.9g\n", cl->origin.x, cl->origin.y, cl->origin.z);
    fprintf(fp, "boundary_m %.9g\nnoise %s\nnoise_scale %.9g\nnoise_octaves %d\nprofile %s\n", cl->h,
            cl->noise_on ? "on" : "off", s->noise_scale, cl->octaves, cl->profile == CU_PROFILE_KOL ? "kol" : "tapered");
    if (tool_close_output(fp))
        return cu_fail(err, "%.400s: write failed", hp);
    return 0;
}

