/* src/gpu/pass_sky.c: the sky pass (see pass_sky.h). */
#include "pass_sky.h"
#include "camera.h"
#include "error.h"
#include <stdio.h>
#include <math.h>
#include <string.h>

static void locs_get(const cu_gl *gl, GLuint prog, cu_sky_locs *l)
{
    cu_sun_locs_get(gl, prog, &l->sun);
#define LOC(f) l->f = cu_gpu_loc(gl, prog, "u_" #f)
    LOC(inv_viewproj); LOC(sun_irr); LOC(out_max); LOC(ground); LOC(out_scale); LOC(sky_color);
    LOC(ground_sun); LOC(eye); LOC(gmap); LOC(gmap2); LOC(shadow_g); LOC(cloud_factor); LOC(refined_on);
    LOC(grid_box); LOC(grid_cell); LOC(grid_size); LOC(grid_cols);
#undef LOC
    cu_gpu_unit(gl, prog, "u_clouds", CU_UNIT_CLOUDS);
    cu_gpu_unit(gl, prog, "u_refined", CU_UNIT_REFINED);
    cu_gpu_unit(gl, prog, "u_ground_tau", CU_UNIT_SHADOW);
    cu_gpu_unit(gl, prog, "u_ground_tau2", CU_UNIT_GROUND2);
    cu_gpu_unit(gl, prog, "u_sky_tables", CU_UNIT_SKY);
}

/* Makes the program of a kind, part, count of ground maps and shape (CU_SKY_PIXEL...), once. */
static int program(cu_pass_sky *p, const cu_gl *gl, int kind, int part, int maps, int shape, cu_error *err)
{
    static const char *const kinds[CU_SKY_KINDS] = {"", "#define SKY_TONEMAP 1\n",
                                                    "#define SKY_TONEMAP 1\n#define SKY_COMPOSITE 1\n",
                                                    "#define SKY_TONEMAP 1\n#define SKY_CORNER_TONE 1\n"};
    if (p->prog[kind][part][maps][shape])
        return 0;
    char defs[2200];
    if (snprintf(defs, sizeof defs, "%s%s#define SKY_PART %d\n#define GROUND_MAPS %d\n#define SKY_VERTEX %d\n",
                 p->defines, kinds[kind], part, maps, shape) >= (int)sizeof defs)
        return cu_fail(err, "sky: shader defines too long");
    if (!(p->prog[kind][part][maps][shape] = cu_gl_program(gl, "sky.vert", "sky.frag", defs, err)))
        return 1;
    locs_get(gl, p->prog[kind][part][maps][shape], &p->loc[kind][part][maps][shape]);
    return 0;
}

int cu_pass_sky_create(cu_pass_sky *p, const cu_gpu_scene *ctx, const char *defines, cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    memset(p, 0, sizeof *p);
    if (snprintf(p->defines, sizeof p->defines, "%s#define SKY_TABLE %d\n", defines, CU_SKY_TABLE) >=
        (int)sizeof p->defines)
        return cu_fail(err, "sky: shader defines too long");
    for (int kind = 0; kind < CU_SKY_ALONE; kind++) /* CU_SKY_ALONE draws a pixel at a time as CU_SKY_OUT */
        if (program(p, gl, kind, CU_SKY_BOTH, 0, CU_SKY_PIXEL, err))
            return 1;
    gl->GenTextures(1, &p->tables);
    gl->BindTexture(GL_TEXTURE_2D, p->tables);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return 0;
}

/* The Perez tables for this sky, rebuilt only when its coefficients changed (the sun moved, the turbidity changed):
 * 2 x 256 entries on the CPU and an 8 KiB upload. RGBA32F, read with texelFetch and interpolated in sky.frag. */
static void tables_update(cu_pass_sky *p, const cu_gl *gl, const cu_sky *sky)
{
    double of[21];
    memcpy(of, sky->perez, sizeof sky->perez);
    memcpy(of + 15, sky->zenith, sizeof sky->zenith);
    memcpy(of + 18, sky->norm, sizeof sky->norm);
    if (p->tables_built && !memcmp(of, p->tables_of, sizeof of))
        return;
    cu_sky_tables(sky, p->table, p->table + 4 * CU_SKY_TABLE);
    gl->BindTexture(GL_TEXTURE_2D, p->tables);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, CU_SKY_TABLE, 2, 0, GL_RGBA, GL_FLOAT, p->table);
    memcpy(p->tables_of, of, sizeof of);
    p->tables_built = 1;
    p->tables_made++;
}

void cu_pass_sky_destroy(cu_pass_sky *p, const cu_gl *gl)
{
    for (int kind = 0; kind < CU_SKY_KINDS; kind++)
        for (int part = 0; part < CU_SKY_PARTS; part++)
            for (int maps = 0; maps <= CU_GROUND_MAPS; maps++)
                for (int shape = 0; shape < CU_SKY_SHAPES; shape++)
                    if (p->prog[kind][part][maps][shape])
                        gl->DeleteProgram(p->prog[kind][part][maps][shape]);
    if (p->tables)
        gl->DeleteTextures(1, &p->tables);
    memset(p, 0, sizeof *p);
}

static void uniforms(cu_pass_sky *pass, const cu_gpu_scene *ctx, GLuint prog, const cu_sky_locs *p, int factor)
{
    const cu_gl *gl = ctx->gl;
    const cu_sky *sky = ctx->sky;
    const cu_scene *s = ctx->scene;
    gl->UseProgram(prog);
    gl->UniformMatrix4fv(p->inv_viewproj, 1, GL_FALSE, ctx->camera.inv_rot);
    cu_sun_uniforms(ctx, &p->sun);
    gl->Uniform3f(p->sun_irr, (float)sky->sun_irradiance[0], (float)sky->sun_irradiance[1],
                  (float)sky->sun_irradiance[2]);
    gl->Uniform1f(p->out_max, cu_out_max(ctx)); /* the disk capped below what the target holds */
    gl->Uniform3f(p->ground, (float)sky->ground[0], (float)sky->ground[1], (float)sky->ground[2]);
    gl->Uniform3f(p->ground_sun, (float)sky->ground_sun[0], (float)sky->ground_sun[1], (float)sky->ground_sun[2]);
    gl->Uniform3f(p->eye, (float)ctx->camera.pos.x, (float)ctx->camera.pos.y, (float)ctx->camera.pos.z);
    gl->Uniform3f(p->gmap, (float)ctx->ground_map[0].x, (float)ctx->ground_map[0].y, (float)ctx->ground_map[0].z);
    gl->Uniform3f(p->gmap2, (float)ctx->ground_map[1].x, (float)ctx->ground_map[1].y, (float)ctx->ground_map[1].z);
    gl->Uniform1f(p->shadow_g, (float)cu_shadow_g(ctx));
    gl->Uniform1f(p->cloud_factor, (float)factor); /* -1 (no composite): ignored */
    gl->Uniform1i(p->refined_on, pass->refined);
    float os[3];
    cu_out_scale(ctx, os);
    gl->Uniform3f(p->out_scale, os[0], os[1], os[2]);
    if (s->sky_model == CU_SKY_CONSTANT)
        gl->Uniform3f(p->sky_color, (float)s->sky_color[0], (float)s->sky_color[1], (float)s->sky_color[2]);
    else
        tables_update(pass, gl, sky);
}

#define SUN_RADIUS 0.004654 /* rad: acos(0.99998917), sky.frag's test for the disk */
#define SUN_CELL 32         /* pixels a side of the cells sun_box tests */
#define SUN_ROW 514         /* corners in a row of them: up to 16384 pixels wide (output.size's largest) */

/* The pixels (x0, y0, x1, y1, half-open) the grid's interpolation cannot serve near the sun: its disk, and the
 * aureole about it, whose Perez term C e^(D gamma) peaks in a cone at the sun, which a cell across it would cut
 * (at a clear sky's C = 5.3 and D = -2.3, by several levels of the display); two grid cells' width of it away its
 * curvature is small enough. The union of the cells of a coarse grid whose directions come within the disk's radius,
 * that width and a margin far above fp32's rounding of the sun; none: an empty box. A cell's directions lie within
 * the cap about their mean as wide as the largest angle to a corner (its image on the sphere is bounded by great
 * circles, and a cap narrower than a hemisphere is convex), so a cell farther from the sun than that plus the radius
 * holds none of it (a cell of the grid, `grid` pixels, spans about 2 wide grid / SUN_CELL / sqrt 2 of it). NaN (a
 * degenerate camera) counts as near. */
static void sun_box(const float *m, vec3 sun, int w, int h, int grid, int box[4])
{
    int nx = (w + SUN_CELL - 1) / SUN_CELL, ny = (h + SUN_CELL - 1) / SUN_CELL;
    vec3 row[2][SUN_ROW]; /* the directions at the cells' corners, two rows of them */
    box[0] = box[1] = 1 << 30;
    box[2] = box[3] = 0;
    if (nx + 1 > SUN_ROW) { /* wider than any output: every pixel */
        box[0] = box[1] = 0;
        box[2] = w;
        box[3] = h;
        return;
    }
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            int px[2] = {(i - 1) * SUN_CELL, i * SUN_CELL < w ? i * SUN_CELL : w};
            int py[2] = {(j - 1) * SUN_CELL, j * SUN_CELL < h ? j * SUN_CELL : h};
            row[j & 1][i] = cu_sky_dir(m, 2.0 * px[1] / w - 1.0, 2.0 * py[1] / h - 1.0);
            if (i == 0 || j == 0)
                continue;
            vec3 c[4] = {row[j & 1][i - 1], row[j & 1][i], row[~j & 1][i - 1], row[~j & 1][i]}, mean = v3(0, 0, 0);
            for (int k = 0; k < 4; k++)
                mean = v3_add(mean, c[k]);
            mean = v3_norm(mean);
            double wide = 0.0;
            for (int k = 0; k < 4; k++)
                wide = fmax(wide, acos(fmin(fmax(v3_dot(mean, c[k]), -1.0), 1.0)));
            double far = acos(fmin(fmax(v3_dot(mean, sun), -1.0), 1.0));
            if (!(far > wide * (1.0 + 3.0 * grid / SUN_CELL) + SUN_RADIUS + 1e-3)) {
                box[0] = px[0] < box[0] ? px[0] : box[0];
                box[1] = py[0] < box[1] ? py[0] : box[1];
                box[2] = px[1] > box[2] ? px[1] : box[2];
                box[3] = py[1] > box[3] ? py[1] : box[3];
            }
        }
}

static int over_sun(cu_pass_sky *pass, const cu_gpu_scene *ctx, int k, int part, int maps, int factor,
                    const int box[4], const int sun[4], cu_error *err);

/* Pixels box (x0, y0, x1, y1, half-open) with the program of kind k, part and maps: at every pixel (sun NULL, or
 * quality.sky_grid 0, or anything but rows of the Perez sky alone), or at the corners of quality.sky_grid's cells, or
 * once for a colour that is the same at every pixel of it (the ground where no map is read, a constant sky), and
 * then, after the grid or a constant sky, the pixels of sun (sun_box) inside the box at every pixel again. */
static int piece(cu_pass_sky *pass, const cu_gpu_scene *ctx, int k, int part, int maps, int factor, const int box[4],
                 const int sun[4], cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    if (box[2] <= box[0] || box[3] <= box[1])
        return 0;
    int low = part == CU_SKY_LOW, constant = ctx->scene->sky_model == CU_SKY_CONSTANT;
    part = low ? CU_SKY_ABOVE : part;
    /* the grid only for the Perez sky: a constant colour costs less drawn flat than through the grid's triangles on
     * llvmpipe; flat, not with a cloud image over it (that blends and tone-maps a pixel at a time anyway) */
    int cell = ctx->scene->sky_grid, high = low && cell > 4 ? cell / 4 : cell;
    int shape = !sun ? CU_SKY_PIXEL
              : k != CU_SKY_OVER && (constant || (part == CU_SKY_BELOW && maps == 0)) ? CU_SKY_FLAT
              : cell > 0 && part == CU_SKY_ABOVE && !constant ? CU_SKY_GRID : CU_SKY_PIXEL;
    int band = box[1] / CU_SKY_BAND < CU_SKY_BANDS ? box[1] / CU_SKY_BAND : CU_SKY_BANDS - 1;
    int toned = shape == CU_SKY_GRID && k == CU_SKY_ALONE && pass->toned_now ? pass->toned[band][low] : 0;
    if (k == CU_SKY_ALONE && !toned) /* the curve at every pixel */
        k = CU_SKY_OUT;
    pass->toned_runs += toned > 0;
    if (shape == CU_SKY_GRID) { /* the cells of the box's band (draw's runs keep to one) */
        int scale = toned ? toned : pass->scale[band][low] > 0 ? pass->scale[band][low] : 1; /* 0: no plan yet */
        cell *= scale;
        high *= scale;
    }
    if (program(pass, gl, k, part, maps, shape, err))
        return 1;
    const cu_sky_locs *l = &pass->loc[k][part][maps][shape];
    uniforms(pass, ctx, pass->prog[k][part][maps][shape], l, factor);
    gl->Scissor(box[0], box[1], box[2] - box[0], box[3] - box[1]);
    if (shape != CU_SKY_GRID) {
        gl->DrawArrays(GL_TRIANGLES, 0, 3);
        return shape == CU_SKY_FLAT && constant ? over_sun(pass, ctx, k, part, maps, factor, box, sun, err) : 0;
    }
    /* the cells laid from the viewport's corner, whatever the box: every piece and every kind of pass (a frame's
     * sky drawn under the clouds, or straight to the output) then interpolates between the same corners */
    int w = ctx->width, h = ctx->height > 0 ? ctx->height : 1, ox = box[0] / cell * cell, oy = box[1] / high * high;
    int cols = (box[2] - ox + cell - 1) / cell, rows = (box[3] - oy + high - 1) / high;
    gl->Uniform4f(l->grid_box, (float)ox, (float)oy, (float)w, (float)h);
    gl->Uniform2f(l->grid_cell, (float)cell, (float)high);
    gl->Uniform2f(l->grid_size, (float)w, (float)h);
    gl->Uniform1i(l->grid_cols, cols);
    gl->DrawArrays(GL_TRIANGLE_STRIP, 0, (2 * cols + 4) * rows - 2);
    return over_sun(pass, ctx, k, part, maps, factor, box, sun, err);
}

/* The pixels of sun inside box again, each worked out (piece with no sun box: CU_SKY_PIXEL). */
static int over_sun(cu_pass_sky *pass, const cu_gpu_scene *ctx, int k, int part, int maps, int factor,
                    const int box[4], const int sun[4], cu_error *err)
{
    const int disk[4] = {sun[0] > box[0] ? sun[0] : box[0], sun[1] > box[1] ? sun[1] : box[1],
                         sun[2] < box[2] ? sun[2] : box[2], sun[3] < box[3] ? sun[3] : box[3]};
    return piece(pass, ctx, k, part, maps, factor, disk, NULL, err);
}

/* The pixels (x0, y0, x1, y1, half-open) where the ground can show the first `maps` shadow maps: the image of the
 * rectangles that can hold shadow (gpu_scene.h ground_ink) on the ground, through the sky's matrix from the eye,
 * clipped to what lies in front of it; an empty box where none shows. Elsewhere every map reads zero there, and the
 * ground is the same without them. */
static void shadow_box(const cu_gpu_scene *ctx, int maps, int w, int h, int box[4])
{
    const float *m = ctx->camera.rot_vp;
    vec3 eye = ctx->camera.pos;
    double ndc[4] = {1, 1, -1, -1};
    for (int g = 0; g < maps; g++) {
        const double *ink = ctx->ground_ink[g];
        if (!(ink[2] > ink[0] && ink[3] > ink[1]))
            continue;
        double c[4][4], in[8][4];
        for (int k = 0; k < 4; k++) { /* the corners, around the rectangle, in clip space */
            double p[3] = {ink[k == 1 || k == 2 ? 2 : 0] - eye.x, -eye.y, ink[k >= 2 ? 3 : 1] - eye.z};
            for (int r = 0; r < 4; r++)
                c[k][r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
        }
        int n = 0; /* the polygon cut to w >= eps (Sutherland-Hodgman against one plane) */
        for (int k = 0; k < 4; k++) {
            const double *a = c[k], *b = c[(k + 1) & 3];
            double eps = 1e-7 * (fabs(a[0]) + fabs(a[1]) + fabs(b[0]) + fabs(b[1])) + 1e-30;
            if (a[3] >= eps)
                memcpy(in[n++], a, sizeof in[0]);
            if ((a[3] >= eps) != (b[3] >= eps)) {
                double t = (eps - a[3]) / (b[3] - a[3]);
                for (int r = 0; r < 4; r++)
                    in[n][r] = a[r] + t * (b[r] - a[r]);
                n++;
            }
        }
        for (int k = 0; k < n; k++)
            for (int a = 0; a < 2; a++) {
                double v = in[k][a] / in[k][3];
                v = isfinite(v) ? v : (v > 0 ? 2.0 : -2.0);
                ndc[a] = fmin(ndc[a], v);
                ndc[2 + a] = fmax(ndc[2 + a], v);
            }
    }
    for (int a = 0; a < 4; a++)
        ndc[a] = fmin(fmax(ndc[a], -1.0), 1.0);
    cu_ndc_rect_pixels(ndc, w, h, 1, box);
}

/* The grid's cells for this frame (cu_sky_grid_plan), made again only when what they depend on changed: the sky's
 * matrix, the sun, the tables (the sky's coefficients), the viewport and quality.sky_grid (the sun's box follows from
 * those). And for a frame of sky alone (toned) the cells that take the curve at their corners, keyed on the same and
 * the display's exposure and cap, made only when that key is the one the last frame of sky alone asked for: a view,
 * a sun or an exposure that changes every frame takes the curve at every pixel instead of a plan every frame (on
 * llvmpipe one costs more CPU than it saves in the shader, on a GPU the curve costs little); a still one gets it from
 * its second frame on. The two are kept apart, so that frames with and without clouds in turn (a view panning across
 * a cloud's edge) remake neither. */
static void plan(cu_pass_sky *pass, const cu_gpu_scene *ctx, int w, int h, const int sun[4], int toned)
{
    tables_update(pass, ctx->gl, ctx->sky);
    double of[CU_SKY_PLAN_KEY + 4] = {0}, display[4] = {0, 0, 0, cu_out_max(ctx)};
    for (int i = 0; i < 16; i++)
        of[i] = ctx->camera.inv_rot[i];
    of[16] = ctx->sun_dir.x;
    of[17] = ctx->sun_dir.y;
    of[18] = ctx->sun_dir.z;
    of[19] = w;
    of[20] = h;
    of[21] = ctx->scene->sky_grid;
    of[22] = pass->tables_made;
    if (!pass->plan_made || memcmp(of, pass->plan_of, sizeof pass->plan_of)) {
        cu_sky_grid_plan(pass->table, ctx->sun_dir, ctx->camera.inv_rot, w, h, ctx->scene->sky_grid, sun,
                         pass->scale);
        memcpy(pass->plan_of, of, sizeof pass->plan_of);
        pass->plan_made = 1;
        pass->plans++;
    }
    if (!toned) /* toned_now stays 0 (draw clears it) */
        return;
    float os[3];
    cu_out_scale(ctx, os);
    for (int c = 0; c < 3; c++)
        display[c] = os[c];
    memcpy(of + CU_SKY_PLAN_KEY, display, sizeof display);
    int again = pass->toned_asked && !memcmp(of, pass->toned_ask, sizeof pass->toned_ask);
    memcpy(pass->toned_ask, of, sizeof pass->toned_ask);
    pass->toned_asked = 1;
    if (!again)
        return;
    pass->toned_now = 1;
    if (pass->toned_made && !memcmp(of, pass->toned_of, sizeof pass->toned_of))
        return;
    cu_sky_grid_toned(pass->table, ctx->sun_dir, ctx->camera.inv_rot, w, h, ctx->scene->sky_grid, sun, display,
                      pass->toned);
    memcpy(pass->toned_of, of, sizeof pass->toned_of);
    pass->toned_made = 1;
    pass->toned_plans++;
}

static int in_rows(const int box[4], int row)
{
    return row >= box[1] && row < box[3];
}

/* The full-screen triangle, a run of rows at a time with the program of what they hold: sky rows without the
 * ground's shadow maps, ground rows without the Perez tables (a constant sky has no branch), reading only the maps
 * that hold shadows and only where they can show any (shadow_box); with kind CU_SKY_OVER, outside rect (x0, y0, x1,
 * y1: pixels, half-open) without the cloud image (CU_SKY_OUT: the same colours where the image is empty). */
static int draw(cu_pass_sky *pass, const cu_gpu_scene *ctx, int kind, int factor, const int rect[4], cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_CULL_FACE);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_SHADOW);
    gl->BindTexture(GL_TEXTURE_2D, ctx->ground_tau[0]);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_GROUND2);
    gl->BindTexture(GL_TEXTURE_2D, ctx->ground_tau[1]);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_SKY);
    gl->BindTexture(GL_TEXTURE_2D, pass->tables);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindVertexArray(ctx->empty_vao);
    int w = ctx->width, h = ctx->height > 0 ? ctx->height : 1, split = ctx->scene->sky_model != CU_SKY_CONSTANT;
    int maps = ctx->ground_maps >= 0 && ctx->ground_maps <= CU_GROUND_MAPS ? ctx->ground_maps : CU_GROUND_MAPS;
    int x0 = rect[0] < 0 ? 0 : rect[0] > w ? w : rect[0], x1 = rect[2] < x0 ? x0 : rect[2] > w ? w : rect[2];
    const float *m = ctx->camera.inv_rot;
    int rc = 0, part = split ? cu_sky_rows(m, -1.0, -1.0 + 2.0 / h) : CU_SKY_BOTH, sun[4] = {0, 0, 0, 0};
    int shade[4] = {0, 0, 0, 0}, over = kind == CU_SKY_OVER;
    if (ctx->scene->sky_grid > 0 || !split) /* the grid's cells or a flat constant sky need the sun drawn over */
        sun_box(m, ctx->sun_dir, w, h, ctx->scene->sky_grid, sun);
    if (maps > 0)
        shadow_box(ctx, maps, w, h, shade);
    int banded = ctx->scene->sky_grid > 0 && split;
    pass->toned_runs = 0;
    pass->toned_now = 0;
    if (banded)
        plan(pass, ctx, w, h, sun, kind == CU_SKY_ALONE);
    gl->Enable(GL_SCISSOR_TEST);
    for (int row = 0; row < h && !rc;) {
        /* a run: rows holding the same part, all on the same side of the cloud image's rows and the shadows' */
        int in = in_rows(rect, row), dark = in_rows(shade, row), end = row + 1, next = part;
        while (end < h) {
            next = split ? cu_sky_rows(m, -1.0 + 2.0 * end / h, -1.0 + 2.0 * (end + 1) / h) : CU_SKY_BOTH;
            if (next != part || in_rows(rect, end) != in || in_rows(shade, end) != dark ||
                (banded && end % CU_SKY_BAND == 0 && (part == CU_SKY_ABOVE || part == CU_SKY_LOW)))
                break;
            end++;
        }
        /* and in it, columns: the cloud image's with it, the others without; the shadows' with the maps */
        int cut[6] = {0, w, w, w, w, w}, n = 2;
        if (over && in)
            cut[n++] = x0, cut[n++] = x1;
        if (dark && part != CU_SKY_ABOVE && part != CU_SKY_LOW)
            cut[n++] = shade[0], cut[n++] = shade[2];
        for (int i = 1; i < n; i++) /* insertion sort of at most six */
            for (int j = i; j > 0 && cut[j - 1] > cut[j]; j--) {
                int t = cut[j];
                cut[j] = cut[j - 1];
                cut[j - 1] = t;
            }
        for (int i = 0; i + 1 < n && !rc; i++) {
            const int box[4] = {cut[i], row, cut[i + 1], end};
            int image = over && in && box[0] >= x0 && box[2] <= x1;
            int shaded = dark && box[0] >= shade[0] && box[2] <= shade[2] && part != CU_SKY_ABOVE && part != CU_SKY_LOW;
            rc = piece(pass, ctx, over ? (image ? CU_SKY_OVER : CU_SKY_OUT) : kind, part, shaded ? maps : 0, factor,
                       box, sun, err);
        }
        row = end;
        part = next;
    }
    gl->Disable(GL_SCISSOR_TEST);
    return rc;
}

int cu_pass_sky_draw(cu_pass_sky *pass, const cu_gpu_scene *ctx, int to_output, cu_error *err)
{
    static const int everywhere[4] = {0, 0, 1 << 30, 1 << 30};
    return draw(pass, ctx, to_output ? CU_SKY_ALONE : CU_SKY_HDR, 1, everywhere, err);
}

int cu_pass_sky_draw_over(cu_pass_sky *pass, const cu_gpu_scene *ctx, GLuint clouds, GLuint refined, int factor,
                          const int rect[4], cu_error *err)
{
    const cu_gl *gl = ctx->gl;
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_CLOUDS);
    gl->BindTexture(GL_TEXTURE_2D, clouds);
    gl->ActiveTexture(GL_TEXTURE0 + CU_UNIT_REFINED);
    gl->BindTexture(GL_TEXTURE_2D, refined);
    gl->ActiveTexture(GL_TEXTURE0);
    pass->refined = refined != 0;
    int rc = draw(pass, ctx, CU_SKY_OVER, factor, rect, err);
    pass->refined = 0;
    return rc;
}
