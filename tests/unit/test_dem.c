/* The DEM core against analytic results and docs/theory.md check values:
 * binary collisions (linear law, Uhlig's check values, requested restitution,
 * Hertz), energy conservation of an elastic gas, a sphere on an incline,
 * the JKR minimum, thread independence. */
#include <config.h>

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "assert_close.h"
#include "cohesion.h"
#include "contact_force.h"
#include "dem.h"
#include "setup.h"

/* a scenario from INI text on top of the box defaults */
static void load(sim_scenario *sc, const char *text)
{
    mimas_error err;
    int rc = sim_scenario_load_string(sc, text, "test", &err);
    if (rc)
        fail_msg("%s", err.msg);
}

/* Sets up the scenario's system and its first forces, as mimas simulate does. */
static void start(dem_system *s, const sim_scenario *sc, sim_plan *plan)
{
    mimas_error err;
    dem_init(s);
    if (sim_setup(s, sc, plan, &err))
        fail_msg("%s", err.msg);
    sim_plan_apply(plan, s);
    if (dem_neighbours_build(s, &err))
        fail_msg("%s", err.msg);
    dem_forces(s);
}

/* Two particles of the scenario's diameter meeting head-on at relative speed
 * v, just touching at the start; returns the restitution and the time the
 * particles overlap (contact duration) and the time the force is non-zero. */
static void collide(const sim_scenario *sc, double v, double *e, double *t_overlap,
                    double *t_force)
{
    dem_system s;
    dem_init(&s);
    mimas_error err;
    assert_int_equal(dem_reserve(&s, 2, &err), 0);
    double r = sc->diameter / 2, a[3] = {0, 0, 0}, b[3] = {2 * r, 0, 0};
    size_t i = dem_add_particle(&s, 1, r, sc->density, a);
    size_t j = dem_add_particle(&s, 1, r, sc->density, b);
    s.v[i][0] = v / 2;
    s.v[j][0] = -v / 2;
    assert_int_equal(dem_configure(&s, sc, &err), 0);
    assert_int_equal(dem_neighbours_build(&s, &err), 0);
    dem_forces(&s);
    *t_overlap = *t_force = 0;
    for (long k = 0; k < 10000000; k++) {
        assert_int_equal(dem_step(&s, &err), 0);
        double gap = fabs(s.x[1][0] - s.x[0][0]) - 2 * r;
        if (gap < 0)
            *t_overlap += s.dt;
        if (s.f[0][0] != 0)
            *t_force += s.dt;
        if (gap > 0 && s.f[0][0] == 0 && k > 10)
            break;
    }
    /* the particles swap order in the sorted arrays: use ids */
    double v0 = s.id[0] == 1 ? s.v[0][0] : s.v[1][0], v1 = s.id[0] == 1 ? s.v[1][0] : s.v[0][0];
    *e = (v1 - v0) / v;
    dem_free(&s);
}

/* Uhlig (2012), Table 4.2: d = 2 mm, rho = 2000, k_n = 110 N/m, gamma_n = 2e-3 N s/m
 * give t_c = 6.1372e-4 s and e = 0.86371 (without the clip: the contact ends
 * when the overlap does) */
static void test_linear_uhlig_check(void **state)
{
    (void)state;
    sim_scenario sc;
    load(&sc, "[scenario]\ntype = box\n[run]\ndt = 1e-8\n[contact]\nfriction = 0\n"
              "normal_clip = no\n");
    double m = 2000 * 4.0 / 3.0 * M_PI * 1e-9, tc, e;
    dem_linear_collision(110, 2e-3, m / 2, 0, &tc, &e);
    assert_close(tc, 6.1372e-4, 0.6e-8);
    assert_close(e, 0.86371, 0.6e-5);
    double me, t_overlap, t_force;
    collide(&sc, 0.01, &me, &t_overlap, &t_force);
    assert_close(t_overlap, 6.1372e-4, 1e-8);
    assert_close(me, 0.86371, 1e-5);
}

/* a requested restitution is met to 1e-6, with and without the clip */
static void test_linear_requested_restitution(void **state)
{
    (void)state;
    const double es[] = {0.3, 0.9};
    for (int clip = 0; clip < 2; clip++)
        for (size_t k = 0; k < 2; k++) {
            char text[256];
            snprintf(text, sizeof text, "[scenario]\ntype = box\n[run]\ndt = 1e-9\n"
                                        "[contact]\nfriction = 0\nrestitution = %g\n"
                                        "normal_clip = %s\n", es[k], clip ? "yes" : "no");
            sim_scenario sc;
            load(&sc, text);
            double e, t1, t2;
            collide(&sc, 0.01, &e, &t1, &t2);
            print_message("# linear, clip %d: requested e = %g, measured %.9f\n", clip, es[k], e);
            assert_close(e, es[k], 1e-6);
        }
}

/* coarse graining by alpha (docs/theory.md §2.5): k x alpha, gamma x alpha^2, m x alpha^3
 * keep the restitution and stretch the contact time by alpha (sqrt(m/k)) */
static void test_coarse_grain_collision(void **state)
{
    (void)state;
    double e[2], t[2], tf;
    for (int k = 0; k < 2; k++) {
        sim_scenario sc;
        load(&sc, k ? "[scenario]\ntype = box\n[run]\ndt = 1e-8\n[contact]\nfriction = 0\n"
                      "normal_clip = no\n[particles]\ncoarse_grain = 2\n"
                    : "[scenario]\ntype = box\n[run]\ndt = 1e-8\n[contact]\nfriction = 0\n"
                      "normal_clip = no\n");
        sc.diameter *= k ? 2 : 1;   /* collide() uses the diameter as given */
        collide(&sc, 0.01, &e[k], &t[k], &tf);
    }
    print_message("# coarse grain 2: e %.6f -> %.6f, t_c %.6g -> %.6g s\n", e[0], e[1], t[0], t[1]);
    assert_close(e[1], e[0], 1e-5);
    assert_close(t[1], 2 * t[0], 2e-8);
}

/* Hertz (LIGGGHTS form) gives the requested restitution within 2 % */
static void test_hertz_restitution(void **state)
{
    (void)state;
    const double es[] = {0.5, 0.9};
    for (size_t k = 0; k < 2; k++) {
        char text[256];
        snprintf(text, sizeof text, "[scenario]\ntype = box\n[run]\ndt = 1e-8\n[contact]\n"
                                    "model = hertz\nyoungs_modulus = 1e7\nfriction = 0\n"
                                    "restitution = %g\nnormal_clip = no\n", es[k]);
        sim_scenario sc;
        load(&sc, text);
        double e, t1, t2;
        collide(&sc, 0.1, &e, &t1, &t2);
        print_message("# hertz: requested e = %g, measured %.6f\n", es[k], e);
        assert_close(e, es[k], 0.02 * es[k]);
    }
}

static double energy(const dem_system *s)
{
    double E = 0;
    for (size_t k = 0; k < s->n; k++)
        for (int q = 0; q < 3; q++)
            E += 0.5 * s->mass[k] * s->v[k][q] * s->v[k][q] +
                 0.5 * s->inertia[k] * s->w[k][q] * s->w[k][q];
    /* elastic energy of the linear springs */
    for (size_t k = 0; k < s->nl.ne; k++)
        if (s->nl.e[k].flags & DEM_TOUCH) {
            size_t i = 0;
            while (s->nl.start[i + 1] <= k)
                i++;
            double d[3];
            dem_separation(s, s->x[i], s->x[s->nl.e[k].j], d);
            double delta = s->radius[i] + s->radius[s->nl.e[k].j] -
                           sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (delta > 0)
                E += 0.5 * s->law[1][1].k_n * delta * delta;
        }
    return E;
}

/* Frictionless elastic gas: the energy drift over 1000 collisions.  Velocity
 * Verlet's energy error at the entry and exit of a linear contact is of second
 * order in omega dt and does not cancel exactly: the drift is 2.4e-6 at
 * dt = t_c/50 and 3.2e-7 at t_c/100 (it falls as dt^2), so the bound of 1e-6
 * is checked at t_c/100 and 5e-6 at t_c/50. */
static void elastic_gas(int GAS_STEPS, double max_drift)
{
    double m = 2000 * 4.0 / 3.0 * M_PI * 1e-9, kn = 1e4, tc = M_PI / sqrt(kn / (m / 2));
    char text[640];
    snprintf(text, sizeof text, "[scenario]\ntype = box\n[run]\ndt = %.17g\n"
                                "[contact]\nfriction = 0\ndamping_normal = 0\n"
                                "damping_tangential = 0\nstiffness_tangential = 0\n"
                                "stiffness_normal = %g\n[box]\ncount = 2000\nspeed = 0.05\n"
                                "size_x = 0.03\nsize_y = 0.03\nsize_z = 0.03\n",
             tc / GAS_STEPS, kn);
    sim_scenario sc;
    load(&sc, text);
    dem_system s;
    sim_plan plan;
    mimas_error err;
    start(&s, &sc, &plan);
    double E0 = energy(&s), worst = 0;
    long collisions = 0;
    size_t nE = 0, capE = 1024;
    double *Es = malloc(capE * sizeof *Es);
    /* the first 200 collisions bring the gas from the lattice (no contacts)
     * to a steady number of ongoing contacts; then 1000 collisions are timed */
    long warmup = 200;
    while (collisions < warmup + 1000) {
        /* count contacts that begin in this step (their history starts at zero) */
        size_t builds = s.nl.builds;
        unsigned char *was = NULL;
        if (s.nl.ne) {
            was = malloc(s.nl.ne);
            for (size_t k = 0; k < s.nl.ne; k++)
                was[k] = (s.nl.e[k].flags & DEM_TOUCH) != 0;
        }
        assert_int_equal(dem_step(&s, &err), 0);
        if (s.nl.builds == builds)
            for (size_t k = 0; k < s.nl.ne; k++)
                collisions += !was[k] && (s.nl.e[k].flags & DEM_TOUCH);
        free(was);
        double E = energy(&s), dev = fabs(E - E0) / E0;
        if (dev > worst && collisions >= warmup)
            worst = dev;
        if (collisions < warmup)
            continue;
        if (nE == capE)
            Es = realloc(Es, (capE *= 2) * sizeof *Es);
        Es[nE++] = E;
    }
    /* the drift: the mean energy of the last tenth of the run against the
     * first tenth (Verlet's energy fluctuates by O(dt^2) during each contact
     * and returns; a drift does not) */
    size_t w = nE / 10;
    double a = 0, b = 0;
    for (size_t k = 0; k < w; k++) {
        a += Es[k] / (double)w;
        b += Es[nE - w + k] / (double)w;
    }
    double drift = fabs(b - a) / E0;
    print_message("# elastic gas, 2000 particles: 1000 collisions in %zu steps at dt = t_c/%d, "
                  "largest relative energy deviation %.3g, drift %.3g\n", nE, GAS_STEPS,
                  worst, drift);
    assert_true(drift < max_drift);
    assert_true(worst < 1e-4);
    free(Es);
    dem_free(&s);
}

static void test_elastic_gas_energy(void **state)
{
    (void)state;
    elastic_gas(50, 5e-6);
    elastic_gas(100, 1e-6);
}

/* One sphere on a plane tilted by theta (gravity tilted instead): its
 * velocity along the slope between t = 0.5 s and 1 s gives the
 * acceleration. */
static double incline(double tan_theta, double mu, int rotation)
{
    double th = atan(tan_theta), g = 9.81;
    char text[512];
    snprintf(text, sizeof text, "[scenario]\ntype = box\n[run]\ndt = 1e-5\ngravity_x = %.17g\n"
             "gravity_z = %.17g\n[particles]\nrotation = %s\n[contact]\nfriction = %g\n"
             "[box]\ncount = 1\nspeed = 0\nperiodic_z = no\n", g * sin(th), -g * cos(th),
             rotation ? "yes" : "no", mu);
    sim_scenario sc;
    load(&sc, text);
    dem_system s;
    sim_plan plan;
    mimas_error err;
    start(&s, &sc, &plan);
    double v1 = 0;
    /* the landing and the oscillation of the tangential spring have died
     * out after 0.5 s (damping rate gamma_t/2m = 30/s) */
    for (int k = 1; k <= 100000; k++) {
        assert_int_equal(dem_step(&s, &err), 0);
        if (k == 50000)
            v1 = s.v[0][0];
    }
    double a = (s.v[0][0] - v1) / 0.5;
    assert_true(s.x[0][2] < 1.01 * s.radius[0]);   /* still on the plane */
    dem_free(&s);
    return a;
}

static void test_incline(void **state)
{
    (void)state;
    double g = 9.81, mu = 0.5;
    /* without rotation: sticks below tan(theta) = mu, slides above with
     * a = g (sin - mu cos) */
    double a_stick = incline(0.45, mu, 0), a_slide = incline(0.55, mu, 0);
    double th = atan(0.55), expect = g * (sin(th) - mu * cos(th));
    print_message("# incline, mu = 0.5: tan = 0.45 a = %.3g m/s2 (sticks); tan = 0.55 "
                  "a = %.6f, expected %.6f\n", a_stick, a_slide, expect);
    assert_true(fabs(a_stick) < 1e-6);
    assert_close(a_slide, expect, 1e-4 * expect);
    /* with rotation it rolls without slipping while tan(theta) < 3.5 mu:
     * a = (5/7) g sin(theta) */
    double a_roll = incline(0.45, mu, 1), roll = 5.0 / 7.0 * g * sin(atan(0.45));
    print_message("# rolling: a = %.6f, expected %.6f\n", a_roll, roll);
    assert_close(a_roll, roll, 1e-4 * roll);
}

static double jkr_normal_force(double delta, void *p)
{
    const dem_law *L = p;
    dem_contact_geom g = {.n = {1, 0, 0}, .delta = delta, .r_i = 1e-3, .r_j = 1e-3,
                          .R_eff = 0.5e-3, .m_eff = 1e-6};
    double xi[3] = {0, 0, 0}, f[3], ti[3], tj[3];
    dem_contact_force(L, &g, 1e-6, xi, 0, f, ti, tj);
    return f[0];
}

/* Hertz + JKR between two equal spheres: the least normal force is
 * -(3/2) pi w R* at delta_min = ((9/4) pi (w/E~) sqrt(R*))^(2/3) (docs/theory.md §2.4),
 * found here by a numerical minimisation of the contact law's force */
static void test_jkr_minimum(void **state)
{
    (void)state;
    const double ws[] = {0.05, 0.5}, Es[] = {1e7, 5e8};
    for (int k = 0; k < 2; k++) {
        sim_contact_params p = {.model = SIM_HERTZ, .restitution = 0.5, .youngs_modulus = Es[k],
                                .poisson = 0.3, .cohesion_energy = ws[k], .normal_clip = 1};
        dem_law L;
        dem_law_make(&L, &p, 1);
        double Et = Es[k] / (1 - 0.09), R = 0.5e-3;
        double dmin = pow(2.25 * M_PI * ws[k] / Et * sqrt(R), 2.0 / 3.0);
        gsl_function F = {jkr_normal_force, &L};
        gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
        gsl_min_fminimizer_set(m, &F, dmin * 1.3, dmin * 0.01, dmin * 20);
        for (int it = 0; it < 200; it++) {
            gsl_min_fminimizer_iterate(m);
            if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(m),
                                      gsl_min_fminimizer_x_upper(m), 0, 1e-12) == GSL_SUCCESS)
                break;
        }
        double x = gsl_min_fminimizer_x_minimum(m), fmin = gsl_min_fminimizer_f_minimum(m);
        gsl_min_fminimizer_free(m);
        print_message("# JKR w = %g, E = %g: delta_min %.9g (expected %.9g), F_min %.9g "
                      "(expected %.9g)\n", ws[k], Es[k], x, dmin, fmin, -1.5 * M_PI * ws[k] * R);
        assert_close(fmin, -1.5 * M_PI * ws[k] * R, 1e-9 * 1.5 * M_PI * ws[k] * R);
        assert_close(x, dmin, 1e-5 * dmin);
    }
}

/* The pull-off scenario (Uhlig 2012, Sec. 4.1): two spheres of r = 1 mm with a bridge
 * of V_B = 0.1 r^3 pulled apart at 1 mm/s.  The force along the gap is the
 * bridge law's (checked at every step), it is there at contact, vanishes
 * beyond the rupture distance, and its deviation from Willett's fit is
 * reported (Uhlig 2012: about 18 % below on average at theta = 0).  Willett's
 * dimensionless gap is the half-separation (docs/contact-laws.md). */
static void test_pulloff_willett(void **state)
{
    (void)state;
    const double thetas[] = {0, 10, 20};
    const double r = 1e-3, VB = 0.1 * r * r * r;
    /* liquid content D so that each particle carries V_B/2: D = (V_B/2) rho_f/(rho_p V_p) */
    double D = 0.5 * VB * 1000 / (2000 * 4.0 / 3.0 * M_PI * r * r * r);
    for (int a = 0; a < 3; a++) {
        char text[512];
        snprintf(text, sizeof text, "[scenario]\ntype = pulloff\n[run]\ndt = 1e-6\n"
                 "[particles]\nliquid_content = %.17g\n[contact]\ncontact_angle = %g\n"
                 "[pulloff]\nspeed = 1e-3\ndistance = 0.6\n", D, thetas[a]);
        sim_scenario sc;
        load(&sc, text);
        dem_system s;
        sim_plan plan;
        mimas_error err;
        start(&s, &sc, &plan);
        mimas_bridge b = {VB, 0.072, thetas[a] * M_PI / 180};
        double sc_rupture = mimas_bridge_rupture_distance(&b);
        double dev_sum = 0, F0 = fabs(s.f[0][0]);
        int ndev = 0, ruptured_at = -1;
        double last_gap_with_force = -1;
        assert_close(F0, mimas_bridge_force(&b, r, 0), 1e-12 * F0);
        while (s.step < plan.total_steps) {
            assert_int_equal(dem_step(&s, &err), 0);
            double gap = fabs(s.x[1][0] - s.x[0][0]) - 2 * r, F = fabs(s.f[0][0]);
            if (F > 0) {
                /* the law of the bridge, V_B = the liquid of both particles */
                assert_close(F, mimas_bridge_force(&b, r, gap), 1e-9 * F);
                last_gap_with_force = gap;
                double W = mimas_willett_force(&b, r, gap);
                dev_sum += (F - W) / W;
                ndev++;
            } else if (ruptured_at < 0) {
                ruptured_at = (int)s.step;
                assert_true(gap > sc_rupture);
            }
        }
        assert_true(ruptured_at > 0);
        assert_true(sc_rupture - last_gap_with_force < 2 * 1e-3 * 1e-6 + 1e-15);
        print_message("# pull-off, theta = %g deg: F(0) = %.6g N, rupture at s = %.6g m "
                      "(s_c = %.6g), mean deviation from Willett %.2f %%\n", thetas[a], F0,
                      last_gap_with_force, sc_rupture, 100 * dev_sum / ndev);
        /* at the docs/theory.md §2.4 table points s^ (half-separation s/2 sqrt(r/V_B)) */
        const double shat[] = {0.01, 0.1, 0.25, 0.5, 1.0};
        for (int k = 0; k < 5; k++) {
            double gap = 2 * shat[k] * sqrt(VB / r), W = mimas_willett_force(&b, r, gap);
            double F = mimas_bridge_force(&b, r, gap);
            print_message("#   s^ = %-4g: F^ model %.4f, Willett %.4f (%+.1f %%)\n", shat[k],
                          F / (2 * M_PI * r * 0.072), W / (2 * M_PI * r * 0.072),
                          100 * (F - W) / W);
        }
        if (a == 0)   /* Uhlig (2012), Sec. 4.1 reports 18.26 % below Willett at theta = 0 */
            assert_true(fabs(100 * dev_sum / ndev + 18.3) < 1.5);
        dem_free(&s);
    }
}

/* the same run with 1 and 2 threads: bit-identical states */
static void test_threads_identical(void **state)
{
    (void)state;
#ifdef _OPENMP
    sim_scenario sc;
    load(&sc, "[scenario]\ntype = box\n[run]\ndt = 5e-6\ngravity_z = -9.81\n[particles]\n"
              "diameter_spread = 0.2\n[box]\ncount = 400\nperiodic_z = no\nspeed = 0.2\n");
    double (*x[2])[3] = {NULL, NULL}, (*w[2])[3] = {NULL, NULL};
    for (int t = 0; t < 2; t++) {
        omp_set_num_threads(t + 1);
        dem_system s;
        sim_plan plan;
        mimas_error err;
        start(&s, &sc, &plan);
        for (int k = 0; k < 3000; k++)
            if (dem_step(&s, &err))
                fail_msg("%s", err.msg);
        x[t] = malloc(s.n * sizeof *x[t]);
        w[t] = malloc(s.n * sizeof *w[t]);
        memcpy(x[t], s.x, s.n * sizeof *x[t]);
        memcpy(w[t], s.w, s.n * sizeof *w[t]);
        assert_true(s.nl.builds > 1);
        dem_free(&s);
    }
    omp_set_num_threads(1);
    assert_memory_equal(x[0], x[1], 400 * sizeof *x[0]);
    assert_memory_equal(w[0], w[1], 400 * sizeof *w[0]);
    for (int t = 0; t < 2; t++) {
        free(x[t]);
        free(w[t]);
    }
#else
    skip();
#endif
}

int main(void)
{
#ifdef _OPENMP
    omp_set_num_threads(1);   /* two particles: thread start-up would dominate */
#endif
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linear_uhlig_check),
        cmocka_unit_test(test_linear_requested_restitution),
        cmocka_unit_test(test_hertz_restitution),
        cmocka_unit_test(test_coarse_grain_collision),
        cmocka_unit_test(test_elastic_gas_energy),
        cmocka_unit_test(test_incline),
        cmocka_unit_test(test_jkr_minimum),
        cmocka_unit_test(test_pulloff_willett),
        cmocka_unit_test(test_threads_identical),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
