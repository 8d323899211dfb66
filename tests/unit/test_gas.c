/* The gas-pressure model (src/sim/gas.h) against exact and analytic results:
 * the disk-rectangle areas of the cut cells, the deposit conserving the
 * grain volume, the Crank-Nicolson step conserving the gas with closed ends,
 * a Gaussian pulse spreading with variance 2 D t, Darcy's pressure drop
 * through a fixed packed bed with the Carman-Kozeny permeability of its
 * porosity, and the effective viscosity of Re = 65. */
#include <config.h>

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_rng.h>

#include "assert_close.h"
#include "gas.h"
#include "tube_feed.h"

typedef struct chord_par {
    double r, y0, y1;
} chord_par;

static double chord(double x, void *p)
{
    const chord_par *c = p;
    double s = sqrt(fmax(c->r * c->r - x * x, 0));
    return fmax(0, fmin(c->y1, s) - fmax(c->y0, -s));
}

/* the closed form against quadrature of the chord length */
static void test_disk_rect_area(void **state)
{
    (void)state;
    const double R = 0.0035;
    assert_close(sim_disk_rect_area(R, -R, R, -R, R), M_PI * R * R, 1e-15);
    assert_close(sim_disk_rect_area(R, 0, R, 0, R), M_PI * R * R / 4, 1e-16);
    assert_close(sim_disk_rect_area(R, -2 * R, 2 * R, -2 * R, 2 * R), M_PI * R * R, 1e-15);
    assert_true(sim_disk_rect_area(R, R, 2 * R, 0, R) == 0);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    for (int k = 0; k < 200; k++) {
        double x0 = R * (2.4 * gsl_rng_uniform(rng) - 1.2), x1 = x0 + R * gsl_rng_uniform(rng);
        double y0 = R * (2.4 * gsl_rng_uniform(rng) - 1.2), y1 = y0 + R * gsl_rng_uniform(rng);
        chord_par cp = {R, y0, y1};
        gsl_function F = {chord, &cp};
        /* the chord has kinks where sqrt(R^2 - x^2) = |y0| or |y1|: break there */
        double pts[8];
        size_t np = 0;
        pts[np++] = x0;
        const double ys[2] = {y0, y1};
        for (int q = 0; q < 2; q++)
            for (int sgn = -1; sgn <= 1; sgn += 2)
                if (fabs(ys[q]) < R) {
                    double c = sgn * sqrt(R * R - ys[q] * ys[q]);
                    if (c > x0 && c < x1)
                        pts[np++] = c;
                }
        for (int sgn = -1; sgn <= 1; sgn += 2)   /* and where the disk ends */
            if (sgn * R > x0 && sgn * R < x1)
                pts[np++] = sgn * R;
        pts[np++] = x1;
        for (size_t q = 1; q < np; q++)   /* insertion sort */
            for (size_t p = q; p > 0 && pts[p] < pts[p - 1]; p--) {
                double tmp = pts[p];
                pts[p] = pts[p - 1];
                pts[p - 1] = tmp;
            }
        double v = 0, e;
        for (size_t q = 0; q + 1 < np; q++) {
            double part;
            gsl_integration_qags(&F, pts[q], pts[q + 1], 0, 1e-13, 1000, ws, &part, &e);
            v += part;
        }
        assert_close(sim_disk_rect_area(R, x0, x1, y0, y1), v, 1e-9 * R * R);
    }
    gsl_integration_workspace_free(ws);
    gsl_rng_free(rng);
}

static void make_gas(sim_gas *g, size_t across, size_t axial, double length)
{
    sim_gas_params p = {0.0035, length, across, axial, 101325, 6.72e-5, 1.0, 0.0014, 0.5, 0};
    mimas_error err;
    if (sim_gas_init(g, &p, &err))
        fail_msg("%s", err.msg);
}

/* every cell and face at porosity phi */
static void set_uniform(sim_gas *g, double phi)
{
    for (size_t c = 0; c < sim_gas_cells(g); c++)
        g->porosity[c] = phi;
    for (int d = 0; d < 3; d++)
        for (size_t q = 0; q < g->f[d].m[0] * g->f[d].m[1] * g->f[d].m[2]; q++)
            g->f[d].phi[q] = phi;
    sim_gas_update_permeability(g);
}

/* gas content sum phi a V P */
static double content(const sim_gas *g)
{
    double m = 0;
    for (size_t c = 0; c < sim_gas_cells(g); c++)
        m += fmin(1, fmax(0.2, g->porosity[c])) * g->fraction[c] * g->pressure[c];
    return m;
}

/* closed ends and walls: the diffusion steps keep the gas, for any porosity field */
static void test_cn_conserves(void **state)
{
    (void)state;
    sim_gas g;
    make_gas(&g, 2, 40, 0.14);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    for (size_t c = 0; c < sim_gas_cells(&g); c++) {
        g.porosity[c] = 0.4 + 0.6 * gsl_rng_uniform(rng);
        g.pressure[c] = 1000 * gsl_rng_uniform(rng);
    }
    for (int d = 0; d < 3; d++)
        for (size_t q = 0; q < g.f[d].m[0] * g.f[d].m[1] * g.f[d].m[2]; q++)
            g.f[d].phi[q] = 0.4 + 0.6 * gsl_rng_uniform(rng);
    sim_gas_update_permeability(&g);
    double m0 = content(&g), p0 = g.pressure[0];
    for (int k = 0; k < 100; k++)
        sim_gas_diffuse(&g, 1.5e-5);
    double m1 = content(&g);
    print_message("# CN, closed: gas content %.15g -> %.15g (relative change %.2g)\n", m0, m1,
                  (m1 - m0) / m0);
    assert_close(m1, m0, 1e-11 * m0);
    assert_true(g.pressure[0] != p0);   /* it did diffuse */
    gsl_rng_free(rng);
    sim_gas_free(&g);
}

/* a Gaussian pulse along the tube in a uniform medium: sigma^2(t) = sigma0^2 + 2 D t
 * with D = P0 kappa/(eta phi) */
static void test_gaussian_pulse(void **state)
{
    (void)state;
    sim_gas g;
    const size_t nz = 400;
    const double L = 0.4, h = L / nz, phi = 0.5, s0 = 15 * h;
    make_gas(&g, 1, nz, L);
    set_uniform(&g, phi);
    for (size_t k = 0; k < nz; k++) {
        double z = (k + 0.5) * h - L / 2;
        g.pressure[k] = exp(-z * z / (2 * s0 * s0));
    }
    double D = g.p.P0 * sim_gas_permeability(&g, phi) / (g.p.eta * phi);
    /* to sigma ~ 2.2 sigma0 in 200 steps */
    double t = 4 * s0 * s0 / (2 * D), dt = t / 200;
    for (int k = 0; k < 200; k++)
        sim_gas_diffuse(&g, dt);
    double s = 0, sz = 0, szz = 0;
    for (size_t k = 0; k < nz; k++) {
        double z = (k + 0.5) * h - L / 2;
        s += g.pressure[k];
        sz += z * g.pressure[k];
        szz += z * z * g.pressure[k];
    }
    double var = szz / s - (sz / s) * (sz / s), expect = s0 * s0 + 2 * D * t;
    print_message("# Gaussian pulse: D = %.4g m2/s, variance %.6g, analytic %.6g (%+.2g)\n", D,
                  var, expect, var / expect - 1);
    /* second order in h and dt */
    assert_close(var, expect, 1e-4 * expect);
    sim_gas_free(&g);
}

/* Every grain in the tube deposits its volume: sum over cells of the solid
 * volume equals the sum of the particle volumes. */
static void test_deposit_conserves(void **state)
{
    (void)state;
    sim_gas g;
    make_gas(&g, 2, 20, 0.07);
    dem_system s;
    dem_init(&s);
    mimas_error err;
    assert_int_equal(dem_reserve(&s, 300, &err), 0);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double vol = 0, r = 0.0007;
    while (s.n < 300) {
        double x[3] = {0.0028 * (2 * gsl_rng_uniform(rng) - 1), 0.0028 * (2 * gsl_rng_uniform(rng) - 1),
                       0.07 * gsl_rng_uniform(rng)};
        if (hypot(x[0], x[1]) > 0.0028)
            continue;
        dem_add_particle(&s, 1, r, 1000, x);
        vol += 4.0 / 3.0 * M_PI * r * r * r;
    }
    sim_gas_deposit(&g, &s);
    double sum = 0, vcell = g.h[0] * g.h[1] * g.h[2];
    for (size_t c = 0; c < sim_gas_cells(&g); c++)
        sum += (1 - g.porosity[c]) * g.fraction[c] * vcell;
    assert_close(sum, vol, 1e-12 * vol);
    gsl_rng_free(rng);
    dem_free(&s);
    sim_gas_free(&g);
}

/* A fixed packed bed in the middle third of the tube, gas fed at v_s: the
 * steady pressure gradient in the bed is eta v_s/kappa of the bed's porosity,
 * Carman-Kozeny in series with the tube wall (gas.h). */
static void test_darcy_bed(void **state)
{
    (void)state;
    sim_scenario sc;
    mimas_error err;
    sim_scenario_defaults(&sc, SIM_PLUGTUBE);
    sim_scenario_load_string(&sc, "[scenario]\ntype = plugtube\n", "test", &err);
    /* k_n and dt of the standard set, as mimas simulate derives them */
    double m = 937 * M_PI / 6 * pow(0.0014, 3);
    for (int a = 0; a < SIM_MAX_TYPES; a++)
        for (int b = 0; b < SIM_MAX_TYPES; b++)
            sc.contact[a][b].k_n = m * 9.81 / (0.001 * 0.0014);
    sc.dt = 1.4e-5;
    const double R = 0.0035, phi_feed = 0.5;
    sim_feed_block b;
    if (sim_feed_block_make(&b, &sc, R, phi_feed, &err))
        fail_msg("%s", err.msg);
    print_message("# packed block: %zu grains, length %.4g m, porosity %.4f\n", b.n, b.length,
                  b.porosity);
    const int blocks = 6;
    const double L = 3 * blocks * b.length, z0 = blocks * b.length;
    sim_gas g;
    make_gas(&g, 2, (size_t)lround(L / 0.0035), L);
    dem_system s;
    dem_init(&s);
    assert_int_equal(dem_reserve(&s, blocks * b.n, &err), 0);
    for (int k = 0; k < blocks; k++)
        for (size_t i = 0; i < b.n; i++) {
            double x[3] = {b.x[i][0], b.x[i][1], z0 + k * b.length + b.x[i][2]};
            dem_add_particle(&s, 1, 0.0007, 937, x);
        }
    sim_gas_deposit(&g, &s);
    /* to the steady state: diffusion time of the bed << 3000 steps */
    for (int k = 0; k < 3000; k++)
        sim_gas_step(&g, 1.4e-5, 0);
    /* the gradient over the middle half of the bed, averaged over the cross-section */
    size_t nz = g.n[2], k0 = (size_t)((z0 + 0.25 * blocks * b.length) / g.h[2]),
           k1 = (size_t)((z0 + 0.75 * blocks * b.length) / g.h[2]);
    double p0 = 0, p1 = 0, phi_cells = 0;
    for (size_t c = 0; c < 4; c++) {
        p0 += g.pressure[c + 4 * k0] / 4;
        p1 += g.pressure[c + 4 * k1] / 4;
    }
    for (size_t k = k0; k <= k1; k++)
        for (size_t c = 0; c < 4; c++)
            phi_cells += g.porosity[c + 4 * k] / (4.0 * (double)(k1 - k0 + 1));
    double grad = (p0 - p1) / ((double)(k1 - k0) * g.h[2]);
    double expect_block = g.p.eta * g.p.v_s / sim_gas_permeability(&g, b.porosity);
    double expect_cells = g.p.eta * g.p.v_s / sim_gas_permeability(&g, phi_cells);
    print_message("# Darcy bed: porosity %.4f (cells %.4f), dP/dz = %.6g Pa/m, eta v_s/kappa = "
                  "%.6g (%+.2f %%) with the cells' porosity %.6g (%+.2g %%); %zu cells\n",
                  b.porosity, phi_cells, grad, expect_block, 100 * (grad / expect_block - 1),
                  expect_cells, 100 * (grad / expect_cells - 1), nz);
    /* the cells resolve the bed's porosity (the tent smoothing over ~1.5 d of
     * a packing of D/d = 5 with its wall layers) */
    assert_close(phi_cells, b.porosity, 0.01);
    assert_close(grad, expect_block, 0.06 * expect_block);
    assert_close(grad, expect_cells, 0.02 * expect_cells);
    dem_free(&s);
    sim_gas_free(&g);
    sim_feed_block_free(&b);
}

/* effective viscosity of Strauss (2005, eq. 3.67): Re = 65, eta0 = 0.0182 cP gives 0.0672 cP */
static void test_effective_viscosity(void **state)
{
    (void)state;
    double eta = sim_gas_effective_viscosity(1.82e-5, 65);
    assert_close(eta, 6.72e-5, 0.005e-5);
    assert_true(sim_gas_effective_viscosity(1.82e-5, 0) == 1.82e-5);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_disk_rect_area),   cmocka_unit_test(test_cn_conserves),
        cmocka_unit_test(test_gaussian_pulse),   cmocka_unit_test(test_deposit_conserves),
        cmocka_unit_test(test_darcy_bed),        cmocka_unit_test(test_effective_viscosity),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
