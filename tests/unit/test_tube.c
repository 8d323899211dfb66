/* The tube geometry and the axial profiles (averaging/tube.c,
 * averaging/axial_profile.c, the lens volume of averaging/overlap.c):
 * spherical caps against partitions and closed forms, the lens against the
 * sum of its two caps and a Monte Carlo estimate, the slab porosity of a
 * lattice of spheres against its closed form, the profile fields of frames
 * built here against hand computations, the contact stress and wall force
 * against their totals, the gas pressure, and the geometry errors. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "assert_close.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <string.h>

#include "axial_profile.h"
#include "overlap.h"
#include "tube.h"

#define PI 3.14159265358979323846

static double ball(double R)
{
    return 4.0 / 3.0 * PI * R * R * R;
}

static double cap(double R, double h)
{
    return PI * h * h * (3.0 * R - h) / 3.0;
}

/* every particle quantity the profiles use, n rows */
static void frame_of(mimas_frame *f, size_t n)
{
    mimas_frame_init(f);
    mimas_error err;
    assert_int_equal(mimas_table_set_present(&f->particles, &mimas_particles_desc,
                                             MIMAS_P_ID | MIMAS_P_TYPE | MIMAS_P_RADIUS |
                                                 MIMAS_P_MASS | MIMAS_P_POS | MIMAS_P_VEL,
                                             &err),
                     0);
    assert_int_equal(mimas_table_resize(&f->particles, &mimas_particles_desc, n, &err), 0);
    for (size_t i = 0; i < n; i++) {
        f->particles.id[i] = (int64_t)i + 1;
        f->particles.type[i] = 1;
    }
    for (int d = 0; d < 3; d++) {
        f->box.lo[d] = -1;
        f->box.hi[d] = 1;
    }
}

static void set_particle(mimas_frame *f, size_t i, double x, double y, double z, double a,
                         double m, double vx, double vy, double vz)
{
    mimas_particles *p = &f->particles;
    p->pos[i][0] = x, p->pos[i][1] = y, p->pos[i][2] = z;
    p->vel[i][0] = vx, p->vel[i][1] = vy, p->vel[i][2] = vz;
    p->radius[i] = a;
    p->mass[i] = m;
}

static void options_for(mimas_axial_options *o, double R, double s0, double s1, double w)
{
    mimas_error err;
    memset(o, 0, sizeof *o);
    assert_int_equal(mimas_tube_geom_resolve(&o->geom, NULL, R, NULL, &err), 0);
    assert_int_equal(mimas_slices_set(&o->slices, s0, s1, w, &err), 0);
    o->flow_at = NAN;
    o->check_inside = 1;
}

/* caps over a partition of the axis return the sphere; their first
 * moments its centre */
static void test_caps_sum_to_sphere(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    for (int t = 0; t < 200; t++) {
        double a = 1e-3 * (0.2 + gsl_rng_uniform(rng)), c = 0.01 * gsl_rng_uniform(rng);
        double w = a * (0.05 + 3 * gsl_rng_uniform(rng)), s0 = c - a - 2 * w * gsl_rng_uniform(rng);
        double vol = 0, mom = 0;
        for (double lo = s0; lo < c + a; lo += w) {
            vol += mimas_tube_slab_volume(c, a, lo, lo + w);
            mom += mimas_tube_slab_moment(c, a, lo, lo + w, mimas_tube_slab_volume(c, a, lo, lo + w));
        }
        assert_close(vol, ball(a), 1e-12 * ball(a));
        assert_close(mom / vol, c, 1e-12 * c + 1e-15);
    }
    gsl_rng_free(rng);
    /* the upper half: centroid 3a/8 above the centre */
    double a = 2e-3, c = 0.05;
    assert_close(mimas_tube_slab_volume(c, a, c, c + a), ball(a) / 2, 1e-15);
    double half = mimas_tube_slab_volume(c, a, c, 1);
    assert_close(mimas_tube_slab_moment(c, a, c, 1, half) / half, c + 3 * a / 8, 1e-15);
    /* a cap of height h */
    assert_close(mimas_tube_slab_volume(c, a, c + a - 0.5e-3, 1), cap(a, 0.5e-3), 1e-20);
}

/* the lens: closed form against the sum of its two caps, and Monte Carlo */
static void test_lens(void **state)
{
    (void)state;
    assert_close(overlap_sphere_sphere(3.0, 1.0, 2.0), 0.0, 0.0);
    assert_close(overlap_sphere_sphere(0.5, 1.0, 2.0), ball(1.0), 1e-15);
    assert_close(overlap_sphere_sphere(0.0, 1.0, 1.0), ball(1.0), 1e-15);
    const double cases[][3] = {{1.0, 1.0, 1.0}, {0.3, 1.0, 1.0}, {1.9, 1.0, 1.0},
                               {1.2, 1.0, 0.5}, {0.6, 1.0, 0.5}, {1.45, 1.0, 0.5},
                               {2.2, 2.0, 0.25}};
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double d = cases[k][0], R1 = cases[k][1], R2 = cases[k][2];
        /* cap heights: the plane of intersection at x from centre 1 */
        double x = (d * d + R1 * R1 - R2 * R2) / (2 * d);
        double want = cap(R1, R1 - x) + cap(R2, R2 - (d - x));
        double v = overlap_sphere_sphere(d, R1, R2);
        assert_close(v, want, 1e-13 * want);
        assert_close(overlap_sphere_sphere(d, R2, R1), v, 1e-13 * want);
        /* Monte Carlo in the bounding box of the smaller ball */
        double r = fmin(R1, R2), cx = R2 < R1 ? d : 0.0;
        long n = 400000, in = 0;
        for (long m = 0; m < n; m++) {
            double p[3];
            p[0] = cx + r * (2 * gsl_rng_uniform(rng) - 1);
            p[1] = r * (2 * gsl_rng_uniform(rng) - 1);
            p[2] = r * (2 * gsl_rng_uniform(rng) - 1);
            double d1 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
            double d2 = (p[0] - d) * (p[0] - d) + p[1] * p[1] + p[2] * p[2];
            in += d1 <= R1 * R1 && d2 <= R2 * R2;
        }
        double box = 8 * r * r * r, pf = (double)in / (double)n;
        double mc = box * pf, sigma = box * sqrt(pf * (1 - pf) / (double)n);
        assert_close(v, mc, 4 * sigma);
    }
    gsl_rng_free(rng);
}

/* A simple cubic lattice (spacing h, spheres of radius a <= h/2) of the
 * columns that fit into the tube: a slice of width h holds one sphere per
 * column wherever it lies, so the porosity is 1 - N (4/3) a^3 / (R^2 h);
 * a slice of width h/2 centred on a layer (a = h/2) holds the middle of
 * each sphere, pi (a^3 - a^3/12). */
static void test_lattice_porosity(void **state)
{
    (void)state;
    double h = 1e-3, a = 0.5e-3, R = 4.3e-3;
    int layers = 40, ncol = 0;
    mimas_frame f;
    frame_of(&f, 0);
    mimas_error err;
    size_t n = 0;
    for (int i = -5; i <= 5; i++)
        for (int j = -5; j <= 5; j++) {
            if (hypot(i * h, j * h) + a > R)
                continue;
            ncol++;
            for (int k = 0; k < layers; k++) {
                assert_int_equal(
                    mimas_table_resize(&f.particles, &mimas_particles_desc, n + 1, &err), 0);
                set_particle(&f, n, i * h, j * h, (k + 0.5) * h, a, 1e-6, 0, 0, 0);
                f.particles.id[n] = (int64_t)n + 1;
                f.particles.type[n] = 1;
                n++;
            }
        }
    /* slices of width h at an offset of 0.37 h: the inner ones */
    mimas_axial_options o;
    options_for(&o, R, 0.37 * h, (layers - 3 + 0.37) * h, h);
    mimas_axial *ax;
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    assert_int_equal(mimas_axial_compute(ax, &f, &err), 0);
    double want = 1 - ncol * (4.0 / 3.0) * a * a * a / (R * R * h);
    for (size_t k = 0; k < o.slices.n; k++) {
        assert_close(mimas_axial_value(ax, k, MIMAS_AX_POROSITY), want, 1e-12);
        assert_close(mimas_axial_value(ax, k, MIMAS_AX_NU) +
                         mimas_axial_value(ax, k, MIMAS_AX_POROSITY), 1.0, 1e-15);
        assert_close(mimas_axial_value(ax, k, MIMAS_AX_N), (double)ncol, 1e-12 * ncol);
    }
    mimas_axial_free(ax);
    /* slices of width h/2 centred on the layers 5..30 (at (k + 1/2) h) */
    options_for(&o, R, 5.25 * h, 30.75 * h, h);
    o.slices.w = h / 2;
    o.slices.n = 51;
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    assert_int_equal(mimas_axial_compute(ax, &f, &err), 0);
    double mid = 1 - ncol * (11.0 / 12.0) * a * a * a / (R * R * h / 2);
    for (size_t k = 0; k < o.slices.n; k += 2)
        assert_close(mimas_axial_value(ax, k, MIMAS_AX_POROSITY), mid, 1e-12);
    mimas_axial_free(ax);
    mimas_frame_free(&f);
}

/* Velocities, temperature and kinetic stress of two particles in one slice:
 * masses 1 and 3, axial velocities 1 and 5 (mean 4, fluctuations -3 and 1:
 * sum m dv^2 = 9 + 3 = 12), one of them also moving radially at 2 (mean
 * radial velocity 0.5, sum m dv_r^2 = 1 (1.5)^2 + 3 (0.5)^2 = 3) and
 * azimuthally (none). */
static void test_profile_fields(void **state)
{
    (void)state;
    mimas_frame f;
    frame_of(&f, 2);
    double R = 0.01, a = 1e-3;
    /* particle 0 at (r, 0, s) moves radially (+x) */
    set_particle(&f, 0, 0.004, 0, 0.005, a, 1.0, 2.0, 0, 1.0);
    set_particle(&f, 1, 0, -0.004, 0.005, a, 3.0, 0, 0, 5.0);
    mimas_axial_options o;
    options_for(&o, R, 0, 0.01, 0.01);
    mimas_error err;
    mimas_axial *ax;
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    assert_int_equal(mimas_axial_compute(ax, &f, &err), 0);
    double V = PI * R * R * 0.01;
    assert_close(mimas_axial_value(ax, 0, MIMAS_AX_NU), 2 * ball(a) / V, 1e-15);
    assert_close(mimas_axial_value(ax, 0, MIMAS_AX_N), 2.0, 1e-14);
    assert_close(mimas_axial_value(ax, 0, MIMAS_AX_VS), 4.0, 1e-14);
    assert_close(mimas_axial_value(ax, 0, MIMAS_AX_VR), 0.5, 1e-14);
    assert_close(mimas_axial_value(ax, 0, MIMAS_AX_VPHI), 0.0, 1e-14);
    assert_close(mimas_axial_value(ax, 0, MIMAS_AX_KSTRESS_SS), 12.0 / V, 1e-10 / V);
    assert_close(mimas_axial_value(ax, 0, MIMAS_AX_KSTRESS_RR), 3.0 / V, 1e-10 / V);
    /* T over s, r, phi: (12 + 3 + 0) / (3 x 2) */
    assert_close(mimas_axial_value(ax, 0, MIMAS_AX_T), 15.0 / 6.0, 1e-13);
    assert_true(isnan(mimas_axial_value(ax, 0, MIMAS_AX_WALL_FRICTION)));
    assert_true(isnan(mimas_axial_value(ax, 0, MIMAS_AX_GAS_P)));
    assert_true(isnan(mimas_axial_frame_totals(ax).pressure_drop));
    mimas_axial_free(ax);
    /* only the radial and azimuthal components (Strauß 2005's horizontal ones) */
    o.temperature = MIMAS_TEMP_R | MIMAS_TEMP_PHI;
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    assert_int_equal(mimas_axial_compute(ax, &f, &err), 0);
    assert_close(mimas_axial_value(ax, 0, MIMAS_AX_T), 3.0 / 4.0, 1e-13);
    mimas_axial_free(ax);
    mimas_frame_free(&f);
}

/* A contact across several slices, a wall contact: the contact stress
 * summed over the slices times their volume is f_s b_s (and f_r b_r); the
 * wall's normal and axial force per area are in the slice of the contact
 * point. */
static void test_contact_and_wall(void **state)
{
    (void)state;
    mimas_frame f;
    frame_of(&f, 3);
    double R = 0.01, a = 1e-3;
    set_particle(&f, 0, 0.001, 0, 0.0101, a, 1e-5, 0, 0, 0);
    set_particle(&f, 1, 0.002, 0.0005, 0.0119, a, 1e-5, 0, 0, 0);
    set_particle(&f, 2, R - a, 0, 0.0155, a, 1e-5, 0, 0, 0);
    mimas_error err;
    mimas_contacts *c = &f.contacts;
    assert_int_equal(mimas_table_set_present(c, &mimas_contacts_desc,
                                             MIMAS_C_I | MIMAS_C_J | MIMAS_C_FORCE, &err), 0);
    assert_int_equal(mimas_table_resize(c, &mimas_contacts_desc, 1, &err), 0);
    /* force on 0 from 1: repulsive, pushes 0 away from 1 */
    c->i[0] = 0, c->j[0] = 1;
    double b[3] = {-0.001, -0.0005, -0.0018}, fs = 0.3;
    double len = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    for (int d = 0; d < 3; d++)
        c->force[0][d] = fs * b[d] / len;
    f.has_contacts = 1;
    mimas_wall_contacts *w = &f.walls;
    assert_int_equal(mimas_table_set_present(w, &mimas_walls_desc,
                                             MIMAS_W_PARTICLE | MIMAS_W_WALL | MIMAS_W_POINT |
                                                 MIMAS_W_FORCE, &err), 0);
    assert_int_equal(mimas_table_resize(w, &mimas_walls_desc, 1, &err), 0);
    w->particle[0] = 2;
    w->wall[0] = 1;
    w->point[0][0] = R, w->point[0][1] = 0, w->point[0][2] = 0.0155;
    /* the wall pushes inwards (-x) with 0.2 N and holds the particle up (+z) with 0.05 N */
    w->force[0][0] = -0.2, w->force[0][1] = 0, w->force[0][2] = 0.05;
    f.has_walls = 1;
    mimas_axial_options o;
    options_for(&o, R, 0, 0.02, 0.001);
    mimas_axial *ax;
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    assert_int_equal(mimas_axial_compute(ax, &f, &err), 0);
    double V = PI * R * R * 0.001, css = 0, crr = 0;
    for (size_t k = 0; k < o.slices.n; k++) {
        css += mimas_axial_value(ax, k, MIMAS_AX_CSTRESS_SS) * V;
        crr += mimas_axial_value(ax, k, MIMAS_AX_CSTRESS_RR) * V;
    }
    /* pair: f_s b_s with b = r_0 - r_1; e_r at the branch midpoint
     * (0.0015, 0.00025): f_r b_r = fs |b_r|^2/len; the wall contact's branch
     * r_2 - c = (-a, 0, 0) along e_r: f_r b_r = 0.2 a */
    double mx = 0.0015, my = 0.00025, mr = hypot(mx, my);
    double br = (b[0] * mx + b[1] * my) / mr;
    assert_close(css, fs * b[2] * b[2] / len, 1e-15);
    assert_close(crr, fs * br * br / len + 0.2 * a, 1e-15);
    size_t k = 15; /* the slice of s = 0.0155 */
    double A = 2 * PI * R * 0.001;
    assert_close(mimas_axial_value(ax, k, MIMAS_AX_WALL_P), 0.2 / A, 1e-12);
    /* the particle pushes the wall down: -0.05 N along +s */
    assert_close(mimas_axial_value(ax, k, MIMAS_AX_WALL_SHEAR), -0.05 / A, 1e-12);
    assert_close(mimas_axial_value(ax, k, MIMAS_AX_WALL_FRICTION), -0.25, 1e-14);
    for (size_t q = 0; q < o.slices.n; q++)
        if (q != k)
            assert_close(mimas_axial_value(ax, q, MIMAS_AX_WALL_P), 0.0, 0.0);
    mimas_axial_free(ax);
    mimas_frame_free(&f);
}

/* Gas cells along the axis (1 x 1 x 20 cells of 1 mm), pressure p = 1000 +
 * 50 z_cell(mm): slices aligned with the cells take their pressure; a slice
 * over two cells halfway takes the mean; the tube run along -z too. */
static void test_gas_pressure(void **state)
{
    (void)state;
    mimas_frame f;
    frame_of(&f, 1);
    set_particle(&f, 0, 0, 0, 0.005, 1e-4, 1e-8, 0, 0, 0);
    mimas_error err;
    assert_int_equal(mimas_gas_resize(&f.gas, 1, 1, 20, &err), 0);
    f.gas.origin[0] = f.gas.origin[1] = -0.005;
    f.gas.origin[2] = 0;
    f.gas.spacing[0] = f.gas.spacing[1] = 0.01;
    f.gas.spacing[2] = 0.001;
    for (int k = 0; k < 20; k++)
        f.gas.pressure[k] = 1000 + 50 * (k + 0.5);
    mimas_axial_options o;
    options_for(&o, 0.005, 0.002, 0.010, 0.001);
    mimas_axial *ax;
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    assert_int_equal(mimas_axial_compute(ax, &f, &err), 0);
    for (size_t k = 0; k < o.slices.n; k++)
        assert_close(mimas_axial_value(ax, k, MIMAS_AX_GAS_P), 1000 + 50 * (2 + k + 0.5), 1e-10);
    assert_true(mimas_axial_frame_totals(ax).gas);
    /* the drop from the first slice (cell 2) to the last (cell 9) */
    assert_close(mimas_axial_frame_totals(ax).pressure_drop, -50.0 * 7, 1e-10);
    mimas_axial_free(ax);
    options_for(&o, 0.005, 0.0025, 0.0105, 0.001);
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    assert_int_equal(mimas_axial_compute(ax, &f, &err), 0);
    for (size_t k = 0; k < o.slices.n; k++)
        assert_close(mimas_axial_value(ax, k, MIMAS_AX_GAS_P), 1000 + 50 * (2.5 + k + 0.5), 1e-10);
    mimas_axial_free(ax);
    /* the axis from z = 0.02 downwards: s = 0.02 - z */
    options_for(&o, 0.005, 0.002, 0.010, 0.001);
    assert_int_equal(mimas_tube_geom_resolve(&o.geom, "0,0,0.02,0,0,-1", 0.005, NULL, &err), 0);
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    assert_int_equal(mimas_axial_compute(ax, &f, &err), 0);
    for (size_t k = 0; k < o.slices.n; k++)
        assert_close(mimas_axial_value(ax, k, MIMAS_AX_GAS_P), 1000 + 50 * (17 - k + 0.5), 1e-10);
    mimas_axial_free(ax);
    /* a tilted axis: the grid is not aligned */
    assert_int_equal(mimas_tube_geom_resolve(&o.geom, "0,0,0,0,1,1", 0.005, NULL, &err), 0);
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    assert_int_equal(mimas_axial_compute(ax, &f, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "not aligned"));
    mimas_axial_free(ax);
    mimas_frame_free(&f);
}

/* The axis of a horizontal tube, cylindrical components, the geometry
 * from a file's tube and the options, and the geometry errors. */
static void test_geometry(void **state)
{
    (void)state;
    mimas_error err;
    mimas_tube_geom g;
    mimas_tube file = {1, {0.1, 0.2, 0.3}, {1, 0, 0}, 0.004, 0.5};
    assert_int_equal(mimas_tube_geom_resolve(&g, NULL, 0, &file, &err), 0);
    assert_close(g.radius, 0.004, 0);
    assert_close(g.length, 0.5, 0);
    double s, r, phi, x[3] = {0.35, 0.203, 0.3 - 0.004}, v[3] = {2, 0, 1}, out[3];
    mimas_tube_coords(&g, x, &s, &r, &phi);
    assert_close(s, 0.25, 1e-15);
    assert_close(r, 0.005, 1e-15);
    mimas_tube_vector(&g, x, v, out);
    assert_close(out[0], 2.0, 1e-15);
    /* e_r = (0, 0.6, -0.8) at that point: v . e_r = -0.8 */
    assert_close(out[1], -0.8, 1e-14);
    assert_close(hypot(out[1], out[2]), 1.0, 1e-14);
    /* an explicit radius overrides the file's; --axis drops its length */
    assert_int_equal(mimas_tube_geom_resolve(&g, NULL, 0.01, &file, &err), 0);
    assert_close(g.radius, 0.01, 0);
    assert_int_equal(mimas_tube_geom_resolve(&g, "0,0,0,0,0,1", 0, &file, &err), 0);
    assert_true(isnan(g.length));
    assert_int_equal(mimas_tube_geom_resolve(&g, NULL, 0, NULL, &err), MIMAS_EUSAGE);
    assert_non_null(strstr(err.msg, "--tube-radius"));
    assert_int_equal(mimas_tube_geom_resolve(&g, NULL, -1, NULL, &err), MIMAS_EUSAGE);
    assert_int_equal(mimas_tube_geom_resolve(&g, "1,2,3", 0.01, NULL, &err), MIMAS_EUSAGE);
    /* a particle outside the tube */
    mimas_frame f;
    frame_of(&f, 2);
    set_particle(&f, 0, 0, 0, 0.01, 1e-3, 1e-5, 0, 0, 0);
    /* overlapping the wall by 0.9 of its radius: inside */
    set_particle(&f, 1, 0.0049, 0, 0.01, 1e-3, 1e-5, 0, 0, 0);
    mimas_axial_options o;
    options_for(&o, 0.005, 0, 0.02, 0.001);
    mimas_axial *ax;
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    assert_int_equal(mimas_axial_compute(ax, &f, &err), 0);
    assert_close(mimas_axial_frame_totals(ax).particles, 2, 0); /* both counted */
    /* its centre beyond the wall: outside */
    f.particles.pos[1][0] = 0.0051;
    assert_int_equal(mimas_axial_compute(ax, &f, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "particle 2 at r = 0.0051 m lies outside the tube"));
    /* types: leaving it out is fine */
    int32_t keep[1] = {1};
    f.particles.type[1] = 2;
    mimas_axial_free(ax);
    o.types = keep;
    o.ntypes = 1;
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    assert_int_equal(mimas_axial_compute(ax, &f, &err), 0);
    mimas_axial_free(ax);
    /* slices */
    mimas_slices sl;
    assert_int_equal(mimas_slices_set(&sl, 0, 1, 0.3, &err), 0);
    assert_int_equal(sl.n, 3);
    assert_close(sl.w, 1.0 / 3.0, 1e-16);
    assert_int_equal(mimas_slices_set(&sl, 1, 1, 0.3, &err), MIMAS_EUSAGE);
    assert_int_equal(mimas_slices_set(&sl, 0, 1, 0, &err), MIMAS_EUSAGE);
    mimas_frame_free(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_caps_sum_to_sphere), cmocka_unit_test(test_lens),
        cmocka_unit_test(test_lattice_porosity),  cmocka_unit_test(test_profile_fields),
        cmocka_unit_test(test_contact_and_wall),  cmocka_unit_test(test_gas_pressure),
        cmocka_unit_test(test_geometry),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
