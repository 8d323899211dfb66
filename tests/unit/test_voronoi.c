/* Per-particle Voronoi values (mimas voronoi) and their grid averages
 * (--weight voronoi): stresses summed with cell volumes give the global
 * stress identity of mimas average, the Shepard mean velocity against a
 * brute-force sum, global solid fractions, the cell list against brute
 * force.  Expected values are computed here. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assert_close.h"
#include "average.h"
#include "cell_list.h"
#include "fields.h"
#include "frac_image.h"
#include "liggghts_set.h"
#include "voronoi.h"

static void load(const char *atoms, const char *pgl, const char *wgl, mimas_frame *f)
{
    mimas_error err;
    mimas_frame_init(f);
    if (liggghts_last_frame(liggghts_data(atoms), pgl ? liggghts_data(pgl) : NULL,
                            wgl ? liggghts_data(wgl) : NULL, f, &err))
        fail_msg("%s", err.msg);
}

static void tessellate(mimas_frame *f, const mimas_voronoi_options *o)
{
    mimas_voronoi *v;
    mimas_error err;
    assert_int_equal(mimas_voronoi_create(&v, o, &err), MIMAS_OK);
    if (mimas_voronoi_frame(v, f, &err))
        fail_msg("%s", err.msg);
    mimas_voronoi_free(v);
}

/* sum over particles with a cell of V_cell sigma, full tensor */
static void volume_stress_sum(const mimas_frame *f, double T[9])
{
    mimas_voronoi_values val;
    mimas_voronoi_values_of(&f->particles, &val);
    assert_non_null(val.volume);
    assert_non_null(val.stress);
    memset(T, 0, 9 * sizeof *T);
    for (size_t k = 0; k < f->particles.n; k++)
        if (!isnan(val.volume[k]))
            for (int m = 0; m < 9; m++)
                T[m] += val.volume[k] * val.stress[9 * k + (size_t)m];
}

static double max_abs(const double *T, int n)
{
    double m = 0;
    for (int k = 0; k < n; k++)
        m = fmax(m, fabs(T[k]));
    return m;
}

/* mimas average --grid none --weight bins (types other than `excluded`):
 * V_box times the contact stress sums. */
static void average_contact_sum(const mimas_frame *f, int32_t excluded, double T[9])
{
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&o.grid, "none", NULL, &err), 0);
    assert_int_equal(mimas_weight_parse(&o.weight, "bins", &err), 0);
    o.grid_none = 1;
    if (excluded) {
        o.types = &excluded;
        o.ntypes = 1;
        o.exclude = 1;
    }
    mimas_average *a;
    assert_int_equal(mimas_average_create(&a, &o, &err), 0);
    if (mimas_average_add(a, f, &err))
        fail_msg("%s", err.msg);
    double S[NSUMS];
    mimas_average_sums(a, 0, S);
    double V = mimas_box_volume(&f->box);
    for (int k = 0; k < 9; k++)
        T[k] = S[S_C + k] * V;
    mimas_average_free(a);
}

/* sum_k V_k sigma_k = sum_k m_k v_k (x) v_k (V = 0) + sum_c f_ij (x) (r_i - r_j)
 * + wall and excluded-particle contacts f (x) (r_i - c): the global identity
 * whose contact part mimas average's --grid none gives (test_average checks
 * that part against a direct sum). */
static void check_identity(const char *atoms, const char *pgl, const char *wgl, int32_t excluded)
{
    mimas_frame f;
    load(atoms, pgl, wgl, &f);
    mimas_voronoi_options o;
    memset(&o, 0, sizeof o);
    o.exclude = &excluded;
    o.nexclude = excluded ? 1 : 0;
    tessellate(&f, &o);
    double got[9], want[9];
    volume_stress_sum(&f, got);
    average_contact_sum(&f, excluded, want);
    const mimas_particles *p = &f.particles;
    for (size_t k = 0; k < p->n; k++) {
        if (excluded && p->type[k] == excluded)
            continue;
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                want[3 * a + b] += p->mass[k] * p->vel[k][a] * p->vel[k][b];
    }
    double scale = max_abs(want, 9);
    assert_true(scale > 0);
    for (int m = 0; m < 9; m++)
        assert_close(got[m], want[m], 1e-12 * scale);
    mimas_frame_free(&f);
}

static void test_identity_triclinic(void **state)
{
    (void)state;
    check_identity("triclinic/dump.triclinic_complete.atom", "triclinic/dump.triclinic_complete.pgl",
                   NULL, 0);
}

static void test_identity_periodic(void **state)
{
    (void)state;
    check_identity("periodic_box/dump.periodic.atom.gz", "periodic_box/dump.periodic.pgl.gz", NULL,
                   0);
}

/* the hopper: mesh-wall contacts, and glued type-2 particles excluded (their
 * contacts act on the others as wall contacts at the contact point) */
static void test_identity_hopper_walls(void **state)
{
    (void)state;
    check_identity("hopper_walls/dump.hopper.atom.gz", "hopper_walls/dump.hopper.pgl.gz",
                   "hopper_walls/dump.hopper.wgl", 2);
}

/* --velocity-width W: the kinetic part becomes sum m (v - V)(x)(v - V) with V
 * Shepard's mean sum_j v_j g_j / sum_j g_j, g the Gaussian of width W
 * cut at 3 W (weight.h); V computed here over all pairs. */
static void test_shepard_mean_velocity(void **state)
{
    (void)state;
    const double w = 0.003, R = 3 * w, shift = 0.0; /* the plain cut */
    mimas_frame f;
    load("triclinic/dump.triclinic_complete.atom", "triclinic/dump.triclinic_complete.pgl", NULL,
         &f);
    mimas_voronoi_options o;
    memset(&o, 0, sizeof o);
    const mimas_particles *p = &f.particles;
    double (*plain)[9] = malloc(sizeof *plain * p->n);
    mimas_voronoi_values val;
    tessellate(&f, &o);
    mimas_voronoi_values_of(p, &val);
    for (size_t k = 0; k < p->n; k++)
        for (int m = 0; m < 9; m++)
            plain[k][m] = val.volume[k] * val.stress[9 * k + (size_t)m];
    o.velocity_width = w;
    tessellate(&f, &o);
    mimas_voronoi_values_of(p, &val);
    double largest = 0;
    for (size_t k = 0; k < p->n; k++) {
        double g = 0, gv[3] = {0, 0, 0};
        for (size_t j = 0; j < p->n; j++) {
            double d[3] = {p->pos[k][0] - p->pos[j][0], p->pos[k][1] - p->pos[j][1],
                           p->pos[k][2] - p->pos[j][2]};
            min_image_frac(&f.box, d);
            double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (r2 >= R * R)
                continue;
            double e = exp(-r2 / (2 * w * w)) - shift;
            g += e;
            for (int m = 0; m < 3; m++)
                gv[m] += e * p->vel[j][m];
        }
        double u[3], *v = p->vel[k];
        for (int m = 0; m < 3; m++)
            u[m] = v[m] - gv[m] / g;
        /* V_k sigma_k changes by m ((v - V)(x)(v - V) - v (x) v) */
        double scale = max_abs(plain[k], 9);
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                double diff = p->mass[k] * (u[a] * u[b] - v[a] * v[b]);
                double got = val.volume[k] * val.stress[9 * k + (size_t)(3 * a + b)] -
                             plain[k][3 * a + b];
                assert_close(got, diff, 1e-12 * scale + 1e-12 * fabs(diff));
                largest = fmax(largest, fabs(diff) / scale);
            }
    }
    assert_true(largest > 1e-6); /* the velocities matter at this tolerance */
    free(plain);
    /* a Gaussian reaching beyond half the periodic box is refused */
    o.velocity_width = 0.004;
    mimas_voronoi *v;
    mimas_error err;
    assert_int_equal(mimas_voronoi_create(&v, &o, &err), MIMAS_OK);
    assert_int_equal(mimas_voronoi_frame(v, &f, &err), MIMAS_EUSAGE);
    mimas_voronoi_free(v);
    mimas_frame_free(&f);
}

/* The columns: units, NaN for excluded types, nu = V_p / V_cell, and the
 * global solid fraction of a periodic packing. */
static void test_columns_and_global_nu(void **state)
{
    (void)state;
    mimas_frame f;
    load("hopper_walls/dump.hopper.atom.gz", NULL, NULL, &f);
    mimas_voronoi_options o;
    memset(&o, 0, sizeof o);
    const int32_t two = 2;
    o.exclude = &two;
    o.nexclude = 1;
    tessellate(&f, &o);
    const mimas_particles *p = &f.particles;
    mimas_voronoi_values val;
    mimas_voronoi_values_of(p, &val);
    assert_non_null(val.volume);
    assert_non_null(val.nu);
    assert_non_null(val.faces);
    assert_non_null(val.surface);
    assert_null(val.stress); /* no contact data */
    size_t touching = 0;
    for (size_t k = 0; k < p->n; k++) {
        if (p->type[k] == 2) {
            assert_true(isnan(val.volume[k]) && isnan(val.nu[k]) && isnan(val.faces[k]));
            continue;
        }
        double vp = 4.0 / 3.0 * M_PI * pow(p->radius[k], 3);
        assert_close(val.nu[k], vp / val.volume[k], 1e-15);
        assert_true(val.faces[k] >= 4);
        touching += val.surface[k] == MIMAS_VORO_TOUCHES_WALL;
    }
    assert_true(touching > 0);
    for (size_t e = 0; e < p->n_extra; e++)
        if (!strcmp(p->extra[e].name, MIMAS_VORONOI_VOLUME))
            assert_string_equal(p->extra[e].unit, "m3");
    mimas_frame_free(&f);

    load("periodic_box/dump.periodic.atom.gz", NULL, NULL, &f);
    o.nexclude = 0;
    o.radical = 1;
    tessellate(&f, &o);
    p = &f.particles;
    mimas_voronoi_values_of(p, &val);
    double vp = 0, vc = 0;
    for (size_t k = 0; k < p->n; k++) {
        vp += 4.0 / 3.0 * M_PI * pow(p->radius[k], 3);
        vc += val.volume[k];
    }
    double V = mimas_box_volume(&f.box);
    assert_close(vp / vc, vp / V, 1e-10 * vp / V);
    mimas_frame_free(&f);
}

/* --weight voronoi on a grid: the cells of a Cartesian bin grid hold the
 * particles whose centres they hold; nu = sum V_p / sum V_cell over those,
 * stress = sum V_cell sigma / sum V_cell; voronoi:w=W weighs them with a
 * Gaussian instead. */
static void test_voronoi_weight(void **state)
{
    (void)state;
    mimas_frame f;
    load("periodic_box/dump.periodic.atom.gz", "periodic_box/dump.periodic.pgl.gz", NULL, &f);
    mimas_voronoi_options vo;
    memset(&vo, 0, sizeof vo);
    vo.radical = 1;
    tessellate(&f, &vo);
    const mimas_particles *p = &f.particles;
    mimas_voronoi_values val;
    mimas_voronoi_values_of(p, &val);
    const mimas_box *b = &f.box;
    char grid[256];
    snprintf(grid, sizeof grid, "x=%.17g:%.17g:2,z=%.17g:%.17g:3", b->lo[0], b->hi[0], b->lo[2],
             b->hi[2]);
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&o.grid, grid, NULL, &err), 0);
    assert_int_equal(mimas_weight_parse(&o.weight, "voronoi", &err), 0);
    mimas_average *a;
    assert_int_equal(mimas_average_create(&a, &o, &err), 0);
    assert_int_equal(mimas_average_add(a, &f, &err), 0);
    size_t nf = mimas_fields_count(), cells = 6;
    double *fields = malloc(cells * nf * sizeof *fields);
    assert_int_equal(mimas_average_fields(a, fields, NULL, NULL), 0);
    size_t inu = 0, isxz = 0, ip = 0;
    for (size_t k = 0; k < nf; k++) {
        const char *n = mimas_field_name(k, 0);
        if (n && !strcmp(n, "nu"))
            inu = k;
        if (n && !strcmp(n, "stress_xz"))
            isxz = k;
        if (n && !strcmp(n, "p"))
            ip = k;
    }
    for (size_t c = 0; c < cells; c++) {
        double lo[3], hi[3], vp = 0, vc = 0, sxz = 0, tr = 0;
        mimas_grid_cell_bounds(mimas_average_grid(a), c, lo, hi);
        for (size_t k = 0; k < p->n; k++) {
            const double *x = p->pos[k];
            if (x[0] < lo[0] || x[0] >= hi[0] || x[2] < lo[2] || x[2] >= hi[2])
                continue;
            const double *s = &val.stress[9 * k];
            vp += 4.0 / 3.0 * M_PI * pow(p->radius[k], 3);
            vc += val.volume[k];
            sxz += val.volume[k] * 0.5 * (s[2] + s[6]);
            tr += val.volume[k] * (s[0] + s[4] + s[8]) / 3.0;
        }
        assert_true(vc > 0);
        assert_close(fields[c * nf + inu], vp / vc, 1e-12);
        assert_close(fields[c * nf + isxz], sxz / vc, 1e-9 * fabs(tr / vc));
        assert_close(fields[c * nf + ip], tr / vc, 1e-9 * fabs(tr / vc));
    }
    mimas_average_free(a);
    /* voronoi:w=W: the same ratios with the Gaussian g of each particle at the
     * cell centre (cut at 3 W; one image within reach), integrated over y, which
     * the grid does not resolve: int e^{-(rho^2 + y^2)/2W^2} dy over the cut sphere
     * = sqrt(2 pi) W e^{-rho^2/2W^2} erf(sqrt(9 W^2 - rho^2) / (sqrt 2 W)) */
    const double w = 0.002;
    assert_int_equal(mimas_weight_parse(&o.weight, "voronoi:w=0.002", &err), 0);
    assert_int_equal(mimas_average_create(&a, &o, &err), 0);
    assert_int_equal(mimas_average_add(a, &f, &err), 0);
    assert_int_equal(mimas_average_fields(a, fields, NULL, NULL), 0);
    for (size_t c = 0; c < cells; c++) {
        double ctr[3], vp = 0, vc = 0, tr = 0;
        mimas_grid_cell_centre(mimas_average_grid(a), c, ctr);
        for (size_t k = 0; k < p->n; k++) {
            double d[3] = {ctr[0] - p->pos[k][0], 0.0, ctr[2] - p->pos[k][2]};
            min_image_frac(b, d);
            double r2 = d[0] * d[0] + d[2] * d[2];
            if (r2 >= 9 * w * w)
                continue;
            double g = exp(-r2 / (2 * w * w)) * erf(sqrt(9 * w * w - r2) / (M_SQRT2 * w));
            const double *s = &val.stress[9 * k];
            vp += g * 4.0 / 3.0 * M_PI * pow(p->radius[k], 3);
            vc += g * val.volume[k];
            tr += g * val.volume[k] * (s[0] + s[4] + s[8]) / 3.0;
        }
        assert_true(vc > 0);
        assert_close(fields[c * nf + inu], vp / vc, 1e-12);
        assert_close(fields[c * nf + ip], tr / vc, 1e-9 * fabs(tr / vc));
    }
    free(fields);
    mimas_average_free(a);
    /* without the columns: an error that says what to do */
    mimas_frame g;
    load("periodic_box/dump.periodic.atom.gz", NULL, NULL, &g);
    assert_int_equal(mimas_average_create(&a, &o, &err), 0);
    assert_int_equal(mimas_average_add(a, &g, &err), MIMAS_EMISSING);
    assert_non_null(strstr(err.msg, "mimas voronoi -o"));
    mimas_average_free(a);
    mimas_frame_free(&g);
    mimas_frame_free(&f);
}

typedef struct count_ctx {
    size_t n;
    double d2;
} count_ctx;

static void count_one(void *user, size_t j, const double d[3], double d2)
{
    (void)j;
    (void)d;
    count_ctx *c = user;
    c->n++;
    c->d2 += d2;
}

/* The cell list visits exactly the particles a brute-force minimum-image
 * search finds within the radius (triclinic periodic, and a box periodic
 * along one axis with points outside it along the others). */
static void test_cell_list(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const size_t n = 3000;
    double (*pos)[3] = malloc(sizeof *pos * n);
    mimas_box boxes[2] = {{{0, -1, 0}, {3, 1, 2.5}, 0.7, -0.4, 0.3, {1, 1, 1}},
                          {{0, 0, 0}, {3, 2, 2}, 0, 0, 0, {0, 1, 0}}};
    for (int t = 0; t < 2; t++) {
        const mimas_box *b = &boxes[t];
        for (size_t k = 0; k < n; k++) {
            double s[3] = {gsl_rng_uniform(rng), gsl_rng_uniform(rng), gsl_rng_uniform(rng)};
            for (int d = 0; d < 3; d++)
                s[d] = 1.4 * s[d] - 0.2; /* some outside the box */
            pos[k][0] = b->lo[0] + s[0] * (b->hi[0] - b->lo[0]) + s[1] * b->xy + s[2] * b->xz;
            pos[k][1] = b->lo[1] + s[1] * (b->hi[1] - b->lo[1]) + s[2] * b->yz;
            pos[k][2] = b->lo[2] + s[2] * (b->hi[2] - b->lo[2]);
        }
        mimas_cell_list cl;
        mimas_cell_list_init(&cl);
        mimas_error err;
        const double R = 0.45;
        assert_int_equal(mimas_cell_list_build(&cl, b, n, (const double (*)[3])pos, NULL, R, &err),
                         MIMAS_OK);
        for (size_t k = 0; k < n; k += 7) {
            count_ctx got = {0, 0};
            mimas_cell_list_query(&cl, pos[k], (const double (*)[3])pos, count_one, &got);
            count_ctx want = {0, 0};
            for (size_t j = 0; j < n; j++) {
                double d[3] = {pos[k][0] - pos[j][0], pos[k][1] - pos[j][1],
                               pos[k][2] - pos[j][2]};
                min_image_frac(b, d);
                double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                if (d2 < R * R)
                    want.n++, want.d2 += d2;
            }
            assert_int_equal(got.n, want.n);
            assert_close(got.d2, want.d2, 1e-12);
        }
        /* too large a radius for the periodic box */
        assert_int_equal(mimas_cell_list_build(&cl, b, n, (const double (*)[3])pos, NULL, 1.0,
                                               &err), MIMAS_EUSAGE);
        mimas_cell_list_free(&cl);
    }
    free(pos);
    gsl_rng_free(rng);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_identity_triclinic),
        cmocka_unit_test(test_identity_periodic),
        cmocka_unit_test(test_identity_hopper_walls),
        cmocka_unit_test(test_shepard_mean_velocity),
        cmocka_unit_test(test_columns_and_global_nu),
        cmocka_unit_test(test_voronoi_weight),
        cmocka_unit_test(test_cell_list),
    };
    return cmocka_run_group_tests_name("voronoi", tests, NULL, NULL);
}
