/* src/gpu/camera.c: the frame's camera from view and projection matrices (see camera.h). The projection's x, y and
 * w rows shape the rays; its depth row is replaced by planes around the clouds' bounds, so the hull pre-pass keeps
 * its depth precision whatever the host's near and far (0.01 m to 1e7 m, infinite, reversed). */
#include "camera.h"
#include "error.h"

mat4 cu_camera_mat4(const float *m)
{
    mat4 r;
    for (int i = 0; i < 16; i++)
        r.m[i] = m[i];
    return r;
}

static mat4 translate(vec3 t)
{
    mat4 r = m4_identity();
    r.m[12] = t.x;
    r.m[13] = t.y;
    r.m[14] = t.z;
    return r;
}

static vec3 apply_point(mat4 m, vec3 p)
{
    double w = m.m[3] * p.x + m.m[7] * p.y + m.m[11] * p.z + m.m[15];
    return v3_scale(v3(m.m[0] * p.x + m.m[4] * p.y + m.m[8] * p.z + m.m[12],
                       m.m[1] * p.x + m.m[5] * p.y + m.m[9] * p.z + m.m[13],
                       m.m[2] * p.x + m.m[6] * p.y + m.m[10] * p.z + m.m[14]), 1.0 / w);
}

/* The depth row for eye distances u = -z_eye in [n, f] mapped to clip z in [-w, w]. With w = k u (perspective,
 * k = -m[11]): z = A z_e + B, A = -k (f + n) / (f - n), B = -2 k n f / (f - n). With w = s (orthographic,
 * s = m[15]): A = -2 s / (f - n), B = -s (f + n) / (f - n). */
static mat4 with_depth_row(mat4 p, int ortho, double n, double f)
{
    p.m[2] = p.m[6] = 0.0;
    if (ortho) {
        double s = p.m[15];
        p.m[10] = -2.0 * s / (f - n);
        p.m[14] = -s * (f + n) / (f - n);
    } else {
        double k = -p.m[11];
        p.m[10] = -k * (f + n) / (f - n);
        p.m[14] = -2.0 * k * n * f / (f - n);
    }
    return p;
}

static double det3(mat4 m)
{
    return m.m[0] * (m.m[5] * m.m[10] - m.m[9] * m.m[6]) - m.m[4] * (m.m[1] * m.m[10] - m.m[9] * m.m[2]) +
           m.m[8] * (m.m[1] * m.m[6] - m.m[5] * m.m[2]);
}

/* A sphere's extent on screen along one axis (a: its centre's eye coordinate on that axis, d: its depth in front
 * of the eye, r: its radius; NDC = k a / depth - kz): the two tangents from the eye in the plane of that axis and
 * the view direction, the centre's direction turned by +- asin(r / |centre|). 1 when the eye is inside or a tangent
 * does not point ahead (the image reaches the screen's edge). */
static int sphere_extent(double a, double d, double r, double k, double kz, double *lo, double *hi)
{
    double l2 = a * a + d * d, t2 = l2 - r * r;
    if (!(t2 > 0))
        return 1;
    double l = sqrt(l2), c = sqrt(t2) / l, s = r / l;
    double a1 = c * a - s * d, d1 = s * a + c * d, a2 = c * a + s * d, d2 = c * d - s * a;
    if (!(d1 > 1e-9 * l && d2 > 1e-9 * l))
        return 1;
    double n1 = k * a1 / d1 - kz, n2 = k * a2 / d2 - kz;
    *lo = fmin(n1, n2);
    *hi = fmax(n1, n2);
    return 0;
}

/* The extent on screen (NDC x0, y0, x1, y1) of the box lo .. hi through m (the box's frame -> clip): its eight
 * corners bound its image once all lie in front of the eye (w > 0); 1 when one does not (the image is unbounded). */
static int box_rect(mat4 m, vec3 lo, vec3 hi, double rect[4])
{
    rect[0] = rect[1] = 1;
    rect[2] = rect[3] = -1;
    for (int q = 0; q < 8; q++) {
        vec3 p = v3(q & 1 ? hi.x : lo.x, q & 2 ? hi.y : lo.y, q & 4 ? hi.z : lo.z);
        double clip[4];
        for (int row = 0; row < 4; row++)
            clip[row] = m.m[row] * p.x + m.m[4 + row] * p.y + m.m[8 + row] * p.z + m.m[12 + row];
        if (!(clip[3] > 1e-9 * (fabs(clip[0]) + fabs(clip[1]) + 1e-30)))
            return 1;
        for (int a = 0; a < 2; a++) {
            rect[a] = fmin(rect[a], clip[a] / clip[3]);
            rect[2 + a] = fmax(rect[2 + a], clip[a] / clip[3]);
        }
    }
    return 0;
}

int cu_camera_build(cu_camera *c, mat4 view, mat4 proj, vec3 origin, double hull_r, cu_error *err)
{
    for (int i = 0; i < 16; i++)
        if (!isfinite(view.m[i]) || !isfinite(proj.m[i]))
            return cu_fail(err, "camera: the %s matrix has a non-finite element %d",
                           isfinite(view.m[i]) ? "projection" : "view", i);
    /* The bottom row decides the kind: w = -c z_eye (perspective) or w = c (orthographic). */
    const double *pm = proj.m;
    int persp = pm[3] == 0 && pm[7] == 0 && pm[15] == 0 && pm[11] < 0;
    int ortho = pm[3] == 0 && pm[7] == 0 && pm[11] == 0 && pm[15] > 0;
    if (!persp && !ortho)
        return cu_fail(err, "camera: the projection's bottom row is (%.9g, %.9g, %.9g, %.9g); cumulo takes a "
                            "perspective (0, 0, -c, 0) or orthographic (0, 0, 0, c) projection, c > 0",
                       pm[3], pm[7], pm[11], pm[15]);
    if (view.m[3] != 0 || view.m[7] != 0 || view.m[11] != 0 || view.m[15] != 1 || fabs(det3(view)) < 1e-12)
        return cu_fail(err, "camera: the view matrix must be affine (bottom row 0, 0, 0, 1) and invertible");
    mat4 local = m4_mul(view, translate(origin)); /* cloud-local -> eye */
    mat4 inv_local = m4_inverse(local);
    /* The view may scale: distances in the eye frame are the world's times the largest axis scale. */
    double scale = 0;
    for (int col = 0; col < 3; col++)
        scale = fmax(scale, v3_len(v3(local.m[col * 4], local.m[col * 4 + 1], local.m[col * 4 + 2])));
    double u_c = -local.m[14], r_eye = hull_r * scale; /* the bounds' centre, as an eye distance, and radius */
    double u_lo = u_c - 1.05 * r_eye - 10.0, u_hi = u_c + 1.05 * r_eye + 10.0;
    double n, f;
    c->ortho = ortho;
    c->near_cuts = 0;
    if (ortho) {
        /* The host's near plane, where its clip z is -w: u = (m15 + m14) / m10. */
        double n_host = pm[10] != 0 ? (pm[15] + pm[14]) / pm[10] : -INFINITY;
        c->near_cuts = n_host > u_lo;
        n = fmax(n_host, u_lo);
        f = u_hi;
    } else {
        /* Near as far out as the clouds allow: depth precision ~ u^2 / (near 2^24). */
        n = fmax(0.05, 0.5 * (u_c - r_eye));
        f = u_hi;
    }
    /* Frustum culling: the bounds' sphere wholly outside a side plane of the view (Gribb and Hartmann's planes
     * w +- x >= 0, w +- y >= 0 in clip space, taken to eye space through the projection's rows) cannot change a
     * pixel, so the cloud pass is skipped. */
    vec3 ce = v3(local.m[12], local.m[13], local.m[14]);
    int outside = 0;
    for (int k = 0; k < 4; k++) {
        int row = k / 2;
        double sg = k % 2 ? -1.0 : 1.0;
        vec3 nrm = v3(pm[3] + sg * pm[row], pm[7] + sg * pm[4 + row], pm[11] + sg * pm[8 + row]);
        double d = pm[15] + sg * pm[12 + row];
        if (v3_dot(nrm, ce) + d < -r_eye * 1.05 * v3_len(nrm))
            outside = 1;
    }
    c->visible = f > n && !outside;
    /* Where on screen. A perspective projection without skew: along x and along y, the tangents from the eye to the
     * bounds' sphere (Mara and McGuire 2013); either one behind the eye, or the eye inside: that whole axis. Else
     * (orthographic, skewed) the extent of a box about the sphere, whose eight corners bound its image once all lie
     * in front of the eye. */
    double rect[4] = {1, 1, -1, -1}, rb = 1.05 * r_eye;
    if (persp && pm[1] == 0 && pm[4] == 0 && pm[12] == 0 && pm[13] == 0) {
        double ca[2] = {ce.x, ce.y}, d = -ce.z, p_aa[2] = {pm[0], pm[5]}, p_az[2] = {pm[8], pm[9]};
        for (int a = 0; a < 2; a++)
            if (sphere_extent(ca[a], d, rb, p_aa[a] / -pm[11], p_az[a] / -pm[11], &rect[a], &rect[2 + a])) {
                rect[a] = -1;
                rect[2 + a] = 1;
            }
    } else if (box_rect(proj, v3_sub(ce, v3(rb, rb, rb)), v3_add(ce, v3(rb, rb, rb)), rect)) {
        rect[0] = rect[1] = -1;
        rect[2] = rect[3] = 1;
    }
    for (int a = 0; a < 4; a++)
        c->ndc_rect[a] = fmin(fmax(rect[a], -1.0), 1.0);
    /* How far from the eye the near plane reaches: znear times the distance of its corners, for the hull test. */
    double k = ortho ? 1.0 : -pm[11]; /* w = k u */
    double tx = (fabs(pm[8]) + k) / fabs(pm[0]), ty = (fabs(pm[9]) + k) / fabs(pm[5]);
    c->near_reach = ortho ? 0.0 : sqrt(1.0 + tx * tx + ty * ty);
    if (!c->visible)
        f = n + 1.0;
    c->znear = n;
    c->pos = apply_point(inv_local, v3(0, 0, 0));
    vec3 o = apply_point(inv_local, v3(0, 0, 0)), fwd = apply_point(inv_local, v3(0, 0, -1));
    c->view_dir = v3_norm(v3_sub(fwd, o));
    mat4 vp = m4_mul(with_depth_row(proj, ortho, n, f), local);
    m4_to_float(vp, c->vp);
    /* The camera-inside pass (cloud.frag, FULLSCREEN) unprojects clip z = 1, the far plane, in fp32: through vp its
     * w is a difference of 1/n and 1/f, which cancels to 0 (a NaN direction) once f / n passes 1/eps ~ 1.7e7 (the
     * camera inside a cloud 2e6 m across, n = 0.05). The far plane does not depend on n, so a perspective camera's
     * inverse is taken of the same frustum with n = f / 2: the same rays, no cancellation. An orthographic camera
     * unprojects the near plane (its ray origins) and keeps vp's own inverse. */
    mat4 unproject = ortho ? vp : m4_mul(with_depth_row(proj, ortho, 0.5 * f, f), local);
    m4_to_float(m4_inverse(unproject), c->inv_vp);
    m4_to_float(m4_inverse(m4_mul(proj, local)), c->host_inv_vp);
    /* The sky only needs directions: the rotation alone and fixed planes, so the sky does not depend on where the
     * clouds are (an empty scene is bit-for-bit the sky). */
    mat4 rot = local;
    rot.m[12] = rot.m[13] = rot.m[14] = 0.0;
    mat4 rot_vp = m4_mul(with_depth_row(proj, ortho, 1.0, 2.0), rot);
    m4_to_float(rot_vp, c->rot_vp);
    m4_to_float(m4_inverse(rot_vp), c->inv_rot);
    return 0;
}

void cu_camera_clip_rect(cu_camera *c, mat4 view, mat4 proj, vec3 origin, vec3 lo, vec3 hi)
{
    double rect[4];
    if (box_rect(m4_mul(proj, m4_mul(view, translate(origin))), lo, hi, rect))
        return; /* a corner behind the eye: the box's image is unbounded */
    for (int a = 0; a < 2; a++) {
        c->ndc_rect[a] = fmax(c->ndc_rect[a], rect[a]);
        c->ndc_rect[2 + a] = fmin(c->ndc_rect[2 + a], rect[2 + a]);
    }
}

void cu_ndc_rect_pixels(const double ndc[4], int width, int height, int grow, int px[4])
{
    int size[2] = {width, height};
    for (int a = 0; a < 2; a++) {
        double lo = floor(0.5 * (ndc[a] + 1.0) * size[a]) - grow, hi = ceil(0.5 * (ndc[2 + a] + 1.0) * size[a]) + grow;
        px[a] = (int)fmin(fmax(lo, 0.0), (double)size[a]);
        px[2 + a] = (int)fmin(fmax(hi, (double)px[a]), (double)size[a]);
    }
}
