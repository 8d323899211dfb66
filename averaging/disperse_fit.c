/* The tables of mimas disperse and their fits of D: MSD = 2 d D t + c and
 * sigma^2 = 2 d D t + c by least squares (averaging/fit.h), the Green-Kubo
 * D = (1/d) int_0^t C(t') dt' of the velocity autocorrelation averaged over
 * the window; d the dimensions of the component.  D_err is the jackknife
 * over groups of particles (Efron 1982): with D_(g) the estimate without
 * group g, D_err^2 = (G-1)/G sum_g (D_(g) - mean)^2, an error that counts
 * the particles as the independent samples they are, where the
 * least-squares error of strongly correlated points (D_err_fit) does not. */
#include <config.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "disperse_impl.h"

#define NC MIMAS_DC_COUNT

int disperse_push_diffusion(mimas_disperse_result *r, const mimas_disperse_diffusion *row,
                            mimas_error *err)
{
    mimas_disperse_diffusion *d = realloc(r->diffusion, (r->ndiffusion + 1) * sizeof *d);
    if (!d)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    d[r->ndiffusion++] = *row;
    r->diffusion = d;
    return MIMAS_OK;
}

/* The points of one fit: abscissa and ordinate, at most n. */
typedef struct points {
    double *x, *y;
    size_t n;
} points;

static int points_alloc(points *p, size_t n, mimas_error *err)
{
    p->n = 0;
    p->x = malloc((n ? n : 1) * sizeof *p->x);
    p->y = malloc((n ? n : 1) * sizeof *p->y);
    if (!p->x || !p->y)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    return MIMAS_OK;
}

static void points_free(points *p)
{
    free(p->x);
    free(p->y);
}

/* A line through the points: D = slope / (2 d), its least-squares error,
 * the abscissa range of the valid points. */
static int line_D(const points *p, int dim, mimas_disperse_diffusion *row, mimas_error *err)
{
    mimas_fit f;
    int rc = mimas_fit_line(p->x, p->y, NULL, p->n, 3, &f, err);
    if (rc)
        return rc;
    row->D = f.p[1] / (2.0 * dim);
    row->D_err_fit = f.err[1] / (2.0 * dim);
    row->intercept = f.p[0];
    row->npts = f.npts;
    row->status = f.status;
    row->t0 = row->t1 = NAN;
    for (size_t i = 0; i < p->n; i++)
        if (isfinite(p->x[i]) && isfinite(p->y[i])) {
            row->t0 = isnan(row->t0) ? p->x[i] : fmin(row->t0, p->x[i]);
            row->t1 = isnan(row->t1) ? p->x[i] : fmax(row->t1, p->x[i]);
        }
    return MIMAS_OK;
}

/* The jackknife error from the leave-one-out estimates (NaN if any failed
 * or with fewer than two groups). */
static double jackknife(const double *Dg, const int *ok, size_t G)
{
    if (G < 2)
        return NAN;
    double mean = 0;
    for (size_t g = 0; g < G; g++) {
        if (!ok[g])
            return NAN;
        mean += Dg[g];
    }
    mean /= (double)G;
    double s = 0;
    for (size_t g = 0; g < G; g++)
        s += (Dg[g] - mean) * (Dg[g] - mean);
    return sqrt((double)(G - 1) / (double)G * s);
}

/* ---- by lag: MSD and VACF ---------------------------------------------- */

/* table[k][6] = the sums over the groups but skip of num / count (NaN
 * without pairs) at the lags they cover (the others NaN); the counts into
 * count (if not NULL). */
static void combine(const mimas_msd_sums *gr, size_t ngroups, size_t skip,
                    const disperse_comps *cm, size_t lags, double *table, double *count)
{
    for (size_t k = 0; k < lags * NC; k++)
        table[k] = NAN;
    size_t first = gr[0].first, n = gr[0].nlags;
    for (size_t k = first; k < first + n && k < lags; k++) {
        double num[8] = {0}, cnt = 0, out[NC];
        for (size_t g = 0; g < ngroups; g++) {
            if (g == skip)
                continue;
            for (size_t c = 0; c < cm->n; c++)
                num[c] += gr[g].num[c * n + k - first];
            cnt += gr[g].count[k - first];
        }
        disperse_comps_expand(cm, num, out);
        for (int c = 0; c < NC; c++)
            table[k * NC + c] = cnt > 0 ? out[c] / cnt : NAN;
        if (count)
            count[k] = cnt;
    }
}

void disperse_window(const mimas_disperse_result *r, size_t *klo, size_t *khi)
{
    double eps = 1e-9;
    double lo = ceil(r->fit_lo / r->dt - eps), hi = floor(r->fit_hi / r->dt + eps);
    *klo = lo < 0 ? 0 : (size_t)lo;
    *khi = hi < 0 ? 0 : hi > (double)(r->lags - 1) ? r->lags - 1 : (size_t)hi;
    if (hi < 0 || lo > (double)*khi)
        *klo = *khi + 1; /* empty */
}

/* D of component c from a lag table. */
static int lag_D(const mimas_disperse_result *r, const double *table, int vacf, int c,
                 points *p, mimas_disperse_diffusion *row, mimas_error *err)
{
    size_t klo, khi;
    disperse_window(r, &klo, &khi);
    int dim = mimas_disperse_component_dim(c);
    if (!vacf) {
        p->n = 0;
        for (size_t k = klo; k <= khi && k < r->lags; k++) {
            p->x[p->n] = (double)k * r->dt;
            p->y[p->n++] = table[k * NC + c];
        }
        return line_D(p, dim, row, err);
    }
    /* the running Green-Kubo integral by the trapezoidal rule, averaged over the window */
    double I = 0, sum = 0;
    size_t n = 0;
    int finite = 1;
    for (size_t k = 0; k <= khi && k < r->lags; k++) {
        if (k > 0)
            I += 0.5 * r->dt * (table[(k - 1) * NC + c] + table[k * NC + c]);
        if (k >= klo) {
            sum += I;
            n++;
        }
    }
    finite = isfinite(sum);
    row->npts = n;
    row->D = n && finite ? sum / (double)n / dim : NAN;
    row->D_err_fit = row->intercept = NAN;
    row->t0 = n ? (double)klo * r->dt : NAN;
    row->t1 = n ? (double)(klo + n - 1) * r->dt : NAN;
    row->status = !n ? MIMAS_FIT_FEW_POINTS : finite ? MIMAS_FIT_OK : MIMAS_FIT_UNDETERMINED;
    return MIMAS_OK;
}

int disperse_lag_tables(mimas_disperse_result *r, const mimas_msd_sums *all,
                        const mimas_msd_sums *groups, size_t ngroups, const disperse_comps *cm,
                        int vacf, mimas_error *err)
{
    size_t lags = r->lags;
    double *table = vacf ? r->vacf : r->msd;
    double *tmp = malloc(lags * NC * sizeof *tmp);
    points p;
    int rc = tmp ? points_alloc(&p, lags, err) : mimas_error_set(err, MIMAS_EIO, "out of memory");
    if (rc) {
        free(tmp);
        return rc;
    }
    combine(all, 1, SIZE_MAX, cm, lags, table, vacf ? NULL : r->count);
    mimas_disperse_diffusion rows[NC];
    double Dg[NC][MIMAS_DISPERSE_GROUPS];
    int ok[NC][MIMAS_DISPERSE_GROUPS];
    for (int c = 0; c < NC && !rc; c++) {
        memset(&rows[c], 0, sizeof rows[c]);
        snprintf(rows[c].what, sizeof rows[c].what, "%s", vacf ? "vacf" : "msd");
        rows[c].component = c;
        rc = lag_D(r, table, vacf, c, &p, &rows[c], err);
    }
    for (size_t g = 0; g < ngroups && !rc; g++) {
        combine(groups, ngroups, g, cm, lags, tmp, NULL);
        for (int c = 0; c < NC && !rc; c++) {
            mimas_disperse_diffusion one;
            rc = lag_D(r, tmp, vacf, c, &p, &one, err);
            Dg[c][g] = one.D;
            ok[c][g] = one.status == MIMAS_FIT_OK && isfinite(one.D);
        }
    }
    for (int c = 0; c < NC && !rc; c++) {
        rows[c].D_err = rows[c].status == MIMAS_FIT_OK ? jackknife(Dg[c], ok[c], ngroups) : NAN;
        rc = disperse_push_diffusion(r, &rows[c], err);
    }
    points_free(&p);
    free(tmp);
    return rc;
}

/* ---- by cohort: sigma^2(t) --------------------------------------------- */

/* sigma^2 axial and transverse at frame t without group skip. */
static void sigma2(const cohort_stats *st, size_t t, size_t skip, double *n, double *ax,
                   double *tr, double mean[3])
{
    double m2[3];
    cohort_stats_merged(st, t, skip, n, mean, m2);
    *ax = *n > 0 ? m2[2] / *n : NAN;
    *tr = *n > 0 ? (m2[0] + m2[1]) / *n : NAN;
}

/* Whether frame t enters the cohort's fits: every member present, and
 * sigma_axial above fit_from or the time since completion in the window. */
static int fit_row(const mimas_disperse_options *o, double n, size_t size, double ax,
                   double time, double complete, double dt)
{
    if (!size || n != (double)size)
        return 0;
    if (o->has_fit_from)
        return sqrt(ax) > o->fit_from;
    if (o->has_fit_lags) {
        double since = time - complete, eps = 1e-9 * dt;
        return since >= o->fit_lo - eps && since <= o->fit_hi + eps;
    }
    return 1;
}

/* The two D rows of the cohort from the fit frames (sel) of the
 * statistics without group skip. */
static int cohort_D(const cohort_stats *st, const unsigned char *sel, const double *times,
                    size_t skip, points *pa, points *pt, mimas_disperse_diffusion rows[2],
                    mimas_error *err)
{
    pa->n = pt->n = 0;
    for (size_t t = 0; t < st->frames; t++) {
        if (!sel[t])
            continue;
        double n, ax, tr, mean[3];
        sigma2(st, t, skip, &n, &ax, &tr, mean);
        pa->x[pa->n] = pt->x[pt->n] = times[t];
        pa->y[pa->n++] = ax;
        pt->y[pt->n++] = tr;
    }
    int rc = line_D(pa, 1, &rows[0], err);
    return rc ? rc : line_D(pt, 2, &rows[1], err);
}

int disperse_cohort_table(mimas_disperse_result *r, size_t k, const mimas_cohort *c,
                          const cohort_stats *st, const double *times,
                          const mimas_disperse_options *o, mimas_error *err)
{
    mimas_disperse_cohort *out = &r->cohorts[k];
    size_t T = st->frames;
    out->spec = c->spec;
    out->size = c->size;
    out->complete_time = NAN;
    out->rows = malloc((T ? T : 1) * sizeof *out->rows);
    unsigned char *sel = calloc(T + 1, 1);
    points pa = {0}, pt = {0};
    int rc = out->rows && sel ? MIMAS_OK : mimas_error_set(err, MIMAS_EIO, "out of memory");
    if (!rc)
        rc = points_alloc(&pa, T, err);
    if (!rc)
        rc = points_alloc(&pt, T, err);
    const mimas_axis *a = &r->axis;
    for (size_t t = 0; t < T && !rc; t++) {
        double n, ax, tr, m[3];
        sigma2(st, t, SIZE_MAX, &n, &ax, &tr, m);
        if (n == 0)
            continue;
        if (n == (double)c->size && isnan(out->complete_time))
            out->complete_time = times[t];
        mimas_disperse_cohort_row *row = &out->rows[out->nrows++];
        row->time = times[t];
        row->n = (size_t)n;
        for (int d = 0; d < 3; d++)
            row->mean[d] = a->origin[d] + m[0] * a->ex[d] + m[1] * a->ey[d] + m[2] * a->ez[d];
        row->sigma2_axial = ax;
        row->sigma2_transverse = tr;
        sel[t] = fit_row(o, n, c->size, ax, times[t], out->complete_time, r->dt);
    }
    mimas_disperse_diffusion rows[2];
    memset(rows, 0, sizeof rows);
    if (!rc)
        rc = cohort_D(st, sel, times, SIZE_MAX, &pa, &pt, rows, err);
    /* the jackknife over the member groups that have members */
    size_t G = c->size < MIMAS_DISPERSE_GROUPS ? c->size : MIMAS_DISPERSE_GROUPS;
    double Dg[2][MIMAS_DISPERSE_GROUPS];
    int ok[2][MIMAS_DISPERSE_GROUPS];
    for (size_t g = 0; g < G && !rc; g++) {
        mimas_disperse_diffusion one[2];
        rc = cohort_D(st, sel, times, g, &pa, &pt, one, err);
        for (int q = 0; q < 2; q++) {
            Dg[q][g] = one[q].D;
            ok[q][g] = one[q].status == MIMAS_FIT_OK && isfinite(one[q].D);
        }
    }
    for (int q = 0; q < 2 && !rc; q++) {
        snprintf(rows[q].what, sizeof rows[q].what, "cohort:%s", c->spec);
        rows[q].component = q ? MIMAS_DC_TRANSVERSE : MIMAS_DC_AXIAL;
        rows[q].D_err = rows[q].status == MIMAS_FIT_OK ? jackknife(Dg[q], ok[q], G) : NAN;
        rc = disperse_push_diffusion(r, &rows[q], err);
    }
    points_free(&pa);
    points_free(&pt);
    free(sel);
    return rc;
}
