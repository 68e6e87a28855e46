/* src/gpu/pass_msd.c: a cloud's diffusion grid, solved and uploaded (see pass_msd.h). */
#include "pass_msd.h"
#include <math.h>
#include <time.h>

/* Relaxation sweeps at most, and the change in a sweep (of the summed fluence) at which a solve stops: about a
 * thousandth of the fluence left to converge at the rate these grids relax. */
#define MSD_MOST_SWEEPS 1000
#define MSD_TOL 1e-5

static void upload(const cu_gpu_scene *ctx, cu_cloud_msd *m)
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
    gl->TexImage3D(GL_TEXTURE_3D, 0, GL_RGBA16F, m->grid.n[0], m->grid.n[1], m->grid.n[2], 0, GL_RGBA, GL_FLOAT,
                   m->grid.out);
    gl->BindTexture(GL_TEXTURE_3D, 0);
    gl->ActiveTexture(GL_TEXTURE0);
}

static double ms_since(const struct timespec *t0)
{
    struct timespec t1;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    return 1e3 * (t1.tv_sec - t0->tv_sec) + 1e-6 * (t1.tv_nsec - t0->tv_nsec);
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
    if (!m->solved)
        work = NULL; /* nothing to show until its first solve is done: whole, now */
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    m->pending = 0;
    if (!m->grid.solving) {
        if (m->solved && !m->resample && v3_dot(m->sun, sun) >= cos(CU_MSD_SUN_STEP * CU_PI / 180.0))
            return 0;
        m->pending = 1;
        if (work && *work <= 0)
            return 0; /* a later frame's: until then the cloud keeps the light it has */
        if (m->resample) { /* never while a solve is under way: its coefficients come from the density */
            cu_msd_sample(&m->grid, cl);
            m->sampled = 1;
            m->resample = 0;
        }
        cu_msd_solve_begin(&m->grid, sun, ctx->msd_f, ctx->msd_g, MSD_MOST_SWEEPS, MSD_TOL);
        m->solving_sun = sun;
        m->solve_frames = 0;
        m->solve_ms = 0.0;
    }
    long cells = (long)m->grid.n[0] * m->grid.n[1] * m->grid.n[2];
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
    upload(ctx, m);
    return 0;
}

void cu_pass_msd_bind(cu_gpu_scene *ctx, const cu_cloud_msd *m)
{
    const cu_msd *g = &m->grid;
    ctx->msd_tex = m->tex;
    ctx->msd_lo = g->lo;
    ctx->msd_size = v3(g->n[0] * g->h[0], g->n[1] * g->h[1], g->n[2] * g->h[2]);
}

void cu_pass_msd_free(cu_cloud_msd *m, const cu_gl *gl)
{
    if (m->tex && gl) /* no GL: the context is gone, and its textures with it */
        gl->DeleteTextures(1, &m->tex);
    cu_msd_free(&m->grid);
    m->tex = 0;
    m->sampled = m->resample = m->solved = 0;
}
