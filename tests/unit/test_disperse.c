/* mimas disperse's analysis (averaging/disperse.h) on frames made here.
 *
 * Brownian walkers with a different D per axis and a drift, along a tilted
 * axis: the D of every component is the mean of the particles' own
 * least-squares slopes (computed here from direct MSDs; the ensemble MSD is
 * their mean, and a line fit is linear in its data); it recovers the D put
 * in within 4 standard errors, the standard error being the spread of the
 * particles' slopes over sqrt(N) (the particles are independent), and the
 * jackknife D_err agrees with that error within what 16 groups allow.
 * Without --remove-drift the fitted D carries the drift's u^2 (a + b) / 2
 * (a, b the window's ends: the slope of t^2 over equally spaced t); with it
 * D (1 - 1/N) (the mean taken off holds 1/N of each particle's own motion).
 * The finite-difference velocities of the walk give VACF(0) = <v^2> and the
 * Green-Kubo D.  Cohorts of every kind: members, n, mean, sigma^2 along and
 * across the axis against two-pass sums here, D and its jackknife against a
 * closed-form line fit here.  The default axis is the input's tube. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assert_close.h"
#include "particle_frame.h"
#include "disperse.h"
#include "scratch.h"

/* ---- frames ---- */

#define frame_of(f, n, bits, time) \
    assert_int_equal(particle_frame(f, n, bits, time, NULL), MIMAS_OK)

static const mimas_disperse_diffusion *row_of(const mimas_disperse_result *r, const char *what,
                                              int component)
{
    for (size_t i = 0; i < r->ndiffusion; i++)
        if (!strcmp(r->diffusion[i].what, what) && r->diffusion[i].component == component)
            return &r->diffusion[i];
    fail_msg("no diffusion row %s %d", what, component);
    return NULL;
}

/* The least-squares slope of y against x (closed form). */
static double slope(const double *x, const double *y, size_t n)
{
    double mx = 0, my = 0;
    for (size_t i = 0; i < n; i++)
        mx += x[i], my += y[i];
    mx /= (double)n;
    my /= (double)n;
    double sxy = 0, sxx = 0;
    for (size_t i = 0; i < n; i++)
        sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
    return sxy / sxx;
}

/* ---- Brownian walkers ---- */

#define BN 240
#define BT 800
#define BDT 0.01
#define KLO 5
#define KHI 40
static const double Dxyz[3] = {1e-3, 4e-3, 2.5e-3};
static const double U[3] = {0.05, -0.02, 0.1};
static const double AXIS_DIR[3] = {1, 2, 0};

static double *walkers(void)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 42);
    double *x = malloc((size_t)BN * BT * 3 * sizeof *x);
    for (int i = 0; i < BN; i++)
        for (int d = 0; d < 3; d++)
            x[(size_t)i * BT * 3 + d] = gsl_rng_uniform(rng);
    for (int i = 0; i < BN; i++)
        for (int t = 1; t < BT; t++)
            for (int d = 0; d < 3; d++) {
                size_t k = ((size_t)i * BT + t) * 3 + d;
                x[k] = x[k - 3] + U[d] * BDT + gsl_ran_gaussian(rng, sqrt(2 * Dxyz[d] * BDT));
            }
    gsl_rng_free(rng);
    return x;
}

static mimas_disperse *analyse_walkers(const double *x, int remove_drift, int vacf)
{
    mimas_disperse_options o;
    memset(&o, 0, sizeof o);
    o.axis = "0,0,0,1,2,0";
    o.remove_drift = remove_drift;
    o.vacf = vacf;
    o.has_fit_lags = 1;
    o.fit_lo = KLO * BDT;
    o.fit_hi = KHI * BDT;
    o.memory = 256u << 20;
    mimas_disperse *d;
    mimas_error err;
    assert_int_equal(mimas_disperse_create(&d, &o, &err), MIMAS_OK);
    mimas_frame f;
    mimas_frame_init(&f);
    /* velocities: forward differences, over the first BT - 1 frames */
    int frames = vacf ? BT - 1 : BT;
    for (int t = 0; t < frames; t++) {
        frame_of(&f, BN, vacf ? MIMAS_P_VEL : 0, t * BDT);
        for (int i = 0; i < BN; i++) {
            f.particles.id[i] = 1000 + i;
            for (int c = 0; c < 3; c++) {
                const double *p = x + ((size_t)i * BT + t) * 3;
                f.particles.pos[i][c] = p[c];
                if (vacf)
                    f.particles.vel[i][c] = (p[3 + c] - p[c]) / BDT;
            }
        }
        assert_int_equal(mimas_disperse_add(d, &f, &err), MIMAS_OK);
    }
    mimas_frame_free(&f);
    assert_int_equal(mimas_disperse_finish(d, &err), MIMAS_OK);
    return d;
}

/* The six components of a displacement d (axis direction e). */
static void components(const double dd[3], const double e[3], double out[6])
{
    double ax = dd[0] * e[0] + dd[1] * e[1] + dd[2] * e[2];
    double tot = dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2];
    out[0] = dd[0] * dd[0];
    out[1] = dd[1] * dd[1];
    out[2] = dd[2] * dd[2];
    out[3] = ax * ax;
    out[4] = tot - ax * ax;
    out[5] = tot;
}

/* Per particle and component the slope of its own MSD over the window,
 * from the direct sums; the drift (the mean position) taken off if asked. */
static void particle_slopes(const double *x, int remove_drift, double *slopes /* [BN][6] */)
{
    double e[3], len = sqrt(AXIS_DIR[0] * AXIS_DIR[0] + AXIS_DIR[1] * AXIS_DIR[1]);
    for (int c = 0; c < 3; c++)
        e[c] = AXIS_DIR[c] / len;
    double *mean = calloc((size_t)BT * 3, sizeof *mean);
    for (int i = 0; remove_drift && i < BN; i++)
        for (int t = 0; t < BT; t++)
            for (int c = 0; c < 3; c++)
                mean[t * 3 + c] += x[((size_t)i * BT + t) * 3 + c] / BN;
    double lag[KHI - KLO + 1], msd[6][KHI - KLO + 1];
    for (int i = 0; i < BN; i++) {
        for (int k = KLO; k <= KHI; k++) {
            double s[6] = {0};
            for (int t = 0; t + k < BT; t++) {
                double dd[3], q[6];
                for (int c = 0; c < 3; c++)
                    dd[c] = x[((size_t)i * BT + t + k) * 3 + c] - x[((size_t)i * BT + t) * 3 + c] -
                            (mean[(t + k) * 3 + c] - mean[t * 3 + c]);
                components(dd, e, q);
                for (int c = 0; c < 6; c++)
                    s[c] += q[c];
            }
            lag[k - KLO] = k * BDT;
            for (int c = 0; c < 6; c++)
                msd[c][k - KLO] = s[c] / (BT - k);
        }
        for (int c = 0; c < 6; c++)
            slopes[i * 6 + c] = slope(lag, msd[c], KHI - KLO + 1);
    }
    free(mean);
}

/* The D each component should have without drift removal (walk plus
 * drift; the drift adds u^2 (a + b) / 2) or with it (times 1 - 1/N). */
static void expected_D(int remove_drift, double out[6])
{
    double e[3], len = sqrt(AXIS_DIR[0] * AXIS_DIR[0] + AXIS_DIR[1] * AXIS_DIR[1]);
    for (int c = 0; c < 3; c++)
        e[c] = AXIS_DIR[c] / len;
    /* the diffusion tensor diag(D) and the drift's u u^T (a + b) / 2 */
    double ab = (KLO + KHI) * BDT, M[3][3] = {{0}};
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            M[a][b] = (a == b ? Dxyz[a] * (remove_drift ? 1 - 1.0 / BN : 1) : 0) +
                      (remove_drift ? 0 : U[a] * U[b] * ab / 2);
    double ax = 0, tr = M[0][0] + M[1][1] + M[2][2];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            ax += e[a] * M[a][b] * e[b];
    out[0] = M[0][0];
    out[1] = M[1][1];
    out[2] = M[2][2];
    out[3] = ax;
    out[4] = (tr - ax) / 2;
    out[5] = tr / 3;
}

static void check_walkers(int remove_drift)
{
    double *x = walkers();
    mimas_disperse *d = analyse_walkers(x, remove_drift, 0);
    const mimas_disperse_result *r = mimas_disperse_result_of(d);
    assert_int_equal(r->frames, BT);
    assert_int_equal(r->particles, BN);
    assert_int_equal(r->lags, BT);
    assert_int_equal(r->groups, MIMAS_DISPERSE_GROUPS);
    assert_close(r->dt, BDT, 1e-15);
    double *s = malloc(BN * 6 * sizeof *s), want[6];
    particle_slopes(x, remove_drift, s);
    expected_D(remove_drift, want);
    for (int c = 0; c < 6; c++) {
        int dim = mimas_disperse_component_dim(c);
        double mean = 0, var = 0;
        for (int i = 0; i < BN; i++)
            mean += s[i * 6 + c] / BN;
        for (int i = 0; i < BN; i++)
            var += (s[i * 6 + c] - mean) * (s[i * 6 + c] - mean) / (BN - 1);
        double D = mean / (2 * dim), se = sqrt(var / BN) / (2 * dim);
        const mimas_disperse_diffusion *row = row_of(r, "msd", c);
        assert_int_equal(row->status, MIMAS_FIT_OK);
        assert_int_equal(row->npts, KHI - KLO + 1);
        assert_close(row->t0, KLO * BDT, 1e-12);
        assert_close(row->t1, KHI * BDT, 1e-12);
        /* the program's D is the mean of the particles' slopes ... */
        assert_close(row->D, D, 1e-8 * D);
        /* ... which recovers what was put in, within 4 standard errors */
        assert_close(row->D, want[c], 4 * se);
        /* the jackknife over 16 groups estimates that error (its own relative
         * spread is 1/sqrt(2 * 15) = 18 %: the bounds catch wrong factors
         * such as sqrt(16), not chance) */
        assert_true(row->D_err > 0.4 * se && row->D_err < 2.0 * se);
        /* the least-squares error of correlated points is far too small */
        if (remove_drift)
            assert_true(row->D_err_fit < 0.5 * se);
    }
    /* the MSD table at lag 1: the count and the total against the direct sum */
    assert_close(r->count[1], (double)BN * (BT - 1), 0);
    double direct = 0;
    for (int i = 0; i < BN && !remove_drift; i++)
        for (int t = 0; t + 1 < BT; t++)
            for (int c = 0; c < 3; c++) {
                double dd = x[((size_t)i * BT + t + 1) * 3 + c] - x[((size_t)i * BT + t) * 3 + c];
                direct += dd * dd;
            }
    if (!remove_drift)
        assert_close(r->msd[MIMAS_DC_COUNT + MIMAS_DC_TOTAL], direct / (BN * (BT - 1.0)),
                     1e-10 * direct / (BN * (BT - 1.0)));
    free(s);
    free(x);
    mimas_disperse_free(d);
}

static void test_walkers_drift_removed(void **state)
{
    (void)state;
    check_walkers(1);
}

static void test_walkers_with_drift(void **state)
{
    (void)state;
    check_walkers(0);
}

static void test_vacf(void **state)
{
    (void)state;
    double *x = walkers();
    mimas_disperse *d = analyse_walkers(x, 1, 1);
    const mimas_disperse_result *r = mimas_disperse_result_of(d);
    assert_non_null(r->vacf);
    /* VACF(0) = <|v - <v>|^2> over every particle and frame, directly */
    double c0[3] = {0, 0, 0};
    for (int t = 0; t < BT - 1; t++) {
        double vm[3] = {0, 0, 0};
        for (int i = 0; i < BN; i++)
            for (int c = 0; c < 3; c++)
                vm[c] += (x[((size_t)i * BT + t + 1) * 3 + c] - x[((size_t)i * BT + t) * 3 + c]) /
                         BDT / BN;
        for (int i = 0; i < BN; i++)
            for (int c = 0; c < 3; c++) {
                double v = (x[((size_t)i * BT + t + 1) * 3 + c] - x[((size_t)i * BT + t) * 3 + c]) /
                           BDT - vm[c];
                c0[c] += v * v / (BN * (BT - 1.0));
            }
    }
    for (int c = 0; c < 3; c++)
        assert_close(r->vacf[c], c0[c], 1e-10 * c0[c]);
    /* Green-Kubo: white-noise velocities, D = dt C(0) / 2 (1 - 1/N) per
     * component; the running integral's noise is what D_err measures */
    double want[6];
    expected_D(1, want);
    for (int c = 0; c < 6; c++) {
        const mimas_disperse_diffusion *row = row_of(r, "vacf", c);
        assert_int_equal(row->status, MIMAS_FIT_OK);
        assert_true(isnan(row->D_err_fit));
        assert_true(row->D_err > 0);
        assert_close(row->D, want[c], 5 * row->D_err + 0.01 * want[c]);
    }
    free(x);
    mimas_disperse_free(d);
}

/* ---- cohorts ---- */

#define CN 40
#define CT 20
#define CDT 0.1

static int first_frame(int i) { return i % 5; }
static int last_frame(int i) { return CT - 1 - i % 3; }
static int32_t type_of(int i) { return 1 + i % 3; }

static const char *cohort_specs[] = {
    "all", "types:2", NULL /* ids:FILE */, "inserted:0.15:0.35",
    "region:box:0,0,0:0.5,0.5,1@0.5", "region:slab:0.2:0.6@0.45", "region:cylinder:0.3@1"};
#define NCOH 7
static const int64_t listed[] = {3, 5, 7, 11, 13, 77};

/* positions of the cohort walk: x[i][t][3] */
static double *cohort_walk(void)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 7);
    double *x = malloc(CN * CT * 3 * sizeof *x);
    for (int i = 0; i < CN; i++)
        for (int t = 0; t < CT; t++)
            for (int c = 0; c < 3; c++)
                x[(i * CT + t) * 3 + c] = t ? x[(i * CT + t - 1) * 3 + c] +
                                                  gsl_ran_gaussian(rng, 0.02 * (c + 1))
                                            : gsl_rng_uniform(rng);
    gsl_rng_free(rng);
    return x;
}

static const double CAX_O[3] = {0.5, 0.5, 0}, CAX_E[3] = {0, 0.70710678118654752,
                                                            0.70710678118654752};

/* Whether particle i belongs to cohort k, decided from the definitions. */
static int member(int k, int i, const double *x)
{
    const double *p5 = x + (i * CT + 5) * 3, *p10 = x + (i * CT + 10) * 3;
    double s5 = 0, s10 = 0, r10 = 0;
    for (int c = 0; c < 3; c++) {
        s5 += (p5[c] - CAX_O[c]) * CAX_E[c];
        s10 += (p10[c] - CAX_O[c]) * CAX_E[c];
    }
    for (int c = 0; c < 3; c++) {
        double q = p10[c] - CAX_O[c] - s10 * CAX_E[c];
        r10 += q * q;
    }
    int id = i + 1;
    switch (k) {
    case 0: return 1;
    case 1: return type_of(i) == 2;
    case 2:
        for (size_t q = 0; q < sizeof listed / sizeof listed[0]; q++)
            if (listed[q] == id)
                return 1;
        return 0;
    case 3: return first_frame(i) == 2 || first_frame(i) == 3;
    /* present at frame 5 (the first at or after 0.5 and 0.45), frame 10 */
    case 4: return p5[0] >= 0 && p5[0] < 0.5 && p5[1] >= 0 && p5[1] < 0.5 && p5[2] >= 0 &&
                   p5[2] < 1 && last_frame(i) >= 5;
    case 5: return s5 >= 0.2 && s5 < 0.6 && last_frame(i) >= 5;
    case 6: return r10 < 0.09 && last_frame(i) >= 10;
    }
    return 0;
}

static mimas_disperse *analyse_cohorts(const double *x, const char *ids_path, double fit_from)
{
    char ids_spec[300];
    snprintf(ids_spec, sizeof ids_spec, "ids:%s", ids_path);
    const char *specs[NCOH];
    for (int k = 0; k < NCOH; k++)
        specs[k] = cohort_specs[k] ? cohort_specs[k] : ids_spec;
    mimas_disperse_options o;
    memset(&o, 0, sizeof o);
    o.axis = "0.5,0.5,0,0,1,1";
    o.cohorts = specs;
    o.ncohorts = NCOH;
    o.memory = 64u << 20;
    if (fit_from > 0) {
        o.has_fit_from = 1;
        o.fit_from = fit_from;
    }
    mimas_disperse *d;
    mimas_error err;
    assert_int_equal(mimas_disperse_create(&d, &o, &err), MIMAS_OK);
    mimas_frame f;
    mimas_frame_init(&f);
    for (int t = 0; t < CT; t++) {
        frame_of(&f, CN, MIMAS_P_TYPE, t * CDT);
        size_t n = 0;
        for (int i = 0; i < CN; i++) {
            if (t < first_frame(i) || t > last_frame(i))
                continue;
            f.particles.id[n] = i + 1;
            f.particles.type[n] = type_of(i);
            memcpy(f.particles.pos[n], x + (i * CT + t) * 3, sizeof f.particles.pos[n]);
            n++;
        }
        mimas_table_resize(&f.particles, &mimas_particles_desc, n, &err);
        assert_int_equal(mimas_disperse_add(d, &f, &err), MIMAS_OK);
    }
    mimas_frame_free(&f);
    assert_int_equal(mimas_disperse_finish(d, &err), MIMAS_OK);
    return d;
}

/* n, mean, sigma^2 along and across the axis of the members of cohort k at
 * frame t, leaving out the members j (in the order of their slots) with
 * j % 16 == skip; two passes. */
static void direct_stats(const double *x, int k, int t, int skip, double *n, double mean[3],
                         double *ax, double *tr)
{
    /* slot order: by first frame, then by id (the frames list particles by id) */
    int order[CN], m = 0;
    for (int f0 = 0; f0 < 5; f0++)
        for (int i = 0; i < CN; i++)
            if (first_frame(i) == f0)
                order[m++] = i;
    *n = 0;
    double sa = 0, tot = 0, sm = 0;
    mean[0] = mean[1] = mean[2] = 0;
    int j = 0;
    for (int q = 0; q < CN; q++) {
        int i = order[q];
        if (!member(k, i, x))
            continue;
        int mine = j++ % 16 == skip;
        if (mine || t < first_frame(i) || t > last_frame(i))
            continue;
        *n += 1;
        for (int c = 0; c < 3; c++)
            mean[c] += x[(i * CT + t) * 3 + c];
    }
    for (int c = 0; c < 3; c++)
        mean[c] /= *n;
    for (int c = 0; c < 3; c++)
        sm += (mean[c] - CAX_O[c]) * CAX_E[c];
    j = 0;
    for (int q = 0; q < CN; q++) {
        int i = order[q];
        if (!member(k, i, x))
            continue;
        int mine = j++ % 16 == skip;
        if (mine || t < first_frame(i) || t > last_frame(i))
            continue;
        const double *p = x + (i * CT + t) * 3;
        double s = 0;
        for (int c = 0; c < 3; c++) {
            s += (p[c] - CAX_O[c]) * CAX_E[c];
            tot += (p[c] - mean[c]) * (p[c] - mean[c]);
        }
        sa += (s - sm) * (s - sm);
    }
    *ax = sa / *n;
    *tr = (tot - sa) / *n;
}

static void check_cohorts(double fit_from)
{
    double *x = cohort_walk();
    const char *path = scratch_path("ids.txt");
    FILE *fp = fopen(path, "w");
    fprintf(fp, "# the listed particles\n3, 5 7\n11 # and\n13,77\n");
    fclose(fp);
    mimas_disperse *d = analyse_cohorts(x, path, fit_from);
    const mimas_disperse_result *r = mimas_disperse_result_of(d);
    assert_int_equal(r->ncohorts, NCOH);
    size_t cut = 0, few = 0; /* fits that --fit-from shortened, or left too short */
    for (int k = 0; k < NCOH; k++) {
        const mimas_disperse_cohort *h = &r->cohorts[k];
        size_t size = 0;
        for (int i = 0; i < CN; i++)
            size += (size_t)member(k, i, x);
        assert_int_equal(h->size, size);
        assert_true(size > 2);
        /* a row per frame with members, its statistics */
        size_t row = 0;
        double lx[CT], ly[CT], ly2[CT];
        size_t nfit = 0;
        double complete = NAN;
        for (int t = 0; t < CT; t++) {
            double n, mean[3], ax, tr;
            direct_stats(x, k, t, -1, &n, mean, &ax, &tr);
            if (n == 0)
                continue;
            const mimas_disperse_cohort_row *got = &h->rows[row++];
            assert_close(got->time, t * CDT, 1e-12);
            assert_int_equal(got->n, (size_t)n);
            for (int c = 0; c < 3; c++)
                assert_close(got->mean[c], mean[c], 1e-12);
            assert_close(got->sigma2_axial, ax, 1e-10 * ax);
            assert_close(got->sigma2_transverse, tr, 1e-10 * tr);
            if (n == (double)size && isnan(complete))
                complete = t * CDT;
            if (n == (double)size && (fit_from <= 0 || sqrt(ax) > fit_from)) {
                lx[nfit] = t * CDT;
                ly[nfit] = ax;
                ly2[nfit++] = tr;
            } else if (n == (double)size) {
                cut++;
            }
        }
        assert_int_equal(h->nrows, row);
        assert_close(h->complete_time, complete, 1e-12);
        /* D from the line through the complete (and wide enough) frames */
        char what[300];
        snprintf(what, sizeof what, "cohort:%s", h->spec);
        const mimas_disperse_diffusion *ra = row_of(r, what, MIMAS_DC_AXIAL);
        const mimas_disperse_diffusion *rt = row_of(r, what, MIMAS_DC_TRANSVERSE);
        assert_int_equal(ra->npts, nfit);
        if (nfit < 3) {
            assert_int_equal(ra->status, MIMAS_FIT_FEW_POINTS);
            assert_true(isnan(ra->D) && isnan(ra->D_err));
            few++;
            continue;
        }
        assert_int_equal(ra->status, MIMAS_FIT_OK);
        double Da = slope(lx, ly, nfit) / 2, Dt = slope(lx, ly2, nfit) / 4;
        assert_close(ra->D, Da, 1e-9 * fabs(Da));
        assert_close(rt->D, Dt, 1e-9 * fabs(Dt));
        assert_close(ra->t0, lx[0], 1e-12);
        assert_close(ra->t1, lx[nfit - 1], 1e-12);
        /* the jackknife over the member groups */
        size_t G = size < 16 ? size : 16;
        double Dg[16], mg = 0, ss = 0;
        for (size_t g = 0; g < G; g++) {
            double yy[CT];
            size_t q = 0;
            for (int t = 0; t < CT; t++) {
                double n, mean[3], ax, tr;
                direct_stats(x, k, t, -1, &n, mean, &ax, &tr);
                if (n == 0 || n != (double)size || (fit_from > 0 && !(sqrt(ax) > fit_from)))
                    continue;
                direct_stats(x, k, t, (int)g, &n, mean, &ax, &tr);
                yy[q++] = ax;
            }
            Dg[g] = slope(lx, yy, nfit) / 2;
            mg += Dg[g] / (double)G;
        }
        for (size_t g = 0; g < G; g++)
            ss += (Dg[g] - mg) * (Dg[g] - mg);
        double je = sqrt((G - 1.0) / G * ss);
        assert_close(ra->D_err, je, 1e-7 * je);
    }
    assert_true(fit_from > 0 ? cut > 0 && few > 0 : cut == 0 && few == 0);
    free(x);
    mimas_disperse_free(d);
}

static void test_cohorts(void **state)
{
    (void)state;
    check_cohorts(0);
}

static void test_cohorts_fit_from(void **state)
{
    (void)state;
    /* sigma_axial of the cohorts' complete frames spans 0.09 .. 0.33 */
    check_cohorts(0.16);
}

/* ---- the tube as the default axis; option and data errors ---- */

static void test_tube_axis_and_errors(void **state)
{
    (void)state;
    mimas_disperse_options o;
    memset(&o, 0, sizeof o);
    o.memory = 16u << 20;
    mimas_disperse *d;
    mimas_error err;
    assert_int_equal(mimas_disperse_create(&d, &o, &err), MIMAS_OK);
    mimas_frame f;
    mimas_frame_init(&f);
    for (int t = 0; t < 50; t++) {
        frame_of(&f, 3, 0, t * 0.5);
        f.tube.present = 1;
        f.tube.direction[0] = -2;
        for (int i = 0; i < 3; i++) {
            f.particles.id[i] = i;
            f.particles.pos[i][0] = 0.1 * t * t * (i + 1);
            f.particles.pos[i][1] = 0.01 * t * i;
            f.particles.pos[i][2] = 0.02 * t;
        }
        assert_int_equal(mimas_disperse_add(d, &f, &err), MIMAS_OK);
    }
    assert_int_equal(mimas_disperse_finish(d, &err), MIMAS_OK);
    const mimas_disperse_result *r = mimas_disperse_result_of(d);
    assert_true(r->axis_from_tube);
    assert_close(r->axis.ez[0], -1, 0);
    for (size_t k = 0; k < r->lags; k++) {
        const double *m = r->msd + k * MIMAS_DC_COUNT;
        assert_true(m[MIMAS_DC_AXIAL] == m[MIMAS_DC_X]);
        double yz = m[MIMAS_DC_Y] + m[MIMAS_DC_Z];
        assert_close(m[MIMAS_DC_TRANSVERSE], yz, 1e-14 * yz);
        /* x = a t^2: (x(t+k) - x(t))^2 averaged over t, directly */
        double want = 0;
        for (int t = 0; t + (int)k < 50; t++)
            for (int i = 0; i < 3; i++) {
                double dd = 0.1 * (i + 1) * ((t + (double)k) * (t + (double)k) - (double)t * t);
                want += dd * dd / (3.0 * (50 - (double)k));
            }
        assert_close(m[MIMAS_DC_X], want, 1e-10 * want);
    }
    mimas_disperse_free(d);

    /* one frame is not enough; no memory is too little */
    assert_int_equal(mimas_disperse_create(&d, &o, &err), MIMAS_OK);
    assert_int_equal(mimas_disperse_add(d, &f, &err), MIMAS_OK);
    assert_int_equal(mimas_disperse_finish(d, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "at least two frames"));
    mimas_disperse_free(d);
    o.memory = 6u << 20;
    assert_int_equal(mimas_disperse_create(&d, &o, &err), MIMAS_EUSAGE);
    assert_non_null(strstr(err.msg, "--memory 6291456 bytes leaves nothing"));
    /* 16 MB leave 4 MB: the transforms of 30000 frames need more */
    o.memory = 16u << 20;
    assert_int_equal(mimas_disperse_create(&d, &o, &err), MIMAS_OK);
    for (int t = 0; t < 30000; t++) {
        f.time = t;
        assert_int_equal(mimas_disperse_add(d, &f, &err), MIMAS_OK);
    }
    assert_int_equal(mimas_disperse_finish(d, &err), MIMAS_EUSAGE);
    assert_non_null(strstr(err.msg, "too small for the analysis of 30000 frames"));
    mimas_disperse_free(d);
    mimas_frame_free(&f);
    o.memory = 1u << 20;
    o.has_fit_from = o.has_fit_lags = 1;
    o.fit_hi = 1;
    assert_int_equal(mimas_disperse_create(&d, &o, &err), MIMAS_EUSAGE);
    assert_non_null(strstr(err.msg, "exclude each other"));
    o.has_fit_from = 0;
    const char *bad[] = {"inserted:2:1"};
    o.cohorts = bad;
    o.ncohorts = 1;
    assert_int_equal(mimas_disperse_create(&d, &o, &err), MIMAS_EUSAGE);
    assert_non_null(strstr(err.msg, "--cohort 'inserted:2:1'"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_walkers_drift_removed),
        cmocka_unit_test(test_walkers_with_drift),
        cmocka_unit_test(test_vacf),
        cmocka_unit_test(test_cohorts),
        cmocka_unit_test(test_cohorts_fit_from),
        cmocka_unit_test(test_tube_axis_and_errors),
    };
    return cmocka_run_group_tests(tests, scratch_setup, scratch_teardown);
}
