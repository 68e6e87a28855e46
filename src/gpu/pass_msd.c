/* src/gpu/pass_msd.c: a cloud's diffusion grid, solved and uploaded (see pass_msd.h). */
#include "pass_msd.h"
#include <math.h>
#include <time.h>

/* Relaxation sweeps at most, and the change in a sweep (of the summed fluence) at which a solve stops: about a
 * thousandth of the fluence left to converge at the rate these grids relax. */
#define MSD_MOST_SWEEPS 1000
#define MSD_TOL 1e-5
/* The work of sampling a cell's density (8 density evaluations) and of a solve's start (the sunbeam's first
 * scattering, three walks to the grid's edge; the leak weights) in cell updates of a sweep: measured on kiosk_day's
 * clouds, 826 ns a cell sampled and 76 ns a cell started, against 7 ns a cell update. */
#define MSD_SAMPLE_WORK 120
#define MSD_BEGIN_WORK 11

/* Grid g's answer into m's texture, and its box as the texture's. */
static void upload(const cu_gpu_scene *ctx, cu_cloud_msd *m, const cu_msd *g)
{
    const cu_gl *gl = ctx->gl;
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_MSD); /* its own unit: unit 0 holds the noise, also a 3D texture */
    if (!m->tex) {
        gl->GenTextures(1, &m->tex);
        gl->BindTexture(GL_TEXTURE_3D, m->tex);
        gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    }
    /* half floats from floats: GLES 3.0 converts, and filters half floats without an extension */
    gl->BindTexture(GL_TEXTURE_3D, m->tex);
    gl->TexImage3D(GL_TEXTURE_3D, 0, GL_RGBA16F, g->n[0], g->n[1], g->n[2], 0, GL_RGBA, GL_FLOAT, g->out);
    gl->BindTexture(GL_TEXTURE_3D, 0);
    gl->ActiveTexture(GL_TEXTURE0);
    m->tex_lo = g->lo;
    m->tex_size = v3(g->n[0] * g->h[0], g->n[1] * g->h[1], g->n[2] * g->h[2]);
}

static double ms_since(const struct timespec *t0)
{
    struct timespec t1;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    return 1e3 * (t1.tv_sec - t0->tv_sec) + 1e-6 * (t1.tv_nsec - t0->tv_nsec);
}

/* A cloud new to a running sky: its grid of half the cells a side sampled (an eighth of the fine grid's samples),
 * solved whole now (about a sixteenth of the fine solve's work) and shown; the fine grid is then sampled and solved
 * within the frames' work, its solve starting from this answer (m->coarse, kept until then). 1 when the grid is too
 * small to halve, or out of memory: then the fine grid is sampled and solved whole. */
static int coarse_first(const cu_gpu_scene *ctx, cu_cloud_msd *m, const cu_cloud *cl, vec3 sun)
{
    const cu_msd *g = &m->grid;
    if (g->n[0] < 2 * CU_MSD_MIN_CELLS && g->n[1] < 2 * CU_MSD_MIN_CELLS && g->n[2] < 2 * CU_MSD_MIN_CELLS)
        return 1;
    if (cu_msd_coarsen(g, &m->coarse)) /* the box; its density is the cloud's own, sampled */
        return 1;
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    cu_msd_sample(&m->coarse, cl);
    cu_msd_solve(&m->coarse, sun, ctx->msd_f, ctx->msd_g, MSD_MOST_SWEEPS, MSD_TOL);
    upload(ctx, m, &m->coarse);
    cu_gpu_log(ctx, CU_LOG_DEBUG, "ms.mode = diffusion: a new cloud's coarse grid first: %dx%dx%d cells, %d sweeps, "
               "%.0f ms on the CPU", m->coarse.n[0], m->coarse.n[1], m->coarse.n[2], m->coarse.sweeps, ms_since(&t0));
    m->sun = sun;
    m->solved = 1;
    return 0;
}

int cu_pass_msd_update(const cu_gpu_scene *ctx, cu_cloud_msd *m, const cu_cloud *cl, vec3 sun, int resample,
                       long *work, cu_error *err)
{
    if (!m->grid.ke) {
        if (cu_msd_init(&m->grid, cl, ctx->scene->ms_grid, err))
            return 1;
        resample = 1;
    }
    m->resample |= resample || !m->sampled;
    m->pending = 0;
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    long cells = (long)m->grid.n[0] * m->grid.n[1] * m->grid.n[2];
    if (!m->grid.solving) {
        if (m->solved && !m->resample && !m->sample_k && !m->stale &&
            v3_dot(m->sun, sun) >= cos(CU_MSD_SUN_STEP * CU_PI / 180.0))
            return 0;
        m->pending = 1;
        if (!m->solved && work)
            coarse_first(ctx, m, cl, sun);
        long *paid = m->solved ? work : NULL; /* a first solve samples and starts whole */
        if (paid && *paid <= 0)
            return 0; /* a later frame's: until then the cloud keeps the light it has */
        if (m->resample || m->sample_k) { /* never while a solve is under way: its coefficients come from the density */
            long slice = (long)m->grid.n[0] * m->grid.n[1] * MSD_SAMPLE_WORK;
            if (!m->sample_k)
                m->resample = 0; /* a new look while it samples is sampled after it */
            int k1 = paid ? m->sample_k + (int)((*paid + slice - 1) / slice) : m->grid.n[2];
            if (k1 > m->grid.n[2])
                k1 = m->grid.n[2];
            cu_msd_sample_slices(&m->grid, cl, m->sample_k, k1);
            if (paid)
                *paid -= (k1 - m->sample_k) * slice;
            m->sample_k = k1 < m->grid.n[2] ? k1 : 0;
            m->sampled = 1;
            m->stale = 1; /* its light is of the density before */
            if (m->sample_k) /* the rest in later frames */
                return 0;
            if (paid && *paid <= 0)
                return 0;
        }
        if (m->coarse.ke) { /* a new cloud's: its solve starts from the coarse grid's answer */
            cu_msd_start_from(&m->grid, &m->coarse);
            cu_msd_free(&m->coarse);
        }
        if (paid)
            *paid -= cells * MSD_BEGIN_WORK;
        cu_msd_solve_begin(&m->grid, sun, ctx->msd_f, ctx->msd_g, MSD_MOST_SWEEPS, MSD_TOL);
        m->stale = 0;
        m->solving_sun = sun;
        m->solve_frames = 0;
        m->solve_ms = 0.0;
    }
    if (!m->solved)
        work = NULL; /* nothing to show yet: whole, now */
    int sweeps = MSD_MOST_SWEEPS;
    if (work && *work / cells < sweeps)
        sweeps = *work / cells > 1 ? (int)(*work / cells) : 1;
    int ran = cu_msd_solve_continue(&m->grid, sweeps);
    if (work)
        *work -= ran * cells;
    m->solve_frames++;
    m->solve_ms += ms_since(&t0);
    m->pending = m->grid.solving;
    if (m->grid.solving)
        return 0;
    m->sun = m->solving_sun;
    m->solved = 1;
    cu_gpu_log(ctx, CU_LOG_DEBUG, "ms.mode = diffusion: %dx%dx%d cells of %.0fx%.0fx%.0f m, %d sweeps in %d frame%s, "
               "last change %.1e, %.0f ms on the CPU", m->grid.n[0], m->grid.n[1], m->grid.n[2], m->grid.h[0],
               m->grid.h[1], m->grid.h[2], m->grid.sweeps, m->solve_frames, m->solve_frames == 1 ? "" : "s",
               m->grid.change, m->solve_ms);
    upload(ctx, m, &m->grid);
    return 0;
}

void cu_pass_msd_bind(cu_gpu_scene *ctx, const cu_cloud_msd *m)
{
    ctx->msd_tex = m->tex;
    ctx->msd_lo = m->tex_lo;
    ctx->msd_size = m->tex_size;
}

void cu_pass_msd_free(cu_cloud_msd *m, const cu_gl *gl)
{
    if (m->tex && gl) /* no GL: the context is gone, and its textures with it */
        gl->DeleteTextures(1, &m->tex);
    cu_msd_free(&m->grid);
    cu_msd_free(&m->coarse);
    m->tex = 0;
    m->sampled = m->resample = m->solved = m->sample_k = m->stale = 0;
}
