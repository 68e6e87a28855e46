/* tools/slab/slab.c: Monte Carlo slab transport core: photon walk, order groups, estimators, threads (phase functions
 * in slab_phase.c). */
#include "slab.h"
#include "rng.h"
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <gsl/gsl_sf_expint.h>
#ifdef CU_SLAB_MPI
#include <mpi.h>
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

int cu_slab_group(int k)
{
    if (k <= 4) return k - 1;
    if (k <= 6) return 4;
    if (k <= 9) return 5;
    if (k <= 15) return 6;
    return 7;
}

const char *cu_slab_group_name(int g)
{
    static const char *names[CU_NGROUP] = { "1", "2", "3", "4", "5-6", "7-9", "10-15", "16+" };
    return (g >= 0 && g < CU_NGROUP) ? names[g] : "?";
}

/* ---------------------------------------------------------------- phase functions */
/* ---------------------------------------------------------------- statistics */

void cu_acc_stats(const cu_acc *a, long long n, double *mean, double *se)
{
    double m = n > 0 ? a->s / n : 0;
    double var = n > 1 ? (a->s2 / n - m * m) * n / (n - 1) : 0;
    if (var < 0) var = 0;
    *mean = m;
    *se = n > 0 ? sqrt(var / n) : 0;
}

int cu_slab_ncell(const cu_slab_cfg *c)
{
    return c->table ? CU_NGROUP * c->nd * c->nv * c->nphi : 0;
}

int cu_slab_cell(const cu_slab_cfg *c, int grp, int id, int iv, int ip)
{
    return ((grp * c->nd + id) * c->nv + iv) * c->nphi + ip;
}

/* ---------------------------------------------------------------- photon walk */

#define NAZ 8          /* stratified azimuths for the azimuth-averaged local estimate */
#define MU_GRAZE 0.05  /* below this outgoing cosine the point estimator is replaced by the band estimator */
#define BAND_HALF 0.025
#define LMAX 40.0      /* contributions below exp(-40) are skipped */

typedef struct {
    cu_acc R, T, Rn[CU_NGROUP], Tn[CU_NGROUP], Re, Te, Ren[CU_NGROUP], Ten[CU_NGROUP], RTe;
    cu_acc rad_r[CU_MAXMU], rad_t[CU_MAXMU], rad_rn[CU_MAXMU][CU_NGROUP], rad_tn[CU_MAXMU][CU_NGROUP];
    double collisions;      /* double so that the whole struct can be summed as MPI_DOUBLE */
} batch_acc;

typedef struct {
    const cu_slab_cfg *cfg;
    batch_acc *acc;         /* [nbatch] */
    double *tab;            /* [nbatch][ncell][4] */
    int ncell;
    cu_rng *streams;        /* [nbatch] */
    int next, done;
    pthread_mutex_t lock;
    pthread_cond_t cond;    /* signalled when a batch completes (wakes the progress loop) */
    /* precomputed table directions */
    double (*dirv)[3];      /* [nv*nphi] outgoing direction (x, z, w-down) */
} shared_t;

/* Weight of a collision at optical distance z (measured along the normal) from the exit plane, for outgoing cosine
 * mu: the point estimator e^{-z/mu}/mu, whose second moment per collision is ~ c(0)/(2 mu) and so diverges at grazing
 * exit. Below MU_GRAZE we use the exact average of that kernel over the cosine band [mu-h, mu+h] (clipped at 0),
 * (E1(z/hi) - E1(z/lo))/(hi-lo), which behaves like -ln z near the boundary and has finite variance at the price of
 * smoothing the radiance over a band of width 2h (documented in README). */
static double exit_kernel(double z, double mu)
{
    if (mu >= MU_GRAZE) {
        double L = z / mu;
        return L > LMAX ? 0.0 : exp(-L) / mu;
    }
    double lo = mu - BAND_HALF, hi = mu + BAND_HALF;
    if (lo < 0) lo = 0;
    if (z / hi > LMAX) return 0.0;
    double e_hi = gsl_sf_expint_E1(z / hi);
    double e_lo = (lo > 0 && z / lo < 700) ? gsl_sf_expint_E1(z / lo) : 0.0;
    if (z <= 0) return 0.0;
    return (e_hi - e_lo) / (hi - lo);
}

static void rotate(double *ux, double *uy, double *uz, double cost, double phi)
{
    double sint = sqrt(fmax(0.0, 1.0 - cost * cost));
    double cp = cos(phi), sp = sin(phi);
    double x = *ux, y = *uy, z = *uz;
    if (fabs(z) > 0.99999) {
        *ux = sint * cp; *uy = sint * sp; *uz = (z > 0 ? 1.0 : -1.0) * cost;
    } else {
        double t = sqrt(1.0 - z * z);
        *ux = sint * (x * z * cp - y * sp) / t + x * cost;
        *uy = sint * (y * z * cp + x * sp) / t + y * cost;
        *uz = -sint * cp * t + z * cost;
    }
    double n = sqrt(*ux * *ux + *uy * *uy + *uz * *uz);
    *ux /= n; *uy /= n; *uz /= n;
}

static void run_batch(shared_t *sh, int b)
{
    const cu_slab_cfg *c = sh->cfg;
    batch_acc *A = &sh->acc[b];
    double *tab = sh->tab ? sh->tab + (size_t)b * sh->ncell * 4 : NULL;
    cu_rng rng = sh->streams[b];
    long long n0 = c->photons * b / c->nbatch, n1 = c->photons * (b + 1) / c->nbatch;
    const double tau = c->tau, mu0 = c->mu0;
    const double t0 = exp(-tau / mu0), w0 = 1.0 - t0;
    const double s0 = sqrt(fmax(0.0, 1.0 - mu0 * mu0));
    const int nmu = c->nmu;
    double pr[CU_NGROUP], pt[CU_NGROUP];
    double rr[CU_MAXMU][CU_NGROUP], rt[CU_MAXMU][CU_NGROUP];
    const int ndir = c->table ? c->nv * c->nphi : 0;
    for (long long ip = n0; ip < n1; ip++) {
        memset(pr, 0, sizeof pr); memset(pt, 0, sizeof pt);
        memset(rr, 0, sizeof rr); memset(rt, 0, sizeof rt);
        /* sun propagates along -z horizontally (Bouthors' phi_V = 0 is the forward azimuth) and down into the slab */
        double dx = 0, dz = -s0, dw = mu0, px = 0, pz = 0;
        /* forced first collision: depth drawn from the exponential truncated to the slab, weight 1 - e^{-tau/mu0};
         * the unscattered beam e^{-tau/mu0} is added exactly */
        double s = -log(1.0 - w0 * cu_rng_u01(&rng));
        double z = s * mu0;
        if (z >= tau) z = tau * 0.999999999;
        px += s * dx; pz += s * dz;
        double w = w0;
        int k = 0;
        for (;;) {
            k++;
            A->collisions++;
            int grp = cu_slab_group(k);
            /* local estimates toward the requested exit cosines (uses the incoming direction) */
            if (nmu) {
                double off = cu_rng_u01(&rng);
                for (int j = 0; j < nmu; j++) {
                    double mu = c->mu[j], sm = sqrt(fmax(0.0, 1.0 - mu * mu));
                    double kr = exit_kernel(z, mu), kt = exit_kernel(tau - z, mu);
                    if (kr == 0 && kt == 0) continue;
                    double ar = 0, at = 0;
                    for (int a = 0; a < (c->phi_deg >= 0 ? 1 : NAZ); a++) {
                        double phi = c->phi_deg >= 0 ? c->phi_deg * M_PI / 180.0 : 2.0 * M_PI * (a + off) / NAZ;
                        double ox = sm * sin(phi), oz = -sm * cos(phi);
                        double hz = dx * ox + dz * oz;
                        if (kr > 0) ar += cu_phase_eval(c->ph, hz - dw * mu);
                        if (kt > 0) at += cu_phase_eval(c->ph, hz + dw * mu);
                    }
                    int na = c->phi_deg >= 0 ? 1 : NAZ;
                    rr[j][grp] += w * M_PI * kr * ar / na;
                    rt[j][grp] += w * M_PI * kt * at / na;
                }
            }
            if (ndir) {
                for (int q = 0; q < ndir; q++) {
                    const double *o = sh->dirv[q];
                    double wv = o[2];
                    if (fabs(wv) < 1e-9) continue;
                    double p = -1;
                    int iv = q / c->nphi, iph = q % c->nphi;
                    for (int jd = 0; jd < c->nd; jd++) {
                        double d = c->d_tau[jd];
                        double L = (d - z) / wv;   /* optical path from the collision to the viewpoint along s_V */
                        if (L <= 0 || L > LMAX) continue;
                        if (p < 0) p = cu_phase_eval(c->ph, dx * o[0] + dz * o[1] + dw * wv);
                        /* C = I / F_sun: a photon carries unit horizontal flux, so F_sun = 1/mu0 */
                        double val = w * mu0 * p * exp(-L) / fabs(wv);
                        double xp = -(px + L * o[0]), zp = -(pz + L * o[1]);
                        double *cell = tab + (size_t)cu_slab_cell(c, grp, jd, iv, iph) * 4;
                        cell[0] += val; cell[1] += val * xp; cell[2] += val * zp; cell[3] += val * (xp * xp + zp * zp);
                    }
                }
            }
            /* new direction */
            double ct = cu_phase_sample(c->ph, cu_rng_u01(&rng));
            rotate(&dx, &dz, &dw, ct, 2.0 * M_PI * cu_rng_u01(&rng));
            /* escape-probability estimator: the conditional expectation of "leaves after this scattering" */
            if (dw < 0) { double L = z / -dw; if (L < LMAX) pr[grp] += w * exp(-L); }
            else if (dw > 0) { double L = (tau - z) / dw; if (L < LMAX) pt[grp] += w * exp(-L); }
            if (c->max_order && k >= c->max_order) break;
            s = -log(cu_rng_u01_open0(&rng));
            z += s * dw; px += s * dx; pz += s * dz;
            if (z < 0 || z > tau) {
                /* analog exit count: per-photon score is w or 0, so its variance is w^2 R(1-R) at most */
                cu_acc *e = z < 0 ? &A->R : &A->T, *eg = z < 0 ? &A->Rn[grp] : &A->Tn[grp];
                e->s += w; e->s2 += w * w; eg->s += w; eg->s2 += w * w;
                break;
            }
        }
        double sr = 0, st = 0;
        for (int g = 0; g < CU_NGROUP; g++) {
            sr += pr[g]; st += pt[g];
            A->Ren[g].s += pr[g]; A->Ren[g].s2 += pr[g] * pr[g];
            A->Ten[g].s += pt[g]; A->Ten[g].s2 += pt[g] * pt[g];
        }
        A->Re.s += sr; A->Re.s2 += sr * sr;
        A->Te.s += st; A->Te.s2 += st * st;
        A->RTe.s += sr + st; A->RTe.s2 += (sr + st) * (sr + st);
        for (int j = 0; j < nmu; j++) {
            double a = 0, bb = 0;
            for (int g = 0; g < CU_NGROUP; g++) {
                a += rr[j][g]; bb += rt[j][g];
                A->rad_rn[j][g].s += rr[j][g]; A->rad_rn[j][g].s2 += rr[j][g] * rr[j][g];
                A->rad_tn[j][g].s += rt[j][g]; A->rad_tn[j][g].s2 += rt[j][g] * rt[j][g];
            }
            A->rad_r[j].s += a; A->rad_r[j].s2 += a * a;
            A->rad_t[j].s += bb; A->rad_t[j].s2 += bb * bb;
        }
    }
}

static void *worker(void *arg)
{
    shared_t *sh = arg;
    for (;;) {
        pthread_mutex_lock(&sh->lock);
        int b = sh->next;
        /* MPI ranks own batches b with b % nranks == rank */
        while (b < sh->cfg->nbatch && b % sh->cfg->nranks != sh->cfg->rank) b++;
        sh->next = b + 1;
        pthread_mutex_unlock(&sh->lock);
        if (b >= sh->cfg->nbatch) break;
        run_batch(sh, b);
        pthread_mutex_lock(&sh->lock);
        sh->done++;
        pthread_cond_signal(&sh->cond);
        pthread_mutex_unlock(&sh->lock);
    }
    return NULL;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void add_acc(cu_acc *d, const cu_acc *s) { d->s += s->s; d->s2 += s->s2; }

int cu_slab_run(const cu_slab_cfg *cfg, cu_slab_result *res)
{
    memset(res, 0, sizeof *res);
    int nb = cfg->nbatch, nr = cfg->nranks > 0 ? cfg->nranks : 1;
    cu_slab_cfg c = *cfg;
    c.nranks = nr;
    shared_t sh;
    memset(&sh, 0, sizeof sh);
    sh.cfg = &c;
    sh.ncell = cu_slab_ncell(&c);
    sh.acc = calloc(nb, sizeof *sh.acc);
    sh.streams = malloc(sizeof(cu_rng) * nb);
    if (sh.ncell) {
        sh.tab = calloc((size_t)nb * sh.ncell * 4, sizeof(double));
        sh.dirv = malloc(sizeof(double[3]) * c.nv * c.nphi);
    }
    if (!sh.acc || !sh.streams || (sh.ncell && (!sh.tab || !sh.dirv))) {
        free(sh.acc); free(sh.streams); free(sh.tab); free(sh.dirv);
        return -1;
    }
    for (int iv = 0; sh.ncell && iv < c.nv; iv++)
        for (int ip = 0; ip < c.nphi; ip++) {
            /* s_V in Bouthors' angles: theta_V from -y (down), phi_V from -z; internal (x, z, downward cosine) */
            double tv = c.thv_deg[iv] * M_PI / 180.0, pv = c.phv_deg[ip] * M_PI / 180.0;
            double *o = sh.dirv[iv * c.nphi + ip];
            o[0] = sin(tv) * sin(pv); o[1] = -sin(tv) * cos(pv); o[2] = cos(tv);
        }
    cu_rng base;
    cu_rng_seed(&base, cfg->seed);
    for (int b = 0; b < nb; b++) { sh.streams[b] = base; cu_rng_jump(&base); }
    pthread_mutex_init(&sh.lock, NULL);
    pthread_cond_init(&sh.cond, NULL);
    int nt = cfg->threads < 1 ? 1 : cfg->threads;
    pthread_t *th = malloc(sizeof(pthread_t) * nt);
    double t_start = now_s();
    int started = 0;
    for (int i = 0; i < nt; i++)
        if (pthread_create(&th[i], NULL, worker, &sh) == 0) started++;
    if (started == 0) worker(&sh);
    int mine = 0;
    for (int b = 0; b < nb; b++) if (b % nr == c.rank) mine++;
    int shown = 0, tty = isatty(2);
    double last_print = 0;
    for (;;) {
        pthread_mutex_lock(&sh.lock);
        if (sh.done < mine) {
            struct timespec ts;
            clock_gettime(CLOCK_REALTIME, &ts);
            ts.tv_nsec += 250000000L;
            if (ts.tv_nsec >= 1000000000L) { ts.tv_sec++; ts.tv_nsec -= 1000000000L; }
            pthread_cond_timedwait(&sh.cond, &sh.lock, &ts);
        }
        int d = sh.done;
        pthread_mutex_unlock(&sh.lock);
        double el = now_s() - t_start;
        if (!cfg->quiet && el > 1.0 && d > 0 && d < mine && (tty || el - last_print > 10.0)) {
            last_print = el;
            /* progress bar with ETA from the completed fraction of fixed-size batches */
            double fr = (double)d / mine, eta = el * (1.0 - fr) / fr;
            int bar = (int)(30 * fr);
            fprintf(stderr, "%s[%.*s%*s] %3.0f%% %6.1fs elapsed, ETA %6.1fs%s", tty ? "\r" : "", bar,
                    "##############################", 30 - bar, "", 100 * fr, el, eta, tty ? "" : "\n");
            shown = 1;
        }
        if (d >= mine) break;
    }
    if (shown && tty) fprintf(stderr, "\n");
    for (int i = 0; i < started; i++) pthread_join(th[i], NULL);
    free(th);
    pthread_mutex_destroy(&sh.lock);
    pthread_cond_destroy(&sh.cond);
    res->seconds = now_s() - t_start;
#ifdef CU_SLAB_MPI
    /* every batch was run by exactly one rank and is zero elsewhere, so an element-wise sum reproduces the
     * single-process per-batch arrays bit for bit; the ordered reduction below then gives identical results */
    if (nr > 1) {
        MPI_Allreduce(MPI_IN_PLACE, sh.acc, (int)(nb * (sizeof(batch_acc) / sizeof(double))), MPI_DOUBLE, MPI_SUM,
                      MPI_COMM_WORLD);
        if (sh.tab)
            MPI_Allreduce(MPI_IN_PLACE, sh.tab, nb * sh.ncell * 4, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    }
#endif
    /* reduce in batch order: identical bits for any thread count */
    for (int b = 0; b < nb; b++) {
        batch_acc *a = &sh.acc[b];
        add_acc(&res->R, &a->R); add_acc(&res->T, &a->T);
        add_acc(&res->Re, &a->Re); add_acc(&res->Te, &a->Te); add_acc(&res->RTe, &a->RTe);
        for (int g = 0; g < CU_NGROUP; g++) {
            add_acc(&res->Rn[g], &a->Rn[g]); add_acc(&res->Tn[g], &a->Tn[g]);
            add_acc(&res->Ren[g], &a->Ren[g]); add_acc(&res->Ten[g], &a->Ten[g]);
        }
        for (int j = 0; j < c.nmu; j++) {
            add_acc(&res->rad_r[j], &a->rad_r[j]); add_acc(&res->rad_t[j], &a->rad_t[j]);
            for (int g = 0; g < CU_NGROUP; g++) { add_acc(&res->rad_rn[j][g], &a->rad_rn[j][g]); add_acc(&res->rad_tn[j][g], &a->rad_tn[j][g]); }
        }
        res->collisions += (long long)a->collisions;
    }
    res->photons = cfg->photons;
    res->t_unscat = exp(-cfg->tau / cfg->mu0);
    res->ncell = sh.ncell;
    res->tab = sh.tab;
    free(sh.acc); free(sh.streams); free(sh.dirv);
    return 0;
}

void cu_slab_result_free(cu_slab_result *res)
{
    free(res->tab);
    res->tab = NULL;
}

void cu_slab_cell_stats(const cu_slab_cfg *cfg, const cu_slab_result *res, int cell, cu_cell_stats *st)
{
    /* batch means: each batch gives C_b and the ratio estimates of the collector moments; SE = sd/sqrt(nb) */
    int nb = cfg->nbatch;
    double sc = cfg->metres_per_tau > 0 ? cfg->metres_per_tau : 1.0;
    double sC = 0, sC2 = 0, sx = 0, sx2 = 0, sz = 0, sz2 = 0, ss = 0, ss2 = 0;
    double T0 = 0, T1 = 0, T2 = 0, T3 = 0;
    int nvalid = 0;
    for (int b = 0; b < nb; b++) {
        const double *v = res->tab + ((size_t)b * res->ncell + cell) * 4;
        long long nph = cfg->photons * (b + 1) / nb - cfg->photons * b / nb;
        double Cb = nph > 0 ? v[0] / nph : 0;
        sC += Cb; sC2 += Cb * Cb;
        T0 += v[0]; T1 += v[1]; T2 += v[2]; T3 += v[3];
        if (v[0] > 0) {
            double cx = v[1] / v[0], cz = v[2] / v[0];
            double var = v[3] / v[0] - cx * cx - cz * cz;
            double sg = sqrt(fmax(0.0, var / 2.0));
            sx += cx; sx2 += cx * cx; sz += cz; sz2 += cz * cz; ss += sg; ss2 += sg * sg;
            nvalid++;
        }
    }
    double m = sC / nb;
    st->C = T0 / cfg->photons;
    st->C_se = nb > 1 ? sqrt(fmax(0.0, (sC2 / nb - m * m) / (nb - 1))) : 0;
    if (T0 > 0) {
        double cx = T1 / T0, cz = T2 / T0;
        st->cx = cx * sc; st->cz = cz * sc;
        st->sigma = sqrt(fmax(0.0, (T3 / T0 - cx * cx - cz * cz) / 2.0)) * sc;
    } else st->cx = st->cz = st->sigma = 0;
    if (nvalid > 1) {
        double a = sx / nvalid, bz = sz / nvalid, cs = ss / nvalid;
        st->cx_se = sqrt(fmax(0.0, (sx2 / nvalid - a * a) / (nvalid - 1))) * sc;
        st->cz_se = sqrt(fmax(0.0, (sz2 / nvalid - bz * bz) / (nvalid - 1))) * sc;
        st->sigma_se = sqrt(fmax(0.0, (ss2 / nvalid - cs * cs) / (nvalid - 1))) * sc;
    } else st->cx_se = st->cz_se = st->sigma_se = 0;
}
