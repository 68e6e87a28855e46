/* src/gpu/pass_energy.c: the slab model's energy closure.
 *
 * Why: the slab model is local. Each point of a cloud is lit as if it lay in an infinite slab fitted around it, so a
 * finite cloud can send out more light than it intercepts: light that leaves a real cloud through its sides is also
 * counted at its faces, and the blurred slab maps light the flanks as if they faced the sun (docs/gpu_notes.md has
 * the measured excess).
 *
 * What: when the sun or the clouds change, the cloud's sunlit terms are rendered small (EN_SIZE pixels square,
 * cloud.frag with ENERGY_PASS) from EN_VIEWS directions in bands of the scattering angle about the sun. Radiance
 * times pixel footprint summed over a view is the radiant intensity toward that direction; each view stands for its
 * cell of the sphere of directions:
 *   - multiple scattering, reflected and transmitted apart (the eye on the lit side of the fitted slab or not):
 *     intensity x the cell's solid angle (P_r, P_t);
 *   - single scattering (P_ss): the intensity is the phase function P~(Theta) times a factor smooth in direction, so
 *     it is weighted by the integral of P~ over the cell over P~ at the view (a plain rule would put the forward
 *     lobe's peak on a whole cell).
 * A budget view from the sun (EN_SUN_SIZE square) gives per column its optical depth tau and the sun's angle thL to
 * the slab fitted where it enters: what the chopped medium intercepts, 1 - e^-(1-f) tau (P_in), and what a slab of
 * thickness tau cos(thL) lit at thL reflects and transmits by multiple scattering (B_r, B_t: the tables' own budget,
 * cu_slab_model_ms_budget). Reflected and transmitted light are each scaled down to their budget, then both together
 * to what single scattering leaves, P_in - P_ss: the column budget alone does not bound a cloud whose single
 * scattering exceeds a slab's, the total alone would let the errors of P_ss decide, and a single gain would darken
 * transmitted light that was within its budget. A cloud within its budgets is left alone; a wide flat cloud keeps
 * gains 1. The forward peak is left out on both sides (its energy is exact by construction, cloud.frag). One pair of
 * gains per scene: a field of clouds shares it.
 *
 * Cost: EN_VIEWS x 16 x 16 + 64 x 64 cloud fragments and two read-backs, only when the clouds change or the sun has
 * moved by 1 deg. */
#include "pass_energy.h"
#include "error.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EN_SIZE 16
#define EN_SUN_SIZE 64 /* the budget view from the sun: its columns set the budgets, so finer than the views */
#define EN_BANDS 8
#define EN_VIEWS 26
#define EN_DIST 64.0 /* camera distance in bounding radii: rays parallel to 1/64 rad, footprints equal to 1.6 % */
/* bands of the scattering angle (degrees) and views per band: a cap at each pole, four azimuths between */
static const double BAND_EDGE[EN_BANDS + 1] = {0, 15, 40, 65, 90, 115, 140, 165, 180};
static const int BAND_NPHI[EN_BANDS] = {1, 4, 4, 4, 4, 4, 4, 1};
typedef char band_views_add_up[1 + 6 * 4 + 1 == EN_VIEWS ? 1 : -1];
typedef char band_weights_fit[EN_BANDS == CU_ENERGY_BANDS ? 1 : -1];

static double band_node(int b) /* the view's scattering angle in band b, radians: the poles, else mid-cosine */
{
    if (b == 0)
        return 0;
    if (b == EN_BANDS - 1)
        return CU_PI;
    double m0 = cos(BAND_EDGE[b] * CU_PI / 180), m1 = cos(BAND_EDGE[b + 1] * CU_PI / 180);
    return acos(0.5 * (m0 + m1));
}

/* P~ (green) at scattering angle x radians, linear between the table's nodes (as cloud.frag's phase_table) */
static double phase_at(const cu_phase_table *t, double x)
{
    double u = x / CU_PI * (t->n - 1);
    int j = u >= t->n - 1 ? t->n - 2 : (int)u;
    return t->rgb[3 * j + 1] + (u - j) * (t->rgb[3 * (j + 1) + 1] - t->rgb[3 * j + 1]);
}

static void phase_weights(cu_pass_energy *p, const cu_phase_table *t)
{
    double h = CU_PI / (t->n - 1);
    for (int b = 0; b < EN_BANDS; b++) {
        /* trapezoids of P~ sin(Theta) on the table's grid, cut at the band edges a and z */
        double a = BAND_EDGE[b] * CU_PI / 180, z = BAND_EDGE[b + 1] * CU_PI / 180, sum = 0;
        double prev_x = a, prev_f = phase_at(t, a) * sin(a);
        for (int i = (int)floor(a / h) + 1; prev_x < z; i++) {
            double x = fmin(i * h, z), fx = phase_at(t, x) * sin(x);
            sum += 0.5 * (fx + prev_f) * (x - prev_x);
            prev_x = x;
            prev_f = fx;
        }
        double p_node = phase_at(t, band_node(b));
        /* per view: the band's integral of P~ shared by its views, over P~ at the view */
        p->ss_w[b] = p_node > 0 ? 2.0 * CU_PI * sum / BAND_NPHI[b] / p_node : 0.0;
    }
}

int cu_pass_energy_create(cu_pass_energy *p, const cu_gpu_scene *ctx, const cu_phase_table *t, const char *fs_defs,
                          cu_error *err)
{
    memset(p, 0, sizeof *p);
    p->gain[0] = p->gain[1] = 1.0;
    phase_weights(p, t);
    if ((ctx->ms_mode != CU_MS_SLAB && ctx->ms_mode != CU_MS_COLLECTOR) || !ctx->scene->ms_closure)
        return 0;
    const cu_gl *gl = ctx->gl;
    char defs[2048];
    if (snprintf(defs, sizeof defs, "%s#define ENERGY_PASS 1\n", fs_defs) >= (int)sizeof defs)
        return cu_fail(err, "energy closure: shader defines too long");
    if (!(p->prog = cu_gl_program(gl, "fullscreen.vert", "cloud.frag", defs, err)))
        return 1;
    cu_shading_locs_get(gl, p->prog, &p->locs);
    p->budget_view = cu_gpu_loc(gl, p->prog, "u_budget_view");
    /* the slab model already needs half-float targets; RGBA32F where it renders, for the sums' precision */
    cu_target_desc d = {.name = "energy closure", .width = EN_SIZE * EN_VIEWS + EN_SUN_SIZE, .height = EN_SUN_SIZE,
                        .format = ctx->float_rt ? GL_RGBA32F : GL_RGBA16F, .colors = 1};
    return cu_target_create(&p->target, gl, &d, err);
}

void cu_pass_energy_destroy(cu_pass_energy *p, const cu_gl *gl)
{
    if (p->prog)
        gl->DeleteProgram(p->prog);
    p->prog = 0;
    cu_target_delete(&p->target, gl);
}

/* The views: direction d the light leaves toward (scattering angle Theta from the sunbeam -s), the band it stands
 * for, and its solid angle. Azimuths start 0.4 rad off the sun's horizontal axis, so no view lies exactly in a
 * horizontal layer (seen edge on, a layer thinner than a pixel falls between the pixel centres). */
static void views(vec3 s, vec3 right, vec3 up, vec3 *d, int *band, double *omega)
{
    int n = 0;
    for (int b = 0; b < EN_BANDS; b++) {
        double th = band_node(b);
        double cell = 2.0 * CU_PI * (cos(BAND_EDGE[b] * CU_PI / 180) - cos(BAND_EDGE[b + 1] * CU_PI / 180)) /
                      BAND_NPHI[b];
        for (int j = 0; j < BAND_NPHI[b]; j++) {
            double ph = 0.4 + (j + 0.5) * 2.0 * CU_PI / BAND_NPHI[b];
            vec3 side = v3_add(v3_scale(right, cos(ph)), v3_scale(up, sin(ph)));
            d[n] = v3_add(v3_scale(s, -cos(th)), v3_scale(side, sin(th)));
            band[n] = b;
            omega[n++] = cell;
        }
    }
}

void cu_pass_energy_update(cu_pass_energy *p, const cu_gpu_scene *ctx)
{
    if (!p->prog || !(ctx->cloud->ke > 0))
        return;
    /* The gains change smoothly with the sun (test_ms bounds the change per step): kept while the sun stays within
     * 1 deg of where they were measured, so a knob turned slowly pays for them once a degree. */
    if (p->valid && v3_dot(p->sun, ctx->sun_dir) > cos(CU_PI / 180))
        return;
    p->valid = 1;
    p->sun = ctx->sun_dir;
    p->gain[0] = p->gain[1] = 1.0;
    const cu_gl *gl = ctx->gl;
    vec3 d[EN_VIEWS];
    int band[EN_VIEWS];
    double omega[EN_VIEWS];
    views(ctx->sun_dir, ctx->sun_right, ctx->sun_up, d, band, omega);
    double R = ctx->cloud->bound_radius, D = EN_DIST * R;
    double fov = 2.0 * atan(R / D);
    cu_shading_bind(ctx);
    gl->BindFramebuffer(GL_FRAMEBUFFER, p->target.fbo);
    gl->Viewport(0, 0, EN_SIZE * EN_VIEWS + EN_SUN_SIZE, EN_SUN_SIZE);
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_BLEND);
    gl->Disable(GL_CULL_FACE);
    gl->ClearColor(0, 0, 0, 0);
    gl->Clear(GL_COLOR_BUFFER_BIT);
    gl->BindVertexArray(ctx->empty_vao);
    for (int k = 0; k <= EN_VIEWS; k++) { /* the views, then the budget view from the sun (= the last view's) */
        /* the camera on the side the light leaves toward: at D d, looking along -d */
        vec3 dk = d[k < EN_VIEWS ? k : EN_VIEWS - 1];
        vec3 cam = v3_scale(dk, D), look = v3_scale(dk, -1.0);
        vec3 up = fabs(look.y) > 0.9 ? v3(1, 0, 0) : v3(0, 1, 0);
        mat4 vp = m4_mul(m4_perspective(fov, 1.0, D - 2.0 * R, D + 2.0 * R), m4_look_dir(cam, look, up));
        float vpf[16], inv[16];
        m4_to_float(vp, vpf);
        m4_to_float(m4_inverse(vp), inv);
        if (k == 0) /* everything but the camera is the same for all views */
            cu_shading_uniforms(ctx, p->prog, &p->locs, cam, vpf, inv);
        else
            cu_shading_camera(ctx, &p->locs, cam, vpf, inv);
        gl->Uniform1i(p->budget_view, k == EN_VIEWS);
        gl->Viewport(EN_SIZE * k, 0, k == EN_VIEWS ? EN_SUN_SIZE : EN_SIZE, k == EN_VIEWS ? EN_SUN_SIZE : EN_SIZE);
        gl->DrawArrays(GL_TRIANGLES, 0, 3);
    }
    const int strip = EN_SIZE * EN_VIEWS, ns = EN_SUN_SIZE * EN_SUN_SIZE;
    float *px4 = malloc(sizeof(float) * 4 * ((size_t)strip * EN_SIZE + (size_t)ns)), *sun4 = px4 + 4 * strip * EN_SIZE;
    if (!px4) {
        gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
        cu_gpu_log(ctx, CU_LOG_WARN, "energy closure: out of memory: multiple scattering unscaled");
        return;
    }
    gl->ReadPixels(0, 0, strip, EN_SIZE, GL_RGBA, GL_FLOAT, px4);
    gl->ReadPixels(strip, 0, EN_SUN_SIZE, EN_SUN_SIZE, GL_RGBA, GL_FLOAT, sun4);
    GLenum e = gl->GetError();
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (e != GL_NO_ERROR) {
        free(px4);
        cu_gpu_log(ctx, CU_LOG_WARN, "energy closure: read-back failed (GL error 0x%x): multiple scattering unscaled",
                   e);
        return;
    }
    /* pixel footprints on the plane through the centre */
    double p_ss = 0, p_r = 0, p_t = 0, p_in = 0, b_r = 0, b_t = 0, f = ctx->peak_f[1];
    for (int k = 0; k < EN_VIEWS; k++) {
        double a = (2.0 * R / EN_SIZE) * (2.0 * R / EN_SIZE);
        for (int y = 0; y < EN_SIZE; y++)
            for (int x = 0; x < EN_SIZE; x++) {
                const float *q = px4 + 4 * ((size_t)y * strip + (size_t)(EN_SIZE * k + x));
                p_ss += p->ss_w[band[k]] * q[0] * a;
                p_r += omega[k] * q[1] * a;
                p_t += omega[k] * q[2] * a;
            }
    }
    /* from the sun, a column a pixel: optical depth tau along it and the cosine of the sun's angle to its slab */
    double a = (2.0 * R / EN_SUN_SIZE) * (2.0 * R / EN_SUN_SIZE);
    for (int i = 0; i < ns; i++) {
        double tau = sun4[4 * i], mu0 = sun4[4 * i + 1], up, down;
        if (!(tau > 0))
            continue;
        cu_slab_model_ms_budget(ctx->slab.model, tau * mu0 / CU_SLAB_KE_REF, acos(fmin(mu0, 1.0)) * 180 / CU_PI, &up,
                                &down);
        p_in += (1.0 - exp(-(1.0 - f) * tau)) * a;
        b_r += up * a;
        b_t += down * a;
    }
    free(px4);
    if (!(isfinite(p_ss) && isfinite(p_r) && isfinite(p_t) && isfinite(p_in) && isfinite(b_r) && isfinite(b_t))) {
        cu_gpu_log(ctx, CU_LOG_WARN, "energy closure: non-finite powers: multiple scattering unscaled");
        return;
    }
    /* each side within its column budget, then the total within what single scattering leaves */
    double g_r = p_r > b_r ? b_r / p_r : 1.0, g_t = p_t > b_t ? b_t / p_t : 1.0;
    double ms = g_r * p_r + g_t * p_t, left = fmax(p_in - p_ss, 0.0);
    if (ms > left) {
        g_r *= left / ms;
        g_t *= left / ms;
    }
    p->gain[0] = g_r;
    p->gain[1] = g_t;
    cu_gpu_log(ctx, CU_LOG_DEBUG, "energy closure: intercepted %.4g m^2, single %.4g, multiple reflected %.4g of %.4g, "
           "transmitted %.4g of %.4g: gains %.4f %.4f", p_in, p_ss, p_r, b_r, p_t, b_t, g_r, g_t);
}
