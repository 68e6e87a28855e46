/* tools/mie/mietable_out.c: integrals of tabulated phase functions over the sphere, the chopped forward peak
 * (Kol 3.64-3.69), and the table file data/mie_cloud.tbl with its header. */
#include "mietable.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* ---- integrals and the chop ---------------------------------------------------------------------------------- */

double mt_sphere_integral(const double *theta_deg, const double *v, int n, int cosw)
{
    double total = 0.0;
    int i = 0;
    while (i < n - 1) {
        /* Longest run of equal steps starting at i. */
        double h = theta_deg[i + 1] - theta_deg[i];
        int j = i + 1;
        while (j < n - 1 && fabs((theta_deg[j + 1] - theta_deg[j]) - h) < 1e-9 * (1.0 + fabs(h)))
            j++;
        int m = j - i; /* intervals in the run */
        double hr = h * PI / 180.0;
        double f[4];
#define F(k)                                                                                                         \
    (v[k] * (cosw ? cos(theta_deg[k] * PI / 180.0) : 1.0) * sin(theta_deg[k] * PI / 180.0) * 2.0 * PI)
        int simp_end = (m % 2 == 0) ? j : j - 3;
        if (m == 1) {
            total += 0.5 * hr * (F(i) + F(j));
        } else {
            for (int k = i; k + 2 <= simp_end; k += 2)
                total += hr / 3.0 * (F(k) + 4.0 * F(k + 1) + F(k + 2));
            if (simp_end != j) { /* Simpson's 3/8 rule on the last three intervals of an odd run */
                for (int q = 0; q < 4; q++)
                    f[q] = F(simp_end + q);
                total += 3.0 * hr / 8.0 * (f[0] + 3.0 * f[1] + 3.0 * f[2] + f[3]);
            }
        }
#undef F
        i = j;
    }
    return total;
}

int mt_chop(const double *theta_deg, const double *p, int n, double chop_deg, double *f, double *ptilde)
{
    int ic = -1;
    for (int i = 0; i < n; i++)
        if (fabs(theta_deg[i] - chop_deg) < 1e-9)
            ic = i;
    if (ic < 0)
        return -1;
    double *pp = malloc((size_t)(ic + 1) * sizeof *pp);
    if (!pp)
        return -1;
    for (int i = 0; i < n; i++) {
        double pt = i < ic ? p[ic] : p[i];
        if (ptilde)
            ptilde[i] = pt;
        if (i <= ic)
            pp[i] = p[i] - pt;
    }
    /* P_p is zero from the chop angle on; integrating only [0, chop] keeps its kink at a run boundary. */
    *f = mt_sphere_integral(theta_deg, pp, ic + 1, 0);
    free(pp);
    return 0;
}

/* ---- output -------------------------------------------------------------------------------------------------- */

int mt_write_table(FILE *out, const mt_result *r, const double *theta_deg, const char *command, const mt_params *p)
{
    if (r->nchan != 3)
        return -1;
    double f[3];
    for (int c = 0; c < 3; c++)
        if (mt_chop(theta_deg, r->p[c], r->nang, 8.0, &f[c], NULL) != 0)
            return -1;
    fprintf(out, "# cumulo mie table v1\n");
    fprintf(out, "# command: %s\n", command);
    if (p->monodisperse)
        fprintf(out, "# droplets: monodisperse r = %g um\n", p->radius_um);
    else
        fprintf(out, "# droplets: gamma distribution r_eff = %g um, v_eff = %g; radius step dx = %g in size "
                     "parameter, x%g past r^4 n(r) < 1e-2 of peak, golden-ratio grid offset per wavelength\n",
                p->reff_um, p->veff, p->dx, p->tail_stretch);
    if (p->poles && !p->monodisperse)
        fprintf(out, "# resonances: trapezoid error subtracted at %ld poles of a_n, b_n within 3 steps of the real "
                     "size-parameter axis (tools/mie/resonance.h)\n",
                r->npoles);
    fprintf(out, "# spectrum: %g-%g nm, nodes every %g nm, equal-energy; cubic product integration against "
                 "linear-sRGB weights from the Wyman-Sloan-Shirley CIE fit (negative lobes clipped)\n",
            p->lambda_min_nm, p->lambda_max_nm, p->dlambda_nm);
    if (p->use_m)
        fprintf(out, "# refractive index: %.6f - %.3ei (fixed)\n", creal(p->m), -cimag(p->m));
    else
        fprintf(out, "# refractive index: water, Daimon-Masumura 2007 (20 degC) n, Hale-Querry 1973 k\n");
    fprintf(out, "# P(theta) in sr^-1 with integral over the sphere = 1 (composite Simpson on the equal-step runs);"
                 " sigma_ext in um^2 per droplet\n");
    fprintf(out, "# angles: 0.05 deg steps on [0, 10] and [170, 180], 0.25 deg on [10, 170]; g from the Mie "
                 "coefficients; f = integral of P_p = P - P~, P~ = P(8 deg) below 8 deg\n");
    fprintf(out, "# Mie evaluations: %ld (grid nodes and poles)\n", r->nsolves);
    /* No run time or date in the file: it must regenerate byte for byte (the time goes to stderr). */
    fprintf(out, "channels 3\n");
    fprintf(out, "lambda_nm %.2f %.2f %.2f\n", r->lambda_nm[0], r->lambda_nm[1], r->lambda_nm[2]);
    fprintf(out, "sigma_ext_um2 %.7e %.7e %.7e\n", r->sigma_ext[0], r->sigma_ext[1], r->sigma_ext[2]);
    fprintf(out, "g %.7e %.7e %.7e\n", r->g[0], r->g[1], r->g[2]);
    fprintf(out, "chop_deg 8\n");
    fprintf(out, "f %.7e %.7e %.7e\n", f[0], f[1], f[2]);
    fprintf(out, "angles %d\n", r->nang);
    for (int i = 0; i < r->nang; i++)
        fprintf(out, "%.2f %.7e %.7e %.7e\n", theta_deg[i], r->p[0][i], r->p[1][i], r->p[2][i]);
    return ferror(out) ? -1 : 0;
}
