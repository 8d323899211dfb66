#include <config.h>

#include "shearband.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

double mimas_band_profile(int model, const double *p, double r)
{
    double e = erf((r - p[MIMAS_BAND_RC]) / p[MIMAS_BAND_W]);
    return model == 4 ? p[MIMAS_BAND_A] + p[MIMAS_BAND_B] * e : 0.5 + 0.5 * e;
}

/* The model in scaled coordinates u = (r - r0)/L (parameters of order 1
 * help the solver); p: c, w (, A, B). */
static double scaled_model(double u, const double *p, double *grad, const void *ctx)
{
    int model = *(const int *)ctx;
    double w = p[1];
    if (w == 0)
        return NAN;
    double t = (u - p[0]) / w, e = erf(t);
    double amp = model == 4 ? p[3] : 0.5;
    if (grad) {
        double g = amp * M_2_SQRTPI * exp(-t * t) / w; /* d(amp erf t)/du */
        grad[0] = -g;
        grad[1] = -g * t;
        if (model == 4) {
            grad[2] = 1.0;
            grad[3] = e;
        }
    }
    return model == 4 ? p[2] + p[3] * e : 0.5 + 0.5 * e;
}

/* Starting values from the data (u in [0, 1]): the levels inside and
 * outside as the means over the inner and outer quarter; for an erf step
 * of unit height from level y_in to y_out, int (y_out - y)/(y_out - y_in) du
 * over [0, 1] is the centre c, and int |y_n - H(u - c)| du = w/sqrt(pi). */
static void start(int model, const double *u, const double *y, size_t n, double *p)
{
    double in = 0, out = 0;
    size_t nin = 0, nout = 0;
    for (size_t i = 0; i < n; i++) {
        if (u[i] <= 0.25)
            in += y[i], nin++;
        if (u[i] >= 0.75)
            out += y[i], nout++;
    }
    in = nin ? in / (double)nin : y[0];
    out = nout ? out / (double)nout : y[n - 1];
    if (model == 2) {
        /* the model's own levels, in the direction the data go */
        double lo = out >= in ? 0.0 : 1.0;
        in = lo;
        out = 1.0 - lo;
    }
    double h = out - in;
    if (fabs(h) < 1e-12)
        h = 1.0;
    double c = 0, dev = 0;
    for (size_t i = 0; i + 1 < n; i++) {
        double du = u[i + 1] - u[i];
        c += 0.5 * du * ((out - y[i]) + (out - y[i + 1])) / h;
    }
    c = fmin(fmax(c, 0.0), 1.0);
    for (size_t i = 0; i + 1 < n; i++) {
        double du = u[i + 1] - u[i];
        double a = (y[i] - in) / h - (u[i] >= c), b = (y[i + 1] - in) / h - (u[i + 1] >= c);
        dev += 0.5 * du * (fabs(a) + fabs(b));
    }
    double w = sqrt(M_PI) * dev;
    double wmin = 0.5 / (double)(n > 1 ? n - 1 : 1);
    p[0] = c;
    p[1] = fmin(fmax(w, wmin), 1.0);
    if (model == 2 && out < in)
        p[1] = -p[1];
    if (model == 4) {
        p[2] = 0.5 * (in + out);
        p[3] = 0.5 * (out - in);
    }
}

int mimas_band_fit(const double *r, const double *y, const double *sigma, size_t n, int model,
                   size_t min_points, mimas_fit *out, mimas_error *err)
{
    if (model != 2 && model != 4)
        return mimas_error_set(err, MIMAS_EUSAGE, "the band model is 2 or 4, not %d", model);
    /* the valid points in scaled coordinates, by increasing r */
    double *u = malloc((n ? n : 1) * sizeof *u), *v = malloc((n ? n : 1) * sizeof *v),
           *s = sigma ? malloc((n ? n : 1) * sizeof *s) : NULL;
    if (!u || !v || (sigma && !s)) {
        free(u), free(v), free(s);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the shear-band fit");
    }
    size_t m = 0;
    double r0 = INFINITY, r1 = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(r[i]) || !isfinite(y[i]) ||
            (sigma && !(isfinite(sigma[i]) && sigma[i] > 0)))
            continue;
        r0 = fmin(r0, r[i]);
        r1 = fmax(r1, r[i]);
        u[m] = r[i];
        v[m] = y[i];
        if (s)
            s[m] = sigma[i];
        m++;
    }
    /* insertion sort by r: layers come sorted, this only guards */
    for (size_t i = 1; i < m; i++)
        for (size_t j = i; j > 0 && u[j - 1] > u[j]; j--) {
            double t = u[j], tv = v[j];
            u[j] = u[j - 1], v[j] = v[j - 1];
            u[j - 1] = t, v[j - 1] = tv;
            if (s) {
                double ts = s[j];
                s[j] = s[j - 1], s[j - 1] = ts;
            }
        }
    double L = m > 1 && r1 > r0 ? r1 - r0 : 1.0;
    for (size_t i = 0; i < m; i++)
        u[i] = (u[i] - (m ? r0 : 0)) / L;
    double p0[4] = {0.5, 0.25, 0.5, 0.5};
    if (m > 1)
        start(model, u, v, m, p0);
    mimas_fit_model fm = {(size_t)model, scaled_model, &model};
    int rc = mimas_fit_nonlinear(&fm, u, v, s, m, p0, min_points, out, err);
    free(u), free(v), free(s);
    if (rc || out->status != MIMAS_FIT_OK)
        return rc;
    /* back to metres */
    out->p[MIMAS_BAND_RC] = r0 + L * out->p[0];
    out->err[MIMAS_BAND_RC] *= L;
    out->p[MIMAS_BAND_W] *= L;
    out->err[MIMAS_BAND_W] *= L;
    if (model == 4 && out->p[MIMAS_BAND_W] < 0) {
        /* B erf(x/W) = (-B) erf(x/(-W)) */
        out->p[MIMAS_BAND_W] = -out->p[MIMAS_BAND_W];
        out->p[MIMAS_BAND_B] = -out->p[MIMAS_BAND_B];
    }
    /* a band that falls with r (the wrong sign of Omega), or a centre or
     * width known no better than the radial range of the data, is no fit */
    double range = r1 - r0;
    if (!(out->p[MIMAS_BAND_W] > 0) || !(out->err[MIMAS_BAND_RC] <= range) ||
        !(out->err[MIMAS_BAND_W] <= range)) {
        for (size_t k = 0; k < out->np; k++)
            out->p[k] = out->err[k] = NAN;
        out->status = MIMAS_FIT_IMPLAUSIBLE;
    }
    return MIMAS_OK;
}

double mimas_band_fenistein_rc(double rs, double h)
{
    return rs * (1.0 - pow(h / rs, 2.5));
}

void mimas_band_free(mimas_band *b)
{
    if (!b)
        return;
    free(b->layers);
    free(b->store);
    free(b);
}

/* The grid a band analysis needs: cylindrical, no phi cells, some r cells. */
static int check_grid(const mimas_fieldset *fs, mimas_error *err)
{
    const mimas_fieldset_grid *g = mimas_fieldset_grid_of(fs);
    const char *name = mimas_fieldset_name(fs);
    if (g->kind != MIMAS_FIELDSET_CYLINDRICAL)
        return mimas_error_set(err, MIMAS_EDATA,
                               "%s: the shear band needs fields on an r-z grid (mimas average "
                               "--grid r=...,z=...), not a %s grid", name,
                               g->kind == MIMAS_FIELDSET_NONE ? "'none'" : "Cartesian");
    if (g->n[1] > 1)
        return mimas_error_set(err, MIMAS_EDATA,
                               "%s: the grid has %d phi cells; the shear band needs an r-z grid "
                               "(average over phi)", name, g->n[1]);
    if (g->n[0] < 2)
        return mimas_error_set(err, MIMAS_EDATA, "%s: the grid has %d radial cell; the shear "
                               "band needs a radial profile", name, g->n[0]);
    return MIMAS_OK;
}

/* omega/Omega and its standard error per cell, from omega or v_phi/r. */
static int read_profile(const mimas_fieldset *fs, double omega, double *y, double *sem,
                        const char **used, mimas_error *err)
{
    const mimas_fieldset_grid *g = mimas_fieldset_grid_of(fs);
    int rc;
    int from_vphi = !mimas_fieldset_has(fs, "omega");
    if (from_vphi && !mimas_fieldset_has(fs, "v_phi"))
        return mimas_error_set(err, MIMAS_EDATA,
                               "%s: no velocity: the field set has neither omega nor v_phi",
                               mimas_fieldset_name(fs));
    *used = from_vphi ? "v_phi" : "omega";
    rc = mimas_fieldset_read(fs, *used, y, sem, err);
    for (size_t c = 0; !rc && c < g->cells; c++) {
        /* v_phi/r at the cell centre, like average's omega */
        double scale = 1.0 / omega;
        if (from_vphi)
            scale /= g->centre[0][c % (size_t)g->n[0]];
        y[c] *= scale;
        sem[c] *= fabs(scale);
    }
    return rc;
}

int mimas_band_analyse(const mimas_fieldset *fs, const mimas_band_options *o, mimas_band **out,
                       mimas_error *err)
{
    *out = NULL;
    if (!(isfinite(o->omega) && o->omega != 0))
        return mimas_error_set(err, MIMAS_EUSAGE, "Omega must be a non-zero rate");
    int rc = check_grid(fs, err);
    if (rc)
        return rc;
    const mimas_fieldset_grid *g = mimas_fieldset_grid_of(fs);
    size_t nr = (size_t)g->n[0], nz = (size_t)g->n[2], cells = g->cells;
    mimas_band *b = calloc(1, sizeof *b);
    double *store = malloc(3 * cells * sizeof *store);
    mimas_band_layer *layers = calloc(nz, sizeof *layers);
    if (!b || !store || !layers) {
        free(b), free(store), free(layers);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the shear-band fit");
    }
    b->model = o->model;
    b->nlayers = nz;
    b->layers = layers;
    b->store = store;
    double *rr = store, *y = store + cells, *sem = store + 2 * cells;
    rc = read_profile(fs, o->omega, y, sem, &b->velocity, err);
    /* weighted when the velocity has standard errors at all */
    int any = 0;
    for (size_t c = 0; c < cells; c++)
        any |= isfinite(sem[c]) && sem[c] > 0;
    b->weighted = any && !o->unweighted;
    for (size_t k = 0; !rc && k < nz; k++) {
        mimas_band_layer *l = &layers[k];
        l->z = g->centre[2][k];
        l->nr = nr;
        /* phi has one cell: the layer's cells are k nr .. k nr + nr - 1 */
        l->r = rr + k * nr;
        l->y = y + k * nr;
        l->sigma = sem + k * nr;
        memcpy(l->r, g->centre[0], nr * sizeof *l->r);
        rc = mimas_band_fit(l->r, l->y, b->weighted ? l->sigma : NULL, nr, o->model,
                            o->min_points, &l->fit, err);
    }
    if (rc) {
        mimas_band_free(b);
        return rc;
    }
    *out = b;
    return MIMAS_OK;
}

int mimas_band_choose_grid(const mimas_frame *f, mimas_grid *g, char *spec, size_t len,
                           mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    int rc = mimas_table_require(p, &mimas_particles_desc, MIMAS_P_RADIUS, err);
    if (rc)
        return rc;
    if (p->n == 0)
        return mimas_error_set(err, MIMAS_EDATA, "the first frame has no particles");
    double cx = 0.5 * (f->box.lo[0] + f->box.hi[0]), cy = 0.5 * (f->box.lo[1] + f->box.hi[1]);
    double r0 = INFINITY, r1 = 0, z0 = INFINITY, z1 = -INFINITY, dsum = 0;
    for (size_t k = 0; k < p->n; k++) {
        double r = hypot(p->pos[k][0] - cx, p->pos[k][1] - cy), a = p->radius[k];
        r0 = fmin(r0, r - a);
        r1 = fmax(r1, r + a);
        z0 = fmin(z0, p->pos[k][2] - a);
        z1 = fmax(z1, p->pos[k][2] + a);
        dsum += 2 * a;
    }
    r0 = fmax(r0, 0.0);
    double d = dsum / (double)p->n;
    if (!(d > 0) || !(r1 > r0) || !(z1 > z0))
        return mimas_error_set(err, MIMAS_EDATA, "the particles of the first frame span no "
                               "volume (radius 0?)");
    /* bounds rounded outwards to a round length q ~ d/10, so that the grid
     * said on standard error is short and holds every sphere */
    double q = pow(10.0, floor(log10(d / 10)));
    r0 = floor(r0 / q) * q;
    r1 = ceil(r1 / q) * q;
    z0 = floor(z0 / q) * q;
    z1 = ceil(z1 / q) * q;
    long nr = lround((r1 - r0) / (2 * d)), nz = lround((z1 - z0) / (2 * d));
    nr = nr < 2 ? 2 : nr;
    nz = nz < 1 ? 1 : nz;
    char grid[256], axis[128];
    snprintf(grid, sizeof grid, "r=%.10g:%.10g:%ld,z=%.10g:%.10g:%ld", r0, r1, nr, z0, z1, nz);
    snprintf(axis, sizeof axis, "%.10g,%.10g,0,0,0,1", cx, cy);
    snprintf(spec, len, "--grid %s --axis %s", grid, axis);
    return mimas_grid_parse(g, grid, axis, err);
}
