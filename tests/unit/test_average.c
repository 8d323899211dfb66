/* mimas average: conservation identities and analytic fields, with expected
 * values computed here independently of the library (docs/theory.md §6). */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_integration.h>
#include <gsl/gsl_rng.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assert_close.h"
#include "average.h"
#include "fields.h"
#include "frac_image.h"
#include "liggghts_set.h"
#include "reader.h"

static const char *data(const char *rel)
{
    return liggghts_data(rel);
}

/* The last frame of a LIGGGHTS data set. */
static void last_frame(const char *atoms, const char *pgl, mimas_frame *f)
{
    mimas_error err;
    if (liggghts_last_frame(atoms, pgl, NULL, f, &err))
        fail_msg("%s", err.msg);
}

/* sum over contacts of f (x) b, full tensor T[3a+b] = f_a b_b */
static void direct_contact_sum(const mimas_frame *f, double T[9])
{
    memset(T, 0, 9 * sizeof *T);
    const mimas_particles *p = &f->particles;
    for (size_t k = 0; k < f->contacts.n; k++) {
        size_t i = f->contacts.i[k], j = f->contacts.j[k];
        double d[3] = {p->pos[i][0] - p->pos[j][0], p->pos[i][1] - p->pos[j][1],
                       p->pos[i][2] - p->pos[j][2]};
        min_image_frac(&f->box, d);
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                T[3 * a + b] += f->contacts.force[k][a] * d[b];
    }
}

static mimas_average *average_frame(const mimas_frame *f, const char *grid, const char *weight)
{
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&o.grid, grid, NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_weight_parse(&o.weight, weight, &err), MIMAS_OK);
    o.grid_none = !strcmp(grid, "none");
    mimas_average *a;
    assert_int_equal(mimas_average_create(&a, &o, &err), MIMAS_OK);
    if (mimas_average_add(a, f, &err))
        fail_msg("%s", err.msg);
    return a;
}

static double max_abs(const double *T, int n)
{
    double m = 0;
    for (int k = 0; k < n; k++)
        m = fmax(m, fabs(T[k]));
    return m;
}

/* cstress of --grid none equals (1/V) sum f (x) (r_i - r_j); and the sum over
 * a bin grid of V_cell cstress equals the same total (exact segment
 * splitting, periodic images included). */
static void check_stress_identity(const char *atoms, const char *pgl)
{
    mimas_frame f;
    mimas_frame_init(&f);
    last_frame(atoms, pgl, &f);
    double T[9];
    direct_contact_sum(&f, T);
    double V = (f.box.hi[0] - f.box.lo[0]) * (f.box.hi[1] - f.box.lo[1]) *
               (f.box.hi[2] - f.box.lo[2]);
    double scale = max_abs(T, 9);
    assert_true(scale > 0);
    mimas_average *a = average_frame(&f, "none", "bins");
    double S[NSUMS + 1];
    /* the count callers size their buffer by, and no value written past it */
    assert_int_equal(mimas_average_sums_count(), NSUMS);
    S[NSUMS] = -12345.0;
    mimas_average_sums(a, 0, S);
    assert_true(S[NSUMS] == -12345.0);
    for (int k = 0; k < 9; k++)
        assert_close(S[S_C + k] * V, T[k], 1e-12 * scale);
    mimas_average_free(a);

    char grid[512];
    snprintf(grid, sizeof grid, "x=%.17g:%.17g:3,y=%.17g:%.17g:4,z=%.17g:%.17g:5", f.box.lo[0],
             f.box.hi[0], f.box.lo[1], f.box.hi[1], f.box.lo[2], f.box.hi[2]);
    a = average_frame(&f, grid, "bins");
    double total[9] = {0};
    const mimas_grid *g = mimas_average_grid(a);
    for (size_t c = 0; c < mimas_grid_cells(g); c++) {
        mimas_average_sums(a, c, S);
        for (int k = 0; k < 9; k++)
            total[k] += S[S_C + k] * mimas_grid_cell_volume(g, c);
    }
    for (int k = 0; k < 9; k++)
        assert_close(total[k], T[k], 1e-12 * scale);
    mimas_average_free(a);
    mimas_frame_free(&f);
}

static void test_stress_identity_triclinic(void **state)
{
    (void)state;
    check_stress_identity(data("triclinic/dump.triclinic_complete.atom"),
                          data("triclinic/dump.triclinic_complete.pgl"));
}

static void test_stress_identity_periodic(void **state)
{
    (void)state;
    check_stress_identity(data("periodic_box/dump.periodic.atom.gz"),
                          data("periodic_box/dump.periodic.pgl.gz"));
}

/* LIGGGHTS' compute stress/atom: per atom -m v (x) v - 1/2 sum (x1 - x2) (x) F1
 * (stress times volume, compression negative; tests/data/liggghts/README.md),
 * so -sum_atoms (c_stress + m v v) = sum_contacts (x1 - x2) (x) F1; mimas'
 * V cstress holds F1 (x) (x1 - x2), the transpose.  6 printed digits. */
static void test_matches_liggghts_stress_atom(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    last_frame(data("periodic_box/dump.periodic.atom.gz"),
               data("periodic_box/dump.periodic.pgl.gz"), &f);
    const mimas_particles *p = &f.particles;
    assert_string_equal(p->extra[0].name, "c_stress");
    static const int comp[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
    double pair[6] = {0};
    for (size_t i = 0; i < p->n; i++)
        for (int c = 0; c < 6; c++)
            pair[c] -= p->extra[0].data[6 * i + (size_t)c] +
                       p->mass[i] * p->vel[i][comp[c][0]] * p->vel[i][comp[c][1]];
    mimas_average *a = average_frame(&f, "none", "bins");
    double S[NSUMS];
    mimas_average_sums(a, 0, S);
    double V = mimas_box_volume(&f.box);
    double scale = max_abs(pair, 6);
    for (int c = 0; c < 6; c++) {
        int x = comp[c][0], y = comp[c][1];
        /* (x1 - x2)_x F_y is mimas' [y][x] entry */
        assert_close(S[S_C + 3 * y + x] * V, pair[c], 2e-5 * scale);
    }
    /* the kinetic part: sum m (v - V)(x)(v - V) / V_box, V the mass-weighted mean */
    double M = 0, P[3] = {0};
    for (size_t i = 0; i < p->n; i++) {
        M += p->mass[i];
        for (int d = 0; d < 3; d++)
            P[d] += p->mass[i] * p->vel[i][d];
    }
    double K[6] = {0};
    for (size_t i = 0; i < p->n; i++)
        for (int c = 0; c < 6; c++)
            K[c] += p->mass[i] * (p->vel[i][comp[c][0]] - P[comp[c][0]] / M) *
                    (p->vel[i][comp[c][1]] - P[comp[c][1]] / M) / V;
    double out[128];
    assert_int_equal(mimas_average_fields(a, out, NULL, NULL), 0);
    /* kstress_xx .. kstress_yz follow the 6 stress columns */
    size_t ks = 0;
    while (strcmp(mimas_field_name(ks, 0) ? mimas_field_name(ks, 0) : "", "kstress_xx"))
        ks++;
    double kscale = max_abs(K, 6);
    for (int c = 0; c < 6; c++)
        assert_close(out[ks + (size_t)c], K[c], 1e-12 * kscale);
    mimas_average_free(a);
    mimas_frame_free(&f);
}

/* Column of a field by name. */
static size_t col(const char *name, int cyl)
{
    for (size_t k = 0; k < mimas_fields_count(); k++) {
        const char *n = mimas_field_name(k, cyl);
        if (n && !strcmp(n, name))
            return k;
    }
    fail_msg("no field %s", name);
    return 0;
}

/* A frame of particles given by the test, with velocities v(x). */
static void make_frame(mimas_frame *f, size_t n, const double (*pos)[3], double R,
                       void (*vel)(const double x[3], double v[3]), const mimas_box *box)
{
    mimas_error err;
    mimas_frame_clear(f);
    mimas_table_set_present(&f->particles, &mimas_particles_desc,
                            MIMAS_P_RADIUS | MIMAS_P_MASS | MIMAS_P_VEL, &err);
    mimas_table_resize(&f->particles, &mimas_particles_desc, n, &err);
    for (size_t k = 0; k < n; k++) {
        f->particles.id[k] = (int64_t)k + 1;
        memcpy(f->particles.pos[k], pos[k], sizeof pos[k]);
        f->particles.radius[k] = R;
        f->particles.mass[k] = 1000.0 * 4.0 / 3.0 * M_PI * R * R * R;
        vel(pos[k], f->particles.vel[k]);
    }
    f->box = *box;
}

static void still(const double x[3], double v[3])
{
    (void)x;
    v[0] = v[1] = v[2] = 0;
}

/* Points at the centres of an m x m x m simple cubic lattice of spacing a. */
static double (*cubic_lattice(int m, double a, size_t *n))[3]
{
    double (*pos)[3] = malloc(sizeof *pos * (size_t)(m * m * m));
    *n = 0;
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++)
            for (int k = 0; k < m; k++) {
                pos[*n][0] = (i + 0.5) * a;
                pos[*n][1] = (j + 0.5) * a;
                pos[*n][2] = (k + 0.5) * a;
                (*n)++;
            }
    return pos;
}

/* The time average of n frames is the sum over them divided by n, to the bit, whether n is
 * a power of two (the reciprocal's product) or not (the quotient): against the sums in
 * the average's packed state (frames, grid, then the cells' sums) divided here; and of n
 * copies of one frame, that frame's sums to a few ulp. */
static void test_sums_over_frames(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    last_frame(data("periodic_box/dump.periodic.atom.gz"),
               data("periodic_box/dump.periodic.pgl.gz"), &f);
    const char *grid = "x=0:0.0293135:4,y=0:0.0293135:3,z=0:0.0293135:3";
    mimas_average *one = average_frame(&f, grid, "gauss:w=0.004");
    size_t cells = mimas_grid_cells(mimas_average_grid(one));
    mimas_bytes packed = {0};
    mimas_error err;
    for (int n = 1; n <= 8; n++) {
        mimas_average *a = average_frame(&f, grid, "gauss:w=0.004");
        for (int k = 1; k < n; k++) {
            f.step++; /* another frame, the same particles */
            assert_int_equal(mimas_average_add(a, &f, &err), MIMAS_OK);
        }
        assert_int_equal(mimas_average_pack(a, &packed, &err), MIMAS_OK);
        const unsigned char *raw = packed.data + sizeof(uint64_t) + sizeof(mimas_grid);
        for (size_t c = 0; c < cells; c++) {
            double S1[NSUMS], Sn[NSUMS];
            mimas_average_sums(one, c, S1);
            mimas_average_sums(a, c, Sn);
            for (int k = 0; k < NSUMS; k++) {
                double sum;
                memcpy(&sum, raw + (c * NSUMS + (size_t)k) * sizeof sum, sizeof sum);
                assert_true(Sn[k] == sum / n);
                assert_true(fabs(Sn[k] - S1[k]) <= 8 * DBL_EPSILON * fabs(S1[k]));
            }
        }
        mimas_average_free(a);
    }
    mimas_bytes_free(&packed);
    mimas_average_free(one);
    mimas_frame_free(&f);
}

/* Simple cubic packing of touching spheres (R = a/2): nu = pi/6 in every cell
 * whose edges are whole multiples of a, wherever the cell edges cut. */
static void test_simple_cubic_solid_fraction(void **state)
{
    (void)state;
    const int m = 10;
    const double a = 0.002;
    size_t n;
    double (*pos)[3] = cubic_lattice(m, a, &n);
    mimas_box box = {{0, 0, 0}, {m * a, m * a, m * a}, 0, 0, 0, {1, 1, 1}};
    mimas_frame f;
    mimas_frame_init(&f);
    make_frame(&f, n, (const double (*)[3])pos, 0.5 * a, still, &box);
    /* cells of 2a x 2a x 2a, starting 0.3a off the lattice: they cut spheres */
    char grid[256];
    snprintf(grid, sizeof grid, "x=%.17g:%.17g:4,y=%.17g:%.17g:4,z=%.17g:%.17g:4", 0.3 * a,
             8.3 * a, 0.3 * a, 8.3 * a, 0.3 * a, 8.3 * a);
    mimas_average *av = average_frame(&f, grid, "bins");
    double S[NSUMS];
    for (size_t c = 0; c < 64; c++) {
        mimas_average_sums(av, c, S);
        assert_close(S[S_V], M_PI / 6.0, 1e-12);
    }
    mimas_average_free(av);
    mimas_frame_free(&f);
    free(pos);
}

/* sum over the cells of V_cell times primary sum q (the grid integral). */
static double grid_integral(const mimas_average *av, int q)
{
    const mimas_grid *g = mimas_average_grid(av);
    double total = 0, S[NSUMS];
    for (size_t c = 0; c < mimas_grid_cells(g); c++) {
        mimas_average_sums(av, c, S);
        total += S[q] * mimas_grid_cell_volume(g, c);
    }
    return total;
}

/* n particles at random in the 1 cm cube, with velocities v(x). */
static double random_cloud(mimas_frame *f, size_t n, gsl_rng *rng,
                           void (*vel)(const double x[3], double v[3]), double (*pos)[3])
{
    for (size_t k = 0; k < n; k++)
        for (int d = 0; d < 3; d++)
            pos[k][d] = 0.01 * gsl_rng_uniform(rng);
    mimas_box box = {{0, 0, 0}, {0.01, 0.01, 0.01}, 0, 0, 0, {0, 0, 0}};
    make_frame(f, n, (const double (*)[3])pos, 0.0005, vel, &box);
    double total = 0;
    for (size_t k = 0; k < n; k++)
        total += f->particles.mass[k];
    return total;
}

/* The plain cut Gaussian written out here: e^{-r^2/2w^2} inside C w, normalised by
 * the ball integral (2 pi w^2)^{3/2} (erf(C/sqrt 2) - sqrt(2/pi) C e^{-C^2/2}). */
static double test_gauss(double r2, double w, double C)
{
    if (r2 >= C * C * w * w)
        return 0.0;
    double ball = pow(2 * M_PI * w * w, 1.5) * (erf(C / M_SQRT2) -
                                               sqrt(2 / M_PI) * C * exp(-0.5 * C * C));
    return exp(-r2 / (2 * w * w)) / ball;
}

/* A Gaussian x-y-z grid integrates rho to the total mass: exactly the sum of the
 * kernel over the cell centres computed here, and the mass to the grid's
 * resolution (the plain cut's jump limits a midpoint sum). */
static void test_gauss_integrates_mass(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const size_t n = 200;
    double (*pos)[3] = malloc(sizeof *pos * n);
    mimas_frame f;
    mimas_frame_init(&f);
    double total = random_cloud(&f, n, rng, still, pos);
    /* w = 1 mm, the default cutoff 3 w: the grid reaches 3 w beyond the box,
     * spacing w/3 */
    const double lo = -0.0035, hi = 0.0135, w = 0.001;
    const int m = 51;
    mimas_average *av = average_frame(&f, "x=-0.0035:0.0135:51,y=-0.0035:0.0135:51,"
                                          "z=-0.0035:0.0135:51", "gauss:w=0.001");
    double h = (hi - lo) / m, sum = 0;
    for (size_t k = 0; k < n; k++)
        for (int i = 0; i < m; i++)
            for (int j = 0; j < m; j++)
                for (int l = 0; l < m; l++) {
                    double c[3] = {lo + (i + 0.5) * h, lo + (j + 0.5) * h, lo + (l + 0.5) * h};
                    double r2 = 0;
                    for (int d = 0; d < 3; d++)
                        r2 += (c[d] - pos[k][d]) * (c[d] - pos[k][d]);
                    sum += f.particles.mass[k] * test_gauss(r2, w, 3.0) * h * h * h;
                }
    double got = grid_integral(av, S_M);
    assert_close(got, sum, 1e-12 * total);
    assert_close(got, total, 1e-4 * total);
    mimas_average_free(av);
    /* the shifted kernel is continuous: the midpoint sum is closer */
    av = average_frame(&f, "x=-0.0035:0.0135:51,y=-0.0035:0.0135:51,z=-0.0035:0.0135:51",
                       "gauss:w=0.001,shift");
    assert_close(grid_integral(av, S_M), total, 1e-6 * total);
    mimas_average_free(av);
    mimas_frame_free(&f);
    free(pos);
    gsl_rng_free(rng);
}

/* The contact stress on an x-y-z grid is f (x) b times the exact line integral at
 * each cell centre (mimas_kernel_line, itself checked against quadrature in
 * test_weight), for branches shorter and longer than w, both kernels, cutoffs 2.5 to 5
 * and lengths on both sides of each change of the quadrature rule (docs/fields.md:
 * 8 nodes up to w (0.75 w beyond cutoff 3), 10 up to 1.5 w, 12 up to 2 w, then pieces):
 * the documented relative error, 3e-16, with room for rounding. */
static void test_gauss_contact_cells(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const char *specs[4] = {"gauss:w=0.001", "gauss:w=0.0008,shift,cutoff=2.5",
                            "gauss:w=0.001,cutoff=5", "gauss:w=0.0009,cutoff=4"};
    const double lens[12] = {0.0003, 0.001, 0.0019, 0.0042, 0.00074, 0.00076, 0.00099,
                             0.00101, 0.00149, 0.00151, 0.00201, 0.0031};
    for (int k = 0; k < 4; k++)
        for (int l = 0; l < 12; l++) {
            double pos[2][3];
            for (int d = 0; d < 3; d++)
                pos[0][d] = 0.004 + 0.002 * gsl_rng_uniform(rng);
            double dir[3], nn = 0;
            for (int d = 0; d < 3; d++) {
                dir[d] = gsl_rng_uniform(rng) - 0.5;
                nn += dir[d] * dir[d];
            }
            for (int d = 0; d < 3; d++)
                pos[1][d] = pos[0][d] + lens[l] * dir[d] / sqrt(nn);
            mimas_box box = {{0, 0, 0}, {0.01, 0.01, 0.01}, 0, 0, 0, {0, 0, 0}};
            mimas_frame f;
            mimas_frame_init(&f);
            make_frame(&f, 2, (const double (*)[3])pos, 0.0005, still, &box);
            mimas_error err;
            mimas_table_set_present(&f.contacts, &mimas_contacts_desc, MIMAS_C_FORCE, &err);
            mimas_table_resize(&f.contacts, &mimas_contacts_desc, 1, &err);
            f.has_contacts = 1;
            f.contacts.i[0] = 1;
            f.contacts.j[0] = 0;
            double F[3] = {0.3, -0.7, 1.1};
            memcpy(f.contacts.force[0], F, sizeof F);
            mimas_average *av = average_frame(&f, "x=0:0.01:23,y=0:0.01:21,z=0:0.01:25", specs[k]);
            mimas_weight wt;
            assert_int_equal(mimas_weight_parse(&wt, specs[k], &err), 0);
            const mimas_grid *g = mimas_average_grid(av);
            double S[NSUMS], peak = wt.coef, bv[3];
            for (int d = 0; d < 3; d++)
                bv[d] = pos[1][d] - pos[0][d];
            for (size_t c = 0; c < mimas_grid_cells(g); c++) {
                double ctr[3], dd[3];
                mimas_grid_cell_centre(g, c, ctr);
                for (int d = 0; d < 3; d++)
                    dd[d] = ctr[d] - pos[0][d];
                double psi = mimas_kernel_line(&wt, dd, bv);
                mimas_average_sums(av, c, S);
                /* |f (x) b| ~ 1e-3 N m */
                assert_close(S[S_C + 0 * 3 + 1], F[0] * bv[1] * psi, 1e-17 * peak);
                assert_close(S[S_C + 2 * 3 + 2], F[2] * bv[2] * psi, 1e-17 * peak);
            }
            mimas_average_free(av);
            mimas_frame_free(&f);
        }
    gsl_rng_free(rng);
}

/* The test's own marginal of the plain cut Gaussian over x and y:
 * int 2 pi rho phi(sqrt(z^2 + rho^2)) drho, by GSL. */
static double MZ_W, MZ_Z;
static double disc_f(double rho, void *p)
{
    (void)p;
    return 2 * M_PI * rho * test_gauss(MZ_Z * MZ_Z + rho * rho, MZ_W, 3.0);
}

static double test_marginal1(double z, double w)
{
    if (fabs(z) >= 3 * w)
        return 0.0;
    MZ_W = w;
    MZ_Z = z;
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
    gsl_function F = {disc_f, NULL};
    double v, e;
    gsl_integration_qag(&F, 0, sqrt(9 * w * w - z * z), 1e-16, 1e-13, 200, 6, ws, &v, &e);
    gsl_integration_workspace_free(ws);
    return v;
}

/* A z profile integrates the kernel over x and y (all of space, with the periodic
 * images along z only): rho(z) = sum m phi_z(z - z_i) / (Lx Ly), phi_z the kernel's
 * marginal computed here; the same as the x-y average of the x-y-z field (to the
 * resolution of a midpoint sum over x and y). */
static void test_gauss_profile_is_marginal(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const size_t n = 120;
    double (*pos)[3] = malloc(sizeof *pos * n);
    mimas_frame f;
    mimas_frame_init(&f);
    double total = random_cloud(&f, n, rng, still, pos);
    f.box.periodic[0] = f.box.periodic[1] = f.box.periodic[2] = 1;
    const double w = 0.0015, L = 0.01;
    mimas_average *av = average_frame(&f, "z=0:0.01:10", "gauss:w=0.0015");
    double S[NSUMS];
    for (int c = 0; c < 10; c++) {
        double z = (c + 0.5) * 0.001, expect = 0;
        for (size_t k = 0; k < n; k++)
            for (int img = -1; img <= 1; img++)
                expect += f.particles.mass[k] * test_marginal1(z - pos[k][2] - img * L, w);
        expect /= L * L;
        mimas_average_sums(av, (size_t)c, S);
        assert_close(S[S_M], expect, 1e-12 * total / (L * L * L));
    }
    /* the x-y average of the x-y-z field at the same heights */
    mimas_average *av3 = average_frame(&f, "x=0:0.01:60,y=0:0.01:60,z=0:0.01:10",
                                       "gauss:w=0.0015");
    for (int c = 0; c < 10; c++) {
        double mean = 0;
        for (size_t k = 0; k < 3600; k++) {
            mimas_average_sums(av3, (size_t)c * 3600 + k, S);
            mean += S[S_M] / 3600;
        }
        mimas_average_sums(av, (size_t)c, S);
        assert_close(mean, S[S_M], 2e-4 * S[S_M]);
    }
    mimas_average_free(av3);
    mimas_average_free(av);
    mimas_frame_free(&f);
    free(pos);
    gsl_rng_free(rng);
}

/* Rigid rotation v = Omega x r about the z axis: on a cylindrical grid
 * v_phi = Omega rho and omega = Omega for particles on the ring centres. */
static const double OMEGA = 0.7;
static void rotation(const double x[3], double v[3])
{
    v[0] = -OMEGA * x[1];
    v[1] = OMEGA * x[0];
    v[2] = 0;
}

static void test_rigid_rotation(void **state)
{
    (void)state;
    const int rings = 5, per_ring = 40;
    double (*pos)[3] = malloc(sizeof *pos * rings * per_ring);
    size_t n = 0;
    for (int r = 0; r < rings; r++)
        for (int k = 0; k < per_ring; k++) {
            double rho = 0.01 * (r + 0.5), th = 2 * M_PI * (k + 0.3) / per_ring;
            pos[n][0] = rho * cos(th);
            pos[n][1] = rho * sin(th);
            pos[n][2] = 0.005;
            n++;
        }
    mimas_box box = {{-0.06, -0.06, 0}, {0.06, 0.06, 0.01}, 0, 0, 0, {0, 0, 0}};
    mimas_frame f;
    mimas_frame_init(&f);
    /* R = 1 mm: every sphere lies inside its ring of width 10 mm */
    make_frame(&f, n, (const double (*)[3])pos, 0.001, rotation, &box);
    mimas_average *av = average_frame(&f, "r=0:0.05:5,z=0:0.01:1", "bins");
    double out[5 * 128];
    assert_int_equal(mimas_average_fields(av, out, NULL, NULL), 0);
    size_t nf = mimas_fields_count();
    size_t vphi = 0, om = 0, vr = 0;
    for (size_t k = 0; k < mimas_fields_count(); k++) {
        const char *nm = mimas_field_name(k, 1);
        if (nm && !strcmp(nm, "v_phi"))
            vphi = k;
        if (nm && !strcmp(nm, "omega"))
            om = k;
        if (nm && !strcmp(nm, "v_r"))
            vr = k;
    }
    for (size_t c = 0; c < 5; c++) {
        double rho = 0.01 * (c + 0.5);
        assert_close(out[c * nf + vphi], OMEGA * rho, 1e-12);
        assert_close(out[c * nf + om], OMEGA, 1e-12);
        assert_close(out[c * nf + vr], 0.0, 1e-12);
        /* a rigid rotation does not shear */
        assert_close(out[c * nf + col("shear_rate", 1)], 0.0, 1e-12);
        assert_close(out[c * nf + col("shear_rate_luding", 1)], 0.0, 1e-12);
    }
    mimas_average_free(av);
    mimas_frame_free(&f);
    free(pos);
}

/* Couette-like v_phi = C r^2 on rings at the cell centres: d v_phi/dr - v_phi/r
 * = C r, so shear_rate_luding = C r/2 and shear_rate = sqrt(2 D':D') = C r
 * (central differences are exact for a quadratic profile). */
static const double CQ = 3.0;
static void couette(const double x[3], double v[3])
{
    double r = hypot(x[0], x[1]), vphi = CQ * r * r;
    v[0] = -vphi * x[1] / r;
    v[1] = vphi * x[0] / r;
    v[2] = 0;
}

static void test_couette_shear_rate(void **state)
{
    (void)state;
    const int rings = 8, per_ring = 60;
    double (*pos)[3] = malloc(sizeof *pos * rings * per_ring);
    size_t n = 0;
    for (int r = 0; r < rings; r++)
        for (int k = 0; k < per_ring; k++) {
            double rho = 0.01 * (r + 0.5), th = 2 * M_PI * k / per_ring;
            pos[n][0] = rho * cos(th);
            pos[n][1] = rho * sin(th);
            pos[n][2] = 0.005;
            n++;
        }
    mimas_box box = {{-0.1, -0.1, 0}, {0.1, 0.1, 0.01}, 0, 0, 0, {0, 0, 0}};
    mimas_frame f;
    mimas_frame_init(&f);
    make_frame(&f, n, (const double (*)[3])pos, 0.001, couette, &box);
    mimas_average *av = average_frame(&f, "r=0:0.08:8,z=0:0.01:1", "bins");
    size_t nf = mimas_fields_count();
    double *out = malloc(8 * nf * sizeof *out);
    assert_int_equal(mimas_average_fields(av, out, NULL, NULL), 0);
    for (size_t c = 1; c + 1 < 8; c++) {
        double r = 0.01 * (c + 0.5);
        assert_close(out[c * nf + col("v_phi", 1)], CQ * r * r, 1e-12);
        assert_close(out[c * nf + col("shear_rate_luding", 1)], 0.5 * CQ * r, 1e-10);
        assert_close(out[c * nf + col("shear_rate", 1)], CQ * r, 1e-10);
    }
    free(out);
    mimas_average_free(av);
    mimas_frame_free(&f);
    free(pos);
}

/* Simple shear v_x = G y on a lattice: shear_rate = G, with bins (finite
 * differences) and with the Gaussian (its analytic gradient). */
static const double GSHEAR = 2.5;
static void shear(const double x[3], double v[3])
{
    v[0] = GSHEAR * x[1];
    v[1] = v[2] = 0;
}

static void test_simple_shear(void **state)
{
    (void)state;
    const int m = 16;
    const double a = 0.001;
    size_t n;
    double (*pos)[3] = cubic_lattice(m, a, &n);
    mimas_box box = {{0, 0, 0}, {m * a, m * a, m * a}, 0, 0, 0, {0, 0, 0}};
    mimas_frame f;
    mimas_frame_init(&f);
    make_frame(&f, n, (const double (*)[3])pos, 0.4 * a, shear, &box);
    size_t nf = mimas_fields_count();
    /* bins: slabs of y, the profile is linear */
    mimas_average *av = average_frame(&f, "y=0:0.016:8", "bins");
    double *out = malloc(64 * nf * sizeof *out);
    assert_int_equal(mimas_average_fields(av, out, NULL, NULL), 0);
    for (size_t c = 0; c < 8; c++)
        assert_close(out[c * nf + col("shear_rate", 0)], GSHEAR, 1e-9);
    mimas_average_free(av);
    /* Gaussian: the analytic gradient is close to G (the lattice makes the
     * coarse-grained profile slightly non-linear at w = a).  The shifted kernel is
     * continuous: its gradient equals the numerical derivative of the coarse-grained
     * velocity itself (three points 2e-7 m apart in y, at a point where the
     * lattice's symmetry leaves only d V_x / d y).  The plain cut's pointwise
     * derivative misses the part kappa = phi(R) 4/3 pi R^3 of the gradient that its
     * jump carries; the analytic gradient puts it back: numeric / (1 - kappa) */
    const double h = 1e-7, x0 = 8 * a, y0 = 7.3 * a, C = 3.0;
    double kappa = test_gauss(C * C * 1e-6 * (1 - 1e-15), 0.001, C) * 4.0 / 3.0 * M_PI *
                   pow(C * 0.001, 3);
    char grid[256];
    snprintf(grid, sizeof grid, "x=%.17g:%.17g:1,y=%.17g:%.17g:3,z=%.17g:%.17g:1", x0 - h / 2,
             x0 + h / 2, y0 - 1.5 * h, y0 + 1.5 * h, x0 - h / 2, x0 + h / 2);
    const char *kernels[2] = {"gauss:w=0.001,shift", "gauss:w=0.001"};
    for (int k = 0; k < 2; k++) {
        av = average_frame(&f, grid, kernels[k]);
        assert_int_equal(mimas_average_fields(av, out, NULL, NULL), 0);
        double numeric = (out[2 * nf + col("v_x", 0)] - out[0 * nf + col("v_x", 0)]) / (2 * h);
        if (k == 1)
            numeric /= 1 - kappa;
        assert_close(out[1 * nf + col("v_y", 0)], 0.0, 1e-12);
        assert_close(out[1 * nf + col("shear_rate", 0)], fabs(numeric), 1e-6 * GSHEAR);
        assert_close(out[1 * nf + col("shear_rate", 0)], GSHEAR, 0.03 * GSHEAR);
        mimas_average_free(av);
    }
    free(out);
    mimas_frame_free(&f);
    free(pos);
}

/* Lucy's kernel integrates rho to the total mass; Shepard's velocity is the
 * ratio sum v g / sum g (computed here with the cut Gaussian, whose
 * normalisation cancels). */
static void random_velocity(const double x[3], double v[3])
{
    v[0] = sin(300 * x[0]) + x[1];
    v[1] = cos(200 * x[2]);
    v[2] = x[0] * x[1] * 1000;
}

static void test_lucy_and_shepard(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const size_t n = 300;
    double (*pos)[3] = malloc(sizeof *pos * n);
    mimas_frame f;
    mimas_frame_init(&f);
    double total = random_cloud(&f, n, rng, random_velocity, pos);
    mimas_average *av = average_frame(&f, "x=-0.003:0.013:48,y=-0.003:0.013:48,"
                                          "z=-0.003:0.013:48", "lucy:c=0.003");
    assert_close(grid_integral(av, S_M), total, 1e-6 * total);
    mimas_average_free(av);

    const double w = 0.002, C = 3.0, x0[3] = {0.004, 0.0055, 0.006};
    av = average_frame(&f, "x=0.0039:0.0041:1,y=0.0054:0.0056:1,z=0.0059:0.0061:1",
                       "shepard:w=0.002");
    double out[128];
    assert_int_equal(mimas_average_fields(av, out, NULL, NULL), 0);
    double num[3] = {0}, den = 0;
    for (size_t k = 0; k < n; k++) {
        double r2 = 0;
        for (int d = 0; d < 3; d++)
            r2 += (x0[d] - pos[k][d]) * (x0[d] - pos[k][d]);
        if (r2 >= C * C * w * w)
            continue;
        double gk = exp(-r2 / (2 * w * w));
        for (int d = 0; d < 3; d++)
            num[d] += f.particles.vel[k][d] * gk;
        den += gk;
    }
    for (int d = 0; d < 3; d++)
        assert_close(out[col("v_x", 0) + (size_t)d], num[d] / den, 1e-12);
    assert_true(isnan(out[col("rho", 0)])); /* densities are not Shepard means */
    mimas_average_free(av);
    mimas_frame_free(&f);
    free(pos);
    gsl_rng_free(rng);
}

/* On an r-z grid the kernel is averaged over the azimuth: the grid still
 * integrates rho to the total mass, and the contact stress (in r, phi, z
 * components at r_i) to its total (particles away from the axis). */
static void test_cylindrical_kernel_integrates_mass(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const size_t n = 150;
    double (*pos)[3] = malloc(sizeof *pos * n);
    for (size_t k = 0; k < n; k++) {
        double rho = 0.02 + 0.02 * gsl_rng_uniform(rng), th = 2 * M_PI * gsl_rng_uniform(rng);
        pos[k][0] = rho * cos(th);
        pos[k][1] = rho * sin(th);
        pos[k][2] = 0.005 + 0.01 * gsl_rng_uniform(rng);
    }
    mimas_box box = {{-0.05, -0.05, 0}, {0.05, 0.05, 0.02}, 0, 0, 0, {0, 0, 0}};
    mimas_frame f;
    mimas_frame_init(&f);
    make_frame(&f, n, (const double (*)[3])pos, 0.0005, still, &box);
    double total = 0;
    for (size_t k = 0; k < n; k++)
        total += f.particles.mass[k];
    /* contacts between neighbours in the list (branches of about 1-2 mm) and
     * their stress in (r, phi, z) components at r_i, computed here */
    mimas_error err;
    const size_t nc = 40;
    mimas_table_set_present(&f.contacts, &mimas_contacts_desc, MIMAS_C_FORCE, &err);
    mimas_table_resize(&f.contacts, &mimas_contacts_desc, nc, &err);
    f.has_contacts = 1;
    for (size_t k = 0; k < nc; k++) {
        size_t i = k, j = k + 1;
        for (int d = 0; d < 3; d++) /* j within 2 mm of i */
            f.particles.pos[j][d] = f.particles.pos[i][d] + 0.002 * (gsl_rng_uniform(rng) - 0.5);
        f.contacts.i[k] = i;
        f.contacts.j[k] = j;
        for (int d = 0; d < 3; d++)
            f.contacts.force[k][d] = gsl_rng_uniform(rng) - 0.5;
    }
    double T[9] = {0};
    for (size_t k = 0; k < nc; k++) {
        const double *ri = f.particles.pos[k], *rj = f.particles.pos[k + 1];
        double rr = hypot(ri[0], ri[1]), c = ri[0] / rr, sn = ri[1] / rr;
        const double *F = f.contacts.force[k];
        double b[3] = {ri[0] - rj[0], ri[1] - rj[1], ri[2] - rj[2]};
        double Fl[3] = {c * F[0] + sn * F[1], -sn * F[0] + c * F[1], F[2]};
        double bl[3] = {c * b[0] + sn * b[1], -sn * b[0] + c * b[1], b[2]};
        for (int x = 0; x < 3; x++)
            for (int y = 0; y < 3; y++)
                T[3 * x + y] += Fl[x] * bl[y];
    }
    /* the plain cut's azimuthal average has a square-root edge: a midpoint sum
     * over the cells converges more slowly than for the continuous kernels (the
     * contacts' rule along the branch is split there, exact to 1e-8 of the peak) */
    const char *weights[3] = {"gauss:w=0.0015,shift", "lucy:c=0.004", "gauss:w=0.0015"};
    const double tol[3] = {1e-6, 1e-6, 2e-5}, ctol[3] = {1e-6, 1e-6, 5e-5};
    for (int k = 0; k < 3; k++) {
        /* spacing w/4.5 (Lucy: c/12); the grid reaches past the kernels' support */
        mimas_average *av = average_frame(&f, "r=0.01:0.05:120,z=0:0.02:60", weights[k]);
        const mimas_grid *g = mimas_average_grid(av);
        double mass = 0, C[9] = {0}, S[NSUMS];
        for (size_t c = 0; c < mimas_grid_cells(g); c++) {
            mimas_average_sums(av, c, S);
            double V = mimas_grid_cell_volume(g, c);
            mass += S[S_M] * V;
            for (int q = 0; q < 9; q++)
                C[q] += S[S_C + q] * V;
        }
        assert_close(mass, total, tol[k] * total);
        double scale = max_abs(T, 9);
        for (int q = 0; q < 9; q++)
            assert_close(C[q], T[q], ctol[k] * scale);
        mimas_average_free(av);
    }
    mimas_frame_free(&f);
    free(pos);
    gsl_rng_free(rng);
}

/* --exclude-types: contacts with excluded particles become wall contacts of
 * the others, with the segment from the contact point; real wall contacts
 * too.  On the LIGGGHTS hopper (types 1 and 2, mesh walls) with type 2
 * excluded, V cstress of --grid none is
 *   sum_{1-1} f (x) (r_i - r_j) + sum_{1-2} f_1 (x) (r_1 - c) + sum_walls f (x) (r - c). */
static void test_exclude_types_as_walls(void **state)
{
    (void)state;
    mimas_reader *r;
    mimas_error err;
    assert_int_equal(liggghts_open(&r, data("hopper_walls/dump.hopper.atom.gz"),
                                   data("hopper_walls/dump.hopper.pgl.gz"),
                                   data("hopper_walls/dump.hopper.wgl"), &err), 0);
    mimas_frame f;
    mimas_frame_init(&f);
    while (mimas_reader_next(r, &f, &err) == MIMAS_OK)
        ;
    mimas_reader_close(r);
    const mimas_particles *p = &f.particles;
    double T[9] = {0};
    size_t mixed = 0;
    for (size_t k = 0; k < f.contacts.n; k++) {
        size_t i = f.contacts.i[k], j = f.contacts.j[k];
        int ti = p->type[i], tj = p->type[j];
        const double *F = f.contacts.force[k], *c = f.contacts.point[k];
        double b[3], sign = 1;
        size_t in = i;
        if (ti == 1 && tj == 1) {
            for (int m = 0; m < 3; m++)
                b[m] = p->pos[i][m] - p->pos[j][m];
        } else if (ti == 2 && tj == 2) {
            continue;
        } else {
            in = ti == 1 ? i : j;
            sign = ti == 1 ? 1 : -1;
            for (int m = 0; m < 3; m++)
                b[m] = p->pos[in][m] - c[m];
            mixed++;
        }
        for (int x = 0; x < 3; x++)
            for (int y = 0; y < 3; y++)
                T[3 * x + y] += sign * F[x] * b[y];
    }
    for (size_t k = 0; k < f.walls.n; k++) {
        size_t i = f.walls.particle[k];
        if (p->type[i] != 1)
            continue;
        for (int x = 0; x < 3; x++)
            for (int y = 0; y < 3; y++)
                T[3 * x + y] += f.walls.force[k][x] * (p->pos[i][y] - f.walls.point[k][y]);
    }
    assert_true(mixed > 10);
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    assert_int_equal(mimas_grid_parse(&o.grid, "none", NULL, &err), 0);
    assert_int_equal(mimas_weight_parse(&o.weight, "bins", &err), 0);
    o.grid_none = 1;
    const int32_t two = 2;
    o.types = &two;
    o.ntypes = 1;
    o.exclude = 1;
    mimas_average *a;
    assert_int_equal(mimas_average_create(&a, &o, &err), 0);
    assert_int_equal(mimas_average_add(a, &f, &err), 0);
    double S[NSUMS];
    mimas_average_sums(a, 0, S);
    double V = mimas_box_volume(&f.box), scale = max_abs(T, 9);
    for (int k = 0; k < 9; k++)
        assert_close(S[S_C + k] * V, T[k], 1e-12 * scale);
    /* only type-1 particles count: n V = their number */
    size_t n1 = 0;
    for (size_t k = 0; k < p->n; k++)
        n1 += p->type[k] == 1;
    assert_close(S[S_N] * V, (double)n1, 1e-9);
    mimas_average_free(a);
    mimas_frame_free(&f);
}

/* Asked for two threads, a frame below the size at which a second thread starts
 * (300 particles) gives the single-thread result (two threads sharing frames:
 * test_threads_agree_over_frames). */
static void test_threads_agree(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    last_frame(data("periodic_box/dump.periodic.atom.gz"),
               data("periodic_box/dump.periodic.pgl.gz"), &f);
    mimas_average *av[2];
    for (int t = 0; t < 2; t++) {
        mimas_average_options o;
        memset(&o, 0, sizeof o);
        mimas_error err;
        assert_int_equal(mimas_grid_parse(&o.grid, "x=0:0.02:4,z=0:0.02:5", NULL, &err), 0);
        assert_int_equal(mimas_weight_parse(&o.weight, "bins", &err), 0);
        o.threads = t + 1;
        assert_int_equal(mimas_average_create(&av[t], &o, &err), 0);
        assert_int_equal(mimas_average_add(av[t], &f, &err), 0);
    }
    double s1[NSUMS], s2[NSUMS];
    for (size_t c = 0; c < 20; c++) {
        mimas_average_sums(av[0], c, s1);
        mimas_average_sums(av[1], c, s2);
        for (int k = 0; k < NSUMS; k++)
            assert_close(s2[k], s1[k], 1e-12 * fmax(1.0, fabs(s1[k])));
    }
    mimas_average_free(av[0]);
    mimas_average_free(av[1]);
    mimas_frame_free(&f);
}

/* Frame q of an m^3 lattice of spacing a (periodic box), with velocities and
 * contact forces that differ from frame to frame: every particle touches its
 * +x, +y, +z neighbour (wrapping round). */
static void lattice_frame(mimas_frame *f, int m, double a, int q)
{
    size_t n;
    double (*pos)[3] = cubic_lattice(m, a, &n);
    mimas_box box = {{0, 0, 0}, {m * a, m * a, m * a}, 0, 0, 0, {1, 1, 1}};
    make_frame(f, n, (const double (*)[3])pos, 0.5 * a, still, &box);
    free(pos);
    mimas_error err;
    for (size_t k = 0; k < n; k++)
        for (int c = 0; c < 3; c++)
            f->particles.vel[k][c] = sin(0.37 * (double)k + 1.3 * c + q);
    mimas_table_set_present(&f->contacts, &mimas_contacts_desc, MIMAS_C_FORCE, &err);
    mimas_table_resize(&f->contacts, &mimas_contacts_desc, 3 * n, &err);
    size_t c = 0;
    for (size_t k = 0; k < n; k++)
        for (size_t stride = 1; stride < n; stride *= (size_t)m, c++) {
            f->contacts.i[c] = k;
            f->contacts.j[c] = (k + stride) % n;
            for (int d = 0; d < 3; d++)
                f->contacts.force[c][d] = cos(0.11 * (double)c + d - q);
        }
    f->has_contacts = 1;
}

static mimas_average *average_of(const char *grid, const char *weight, int threads, int spread)
{
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&o.grid, grid, NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_weight_parse(&o.weight, weight, &err), MIMAS_OK);
    o.threads = threads;
    o.spread = spread;
    mimas_average *a;
    assert_int_equal(mimas_average_create(&a, &o, &err), MIMAS_OK);
    return a;
}

/* Frames large enough for two threads to share them (a team of one below 2,000
 * objects; runs of 4,096 objects dealt out in turn, so both threads get
 * particles and contacts, and a run is cut short at the end), several of them:
 * one and two threads give the same sums up to summation order and the total
 * mass on the grid; with the spread (which -o always keeps) the same sums to
 * the bit as without; a packed state merged into an empty average, and the same
 * frames again after a reset, give the same sums to the bit. */
static void test_threads_agree_over_frames(void **state)
{
    (void)state;
    const int m = 17, frames = 3; /* 4,913 particles, 14,739 contacts */
    const double a = 0.002, L = m * a;
    mimas_frame f[3];
    for (int q = 0; q < frames; q++) {
        mimas_frame_init(&f[q]);
        lattice_frame(&f[q], m, a, q);
    }
    char grid[256];
    snprintf(grid, sizeof grid, "x=0:%.17g:5,y=0:%.17g:4,z=0:%.17g:3", L, L, L);
    const char *weights[2] = {"bins", "gauss:w=0.003"};
    mimas_error err;
    for (int w = 0; w < 2; w++) {
        mimas_average *av[4]; /* threads 1, 2; spread off, on */
        for (int v = 0; v < 4; v++) {
            av[v] = average_of(grid, weights[w], 1 + v % 2, v / 2);
            for (int q = 0; q < frames; q++)
                assert_int_equal(mimas_average_add(av[v], &f[q], &err), MIMAS_OK);
        }
        double ref[NSUMS], S[NSUMS];
        for (size_t c = 0; c < 60; c++) {
            mimas_average_sums(av[0], c, ref);
            double scale = max_abs(ref, NSUMS);
            for (int v = 1; v < 4; v++) {
                mimas_average_sums(av[v], c, S);
                for (int k = 0; k < NSUMS; k++)
                    assert_close(S[k], ref[k], 1e-12 * scale);
                if (v >= 2) { /* the spread changes no bit */
                    double plain[NSUMS];
                    mimas_average_sums(av[v - 2], c, plain);
                    assert_memory_equal(S, plain, sizeof S);
                }
            }
        }
        /* the mass of the frame (each frame's the same) on the grid: exact for
         * bins (the Gaussian is sampled at the cells' centres) */
        double mass = (double)f[0].particles.n * f[0].particles.mass[0];
        for (int v = 0; v < 4 && w == 0; v++)
            assert_close(grid_integral(av[v], S_M), mass, 1e-12 * mass);
        /* two threads' state packed and merged into an empty average */
        mimas_bytes packed = {0};
        assert_int_equal(mimas_average_pack(av[1], &packed, &err), MIMAS_OK);
        mimas_average *merged = average_of(grid, weights[w], 1, 0);
        assert_int_equal(mimas_average_merge(merged, packed.data, packed.n, &err), MIMAS_OK);
        assert_int_equal(mimas_average_frames(merged), frames);
        double again[NSUMS];
        for (size_t c = 0; c < 60; c++) {
            mimas_average_sums(av[1], c, S);
            mimas_average_sums(merged, c, again);
            assert_memory_equal(S, again, sizeof S);
        }
        /* a reset forgets every thread's running sums */
        mimas_average_reset(av[1]);
        for (int q = 0; q < frames; q++)
            assert_int_equal(mimas_average_add(av[1], &f[q], &err), MIMAS_OK);
        for (size_t c = 0; c < 60; c++) {
            mimas_average_sums(merged, c, S);
            mimas_average_sums(av[1], c, again);
            assert_memory_equal(S, again, sizeof S);
        }
        free(packed.data);
        mimas_average_free(merged);
        for (int v = 0; v < 4; v++)
            mimas_average_free(av[v]);
    }
    for (int q = 0; q < frames; q++)
        mimas_frame_free(&f[q]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stress_identity_triclinic),
        cmocka_unit_test(test_stress_identity_periodic),
        cmocka_unit_test(test_matches_liggghts_stress_atom),
        cmocka_unit_test(test_sums_over_frames),
        cmocka_unit_test(test_simple_cubic_solid_fraction),
        cmocka_unit_test(test_gauss_integrates_mass),
        cmocka_unit_test(test_gauss_profile_is_marginal),
        cmocka_unit_test(test_gauss_contact_cells),
        cmocka_unit_test(test_rigid_rotation),
        cmocka_unit_test(test_couette_shear_rate),
        cmocka_unit_test(test_simple_shear),
        cmocka_unit_test(test_threads_agree),
        cmocka_unit_test(test_threads_agree_over_frames),
        cmocka_unit_test(test_lucy_and_shepard),
        cmocka_unit_test(test_cylindrical_kernel_integrates_mass),
        cmocka_unit_test(test_exclude_types_as_walls),
    };
    return cmocka_run_group_tests_name("average", tests, NULL, NULL);
}
