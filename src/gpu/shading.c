/* src/gpu/shading.c: cloud.frag's uniforms and textures (see shading.h). */
#include "shading.h"
#include "collector.h"
#include "phase.h"
#include <math.h>

void cu_shading_locs_get(const cu_gl *gl, GLuint p, cu_shading_locs *l)
{
    cu_density_locs_get(gl, p, &l->density);
    cu_sun_locs_get(gl, p, &l->sun);
#define LOC(f) l->f = cu_gpu_loc(gl, p, "u_" #f)
    LOC(viewproj); LOC(inv_viewproj); LOC(cam); LOC(bound_R); LOC(seg_ratio); LOC(boundary_step); LOC(ramp_step); LOC(phase_n); LOC(sun_irr);
    LOC(sky_rad); LOC(ground_rad); LOC(ms_abc); LOC(ms_g); LOC(peak_f); LOC(ms_gain); LOC(out_scale); LOC(out_max);
    LOC(slab_t); LOC(slab_thv); LOC(slab_thl); LOC(slab_th); LOC(slab_lod); LOC(sky_right); LOC(sky_up);
    LOC(coll_t); LOC(coll_thl); LOC(coll_thv); LOC(coll_phi);
    LOC(ortho); LOC(view_dir); LOC(inv_viewport); LOC(host_depth_on); LOC(host_inv_vp); LOC(host_clear); LOC(host_scale);
    LOC(shadow_g); LOC(px_map); LOC(motion); LOC(msd_lo); LOC(msd_size); LOC(msd_dm);
#undef LOC
    cu_gpu_unit(gl, p, "u_sun_ext", CU_UNIT_SHADOW);
    cu_gpu_unit(gl, p, "u_host_depth", CU_UNIT_HOST_DEPTH);
    cu_gpu_unit(gl, p, "u_phase", CU_UNIT_PHASE);
    cu_gpu_unit(gl, p, "u_slab_tab", CU_UNIT_SLAB + 0);
    cu_gpu_unit(gl, p, "u_slab_a", CU_UNIT_SLAB + 1);
    cu_gpu_unit(gl, p, "u_slab_n", CU_UNIT_SLAB + 2);
    cu_gpu_unit(gl, p, "u_sky_a", CU_UNIT_SLAB + 3);
    cu_gpu_unit(gl, p, "u_sky_n", CU_UNIT_SLAB + 4);
    cu_gpu_unit(gl, p, "u_coll", CU_UNIT_SLAB + 5);
    cu_gpu_unit(gl, p, "u_msd", CU_UNIT_MSD);
}

static void set_array(const cu_gl *gl, GLint loc, const double *x, int n)
{
    float v[64]; /* every axis of the tables has at most 32 nodes (slabmodel.h, collector.h) */
    for (int i = 0; i < n; i++)
        v[i] = (float)x[i];
    gl->Uniform1fv(loc, n, v);
}

/* ms_slab.glsl and ms_collector.glsl: the fitted tables' axes, the blur as a mip level, the zenith map's axes. */
static void slab_uniforms(const cu_gpu_scene *ctx, const cu_shading_locs *l)
{
    const cu_slab_maps *s = &ctx->slab;
    if (!s->tab)
        return;
    const cu_gl *gl = ctx->gl;
    const cu_slab_model *m = s->model;
    set_array(gl, l->slab_t, m->t, m->nt);
    set_array(gl, l->slab_thv, m->thv, m->nv);
    set_array(gl, l->slab_thl, m->thl, m->nl);
    set_array(gl, l->slab_th, m->th, m->np);
    /* the blur in metres as a mip level of the sun-sized maps: level L averages 2^L texels of 2R / size */
    double texel = 2.0 * ctx->sun_R / ctx->sun_size;
    double lod = log2(fmax(ctx->scene->ms_blur_m / texel, 1.0));
    gl->Uniform1f(l->slab_lod, (float)lod);
    gl->Uniform3f(l->sky_right, (float)s->sky_right.x, (float)s->sky_right.y, (float)s->sky_right.z);
    gl->Uniform3f(l->sky_up, (float)s->sky_up.x, (float)s->sky_up.y, (float)s->sky_up.z);
    if (s->coll) {
        const cu_collector *c = s->collector;
        set_array(gl, l->coll_t, c->t, c->nt);
        set_array(gl, l->coll_thl, c->thl, c->nl);
        set_array(gl, l->coll_thv, c->thv, c->nv);
        set_array(gl, l->coll_phi, c->phi, c->np);
    }
}

void cu_shading_camera(const cu_gpu_scene *ctx, const cu_shading_locs *l, vec3 cam, const float *vp,
                       const float *inv_vp)
{
    const cu_gl *gl = ctx->gl;
    gl->UniformMatrix4fv(l->viewproj, 1, GL_FALSE, vp);
    gl->UniformMatrix4fv(l->inv_viewproj, 1, GL_FALSE, inv_vp);
    gl->Uniform3f(l->cam, (float)cam.x, (float)cam.y, (float)cam.z);
}

void cu_shading_frame(const cu_gpu_scene *ctx, const cu_shading_locs *l)
{
    const cu_gl *gl = ctx->gl;
    const cu_camera *c = &ctx->camera;
    gl->Uniform1i(l->ortho, c->ortho);
    gl->Uniform3f(l->view_dir, (float)c->view_dir.x, (float)c->view_dir.y, (float)c->view_dir.z);
    /* a pass at 1/N resolution: its pixel i is the frame's N (i + 1/2), whatever the rounding of its size */
    float px = (float)(ctx->host_scale > 0 ? ctx->host_scale : 1);
    if (ctx->pass_w > 0) /* the temporal grid's own target, under its shifted projection */
        gl->Uniform2f(l->inv_viewport, 1.0f / (float)ctx->pass_w, 1.0f / (float)ctx->pass_h);
    else
        gl->Uniform2f(l->inv_viewport, px / (float)ctx->width, px / (float)ctx->height);
    gl->Uniform4f(l->px_map, ctx->px_map[0], ctx->px_map[1], ctx->px_map[2], ctx->px_map[3]);
    gl->Uniform2f(l->motion, ctx->motion[0], ctx->motion[1]);
    gl->Uniform1i(l->host_depth_on, ctx->host_depth.tex != 0);
    gl->UniformMatrix4fv(l->host_inv_vp, 1, GL_FALSE, c->host_inv_vp);
    gl->Uniform1f(l->host_clear, ctx->host_depth.clear);
    gl->Uniform1f(l->host_scale, (float)(ctx->host_scale > 0 ? ctx->host_scale : 1));
}

void cu_shading_uniforms(const cu_gpu_scene *ctx, GLuint p, const cu_shading_locs *l, vec3 cam, const float *vp,
                         const float *inv_vp)
{
    const cu_gl *gl = ctx->gl;
    const cu_scene *s = ctx->scene;
    const cu_sky *sky = ctx->sky;
    gl->UseProgram(p);
    cu_shading_camera(ctx, l, cam, vp, inv_vp);
    gl->Uniform1f(l->bound_R, (float)ctx->cloud->bound_radius);
    cu_density_uniforms(ctx, &l->density);
    cu_sun_uniforms(ctx, &l->sun);
    gl->Uniform1f(l->seg_ratio, (float)s->segment_ratio);
    gl->Uniform1f(l->boundary_step, (float)s->boundary_step);
    gl->Uniform1f(l->ramp_step, (float)s->ramp_step);
    gl->Uniform1i(l->phase_n, CU_PHASE_N);
    gl->Uniform3f(l->sun_irr, (float)sky->sun_irradiance[0], (float)sky->sun_irradiance[1],
                  (float)sky->sun_irradiance[2]);
    double amb = s->sky_light ? 1.0 : 0.0;
    gl->Uniform3f(l->sky_rad, (float)(amb * sky->sky_mean[0]), (float)(amb * sky->sky_mean[1]),
                  (float)(amb * sky->sky_mean[2]));
    gl->Uniform3f(l->ground_rad, (float)(amb * sky->ground_mean[0]), (float)(amb * sky->ground_mean[1]),
                  (float)(amb * sky->ground_mean[2]));
    slab_uniforms(ctx, l);
    gl->Uniform3f(l->ms_abc, (float)s->ms_a, (float)s->ms_b, (float)s->ms_c);
    gl->Uniform1f(l->ms_g, (float)s->phase_g);
    gl->Uniform3f(l->peak_f, (float)ctx->peak_f[0], (float)ctx->peak_f[1], (float)ctx->peak_f[2]);
    gl->Uniform2f(l->ms_gain, (float)ctx->ms_gain[0], (float)ctx->ms_gain[1]);
    gl->Uniform3f(l->msd_lo, (float)ctx->msd_lo.x, (float)ctx->msd_lo.y, (float)ctx->msd_lo.z);
    gl->Uniform3f(l->msd_size, (float)ctx->msd_size.x, (float)ctx->msd_size.y, (float)ctx->msd_size.z);
    gl->Uniform3f(l->msd_dm, (float)((1.0 - ctx->msd_f) / (1.0 - ctx->peak_f[1])), (float)ctx->msd_g,
                  (float)(1.0 - ctx->msd_f));
    gl->Uniform1f(l->shadow_g, (float)cu_shadow_g(ctx));
    float os[3];
    cu_out_scale(ctx, os);
    gl->Uniform3f(l->out_scale, os[0], os[1], os[2]);
    gl->Uniform1f(l->out_max, cu_out_max(ctx));
}

void cu_shading_bind(const cu_gpu_scene *ctx)
{
    const cu_gl *gl = ctx->gl;
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_NOISE);
    gl->BindTexture(GL_TEXTURE_3D, ctx->noise_tex);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_PHASE);
    gl->BindTexture(GL_TEXTURE_2D, ctx->phase_tex);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_SUN_MAP);
    gl->BindTexture(GL_TEXTURE_2D, ctx->sun.map);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_SUN_TAU);
    gl->BindTexture(GL_TEXTURE_2D, ctx->sun.tau);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_SHADOW);
    gl->BindTexture(GL_TEXTURE_2D, ctx->sun_ext);
    if (ctx->ms_mode == CU_MS_DIFFUSION) {
        gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_MSD);
        gl->BindTexture(GL_TEXTURE_3D, ctx->msd_tex);
    }
    const cu_slab_maps *s = &ctx->slab;
    if (s->tab) {
        GLuint t[6] = {s->tab, s->a[0], s->n[0], s->a[1], s->n[1], s->coll};
        for (int i = 0; i < 6; i++) {
            gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_SLAB + (GLenum)i);
            gl->BindTexture(GL_TEXTURE_2D, t[i]);
        }
    }
    gl->ActiveTexture(GL_TEXTURE0);
}
