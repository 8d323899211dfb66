/* Energies: the DEM state's kinetic, rotational, elastic (linear and Hertz,
 * particle and wall contacts) and bridge energy against the formulas and an
 * independent quadrature of the force laws; the statistics of mimas energy
 * over the observables of a native file and over the thermo output of a
 * LIGGGHTS log (tests/data/liggghts), against gsl_stats of the same values. */
#include <config.h>

#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "assert_close.h"
#include "cohesion.h"
#include "dem.h"
#include "energy.h"
#include "native.h"
#include "random_frame.h"
#include "scratch.h"
#include "setup.h"

static void load(sim_scenario *sc, const char *text)
{
    mimas_error err;
    if (sim_scenario_load_string(sc, text, "test", &err))
        fail_msg("%s", err.msg);
}

/* Composite Simpson's rule with n (even) intervals. */
static double simpson(double (*f)(double, const void *), const void *ctx, double a, double b,
                      int n)
{
    double h = (b - a) / n, s = f(a, ctx) + f(b, ctx);
    for (int k = 1; k < n; k++)
        s += (k % 2 ? 4 : 2) * f(a + k * h, ctx);
    return s * h / 3;
}

/* Two particles of radius r overlapping by delta along x, at rest; their
 * list entry's spring is then set to xi. */
static void two_touching(dem_system *s, const sim_scenario *sc, double delta, double xi)
{
    mimas_error err;
    dem_init(s);
    assert_int_equal(dem_reserve(s, 2, &err), 0);
    double r = sc->diameter / 2, a[3] = {0.01, 0.01, 0.01}, b[3] = {0.01 + 2 * r - delta, 0.01,
                                                                     0.01};
    dem_add_particle(s, 1, r, sc->density, a);
    dem_add_particle(s, 1, r, sc->density, b);
    assert_int_equal(dem_configure(s, sc, &err), 0);
    assert_int_equal(dem_neighbours_build(s, &err), 0);
    dem_forces(s);
    assert_int_equal(s->nl.ne, 1);
    s->nl.e[0].xi[1] = xi;
}

static const char *const linear = "[scenario]\ntype = box\n[run]\ngravity_z = 0\n"
                                  "[contact]\nstiffness_normal = 110\nstiffness_tangential = 12\n";

static void test_motion_and_linear_springs(void **state)
{
    (void)state;
    sim_scenario sc;
    load(&sc, linear);
    dem_system s;
    two_touching(&s, &sc, 2e-5, 3e-6);
    const double v[2][3] = {{0.1, -0.2, 0.3}, {0, 0.05, 0}}, w[2][3] = {{5, 0, 1}, {0, -2, 0}};
    double kin = 0, rot = 0;
    for (int k = 0; k < 2; k++) {
        double m = 2000 * 4.0 / 3.0 * M_PI * pow(s.radius[k], 3), I = 0.4 * m * pow(s.radius[k], 2);
        for (int q = 0; q < 3; q++) {
            s.v[k][q] = v[k][q];
            s.w[k][q] = w[k][q];
            kin += 0.5 * m * v[k][q] * v[k][q];
            rot += 0.5 * I * w[k][q] * w[k][q];
        }
    }
    dem_energy e;
    mimas_error err;
    assert_int_equal(dem_energies(&s, &e, &err), MIMAS_OK);
    assert_close(e.kinetic, kin, 1e-14 * kin);
    assert_close(e.rotational, rot, 1e-14 * rot);
    double el = 0.5 * 110 * 2e-5 * 2e-5 + 0.5 * 12 * 3e-6 * 3e-6;
    assert_close(e.elastic, el, 1e-9 * el);
    assert_true(e.bridge == 0);
    dem_free(&s);
    /* a particle pressed 1e-5 m into a plane wall of a closed box */
    load(&sc, "[scenario]\ntype = box\n[run]\ngravity_z = 0\n[box]\nperiodic_z = no\n"
              "[contact]\nstiffness_normal = 110\n");
    dem_init(&s);
    assert_int_equal(dem_reserve(&s, 1, &err), 0);
    double x[3] = {0.01, 0.01, 1e-3 - 1e-5};
    dem_add_particle(&s, 1, 1e-3, sc.density, x);
    dem_wall bottom = {.kind = DEM_WALL_PLANE, .id = 1, .normal = {0, 0, 1}};
    assert_int_equal(dem_add_wall(&s, &bottom, &err), 0);
    assert_int_equal(dem_configure(&s, &sc, &err), 0);
    assert_int_equal(dem_neighbours_build(&s, &err), 0);
    dem_forces(&s);
    assert_int_equal(dem_energies(&s, &e, &err), MIMAS_OK);
    assert_close(e.elastic, 0.5 * 110 * 1e-10, 1e-9 * 0.5 * 110 * 1e-10);
    dem_free(&s);
}

typedef struct hertz_ctx {
    double E_star, R_eff;
} hertz_ctx;

static double hertz_force(double x, const void *ctx)
{
    const hertz_ctx *h = ctx;
    return 4.0 / 3.0 * h->E_star * sqrt(h->R_eff * x) * x;
}

static void test_hertz_spring(void **state)
{
    (void)state;
    sim_scenario sc;
    load(&sc, "[scenario]\ntype = box\n[run]\ngravity_z = 0\ndt = 1e-7\n[contact]\nmodel = hertz\n"
              "youngs_modulus = 5e6\npoisson = 0.3\nrestitution = 0.5\n");
    dem_system s;
    two_touching(&s, &sc, 4e-6, 0);
    dem_energy e;
    mimas_error err;
    assert_int_equal(dem_energies(&s, &e, &err), MIMAS_OK);
    /* the work of the Hertz force up to the overlap; E* = E/(2 (1 - nu^2)) for
     * equal materials, R* = r/2 */
    hertz_ctx h = {5e6 / (2 * (1 - 0.09)), 0.5e-3};
    double want = simpson(hertz_force, &h, 0, 4e-6, 2000);
    assert_close(e.elastic, want, 1e-9 * want);
    dem_free(&s);
}

typedef struct bridge_ctx {
    mimas_bridge b;
    double r_p;
} bridge_ctx;

static double bridge_force(double x, const void *ctx)
{
    const bridge_ctx *c = ctx;
    return mimas_bridge_force(&c->b, c->r_p, x);
}

static void test_bridge_work(void **state)
{
    (void)state;
    /* the pull-off pair: V_B = 0.1 r^3 (each particle carries half) */
    const double r = 1e-3, VB = 0.1 * r * r * r;
    double D = 0.5 * VB * 1000 / (2000 * 4.0 / 3.0 * M_PI * r * r * r);
    char text[256];
    snprintf(text, sizeof text, "[scenario]\ntype = pulloff\n[particles]\nliquid_content = "
             "%.17g\n[contact]\ncontact_angle = 10\n", D);
    sim_scenario sc;
    load(&sc, text);
    dem_system s;
    sim_plan plan;
    mimas_error err;
    dem_init(&s);
    assert_int_equal(sim_setup(&s, &sc, &plan, &err), MIMAS_OK);
    assert_int_equal(dem_neighbours_build(&s, &err), MIMAS_OK);
    dem_forces(&s);
    bridge_ctx c = {{VB, 0.072, 10 * M_PI / 180}, r};
    double sc_rupture = mimas_bridge_rupture_distance(&c.b);
    /* at contact and at two gaps: the work to rupture, int_s^s_c F ds */
    const double gaps[3] = {0, 0.1 * sc_rupture, 0.7 * sc_rupture};
    for (int k = 0; k < 3; k++) {
        s.x[1][0] = s.x[0][0] + 2 * r + gaps[k];
        dem_energy e;
        assert_int_equal(dem_energies(&s, &e, &err), MIMAS_OK);
        double want = simpson(bridge_force, &c, gaps[k], sc_rupture, 200000);
        assert_close(e.bridge, want, 1e-7 * want);
        assert_close(dem_bridge_energy(&c.b, r, gaps[k], NULL), want, 1e-7 * want);
        assert_true(e.elastic == 0 && e.kinetic == 0);
    }
    assert_true(dem_bridge_energy(&c.b, r, sc_rupture, NULL) == 0);
    assert_true(dem_bridge_energy(&c.b, r, 2 * sc_rupture, NULL) == 0);
    dem_free(&s);
}

/* ---- statistics ---- */

static void test_native_statistics(void **state)
{
    (void)state;
    const double kin[6] = {1, 2, 4, 3, 5, 8}, rot[6] = {0.5, 0.25, 0.5, 0.75, 1, 0.5};
    mimas_error err;
    mimas_writer *w;
    assert_int_equal(mimas_writer_open(&w, scratch_path("e.h5"), NULL, &err), MIMAS_OK);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    mimas_frame f;
    mimas_frame_init(&f);
    random_frame_spec spec = {10, 0, 0, 0, 0, 0, 0};
    for (int k = 0; k < 6; k++) {
        assert_int_equal(random_frame(&f, rng, &spec, k), 0);
        f.time = 0.1 * k;
        mimas_observable obs[4] = {{"kinetic_energy", "J", kin[k]},
                                   {"rotational_energy", "J", rot[k]},
                                   {"elastic_energy", "J", 1},
                                   {"bridge_energy", "J", 2 * k}};
        assert_int_equal(mimas_writer_observe(w, obs, 4, &err), MIMAS_OK);
        assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_OK);
    }
    assert_int_equal(mimas_writer_close(w, &err), MIMAS_OK);
    mimas_energy_options o;
    mimas_energy_options_default(&o);
    o.from = 0.15;  /* frames 2..5 */
    mimas_energy e;
    assert_int_equal(mimas_energy_of(scratch_path("e.h5"), &o, &e, &err), MIMAS_OK);
    assert_int_equal(e.frames, 4);
    assert_close(e.from, 0.2, 1e-15);
    assert_close(e.to, 0.5, 1e-15);
    double tot[4];
    for (int k = 0; k < 4; k++)
        tot[k] = kin[k + 2] + rot[k + 2];
    const mimas_energy_stat *t = &e.q[MIMAS_ENERGY_TOTAL], *kq = &e.q[MIMAS_ENERGY_KINETIC];
    assert_true(t->present && kq->present && e.q[MIMAS_ENERGY_BRIDGE].present);
    assert_close(t->mean, gsl_stats_mean(tot, 1, 4), 1e-14);
    assert_close(t->sd, gsl_stats_sd(tot, 1, 4), 1e-14);
    assert_close(t->cv, gsl_stats_sd(tot, 1, 4) / gsl_stats_mean(tot, 1, 4), 1e-14);
    assert_close(kq->mean, gsl_stats_mean(kin + 2, 1, 4), 1e-14);
    assert_close(e.q[MIMAS_ENERGY_ELASTIC].sd, 0, 1e-15);
    assert_close(e.q[MIMAS_ENERGY_BRIDGE].mean, 7, 1e-14);
    /* an empty window; a native file without the observables */
    o.from = 9;
    assert_int_equal(mimas_energy_of(scratch_path("e.h5"), &o, &e, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "no frame in the selected time range"));
    mimas_energy_options_default(&o);
    assert_int_equal(mimas_writer_open(&w, scratch_path("none.h5"), NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_OK);
    assert_int_equal(mimas_writer_close(w, &err), MIMAS_OK);
    assert_int_equal(mimas_energy_of(scratch_path("none.h5"), &o, &e, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "none.h5: no energy observables"));
    mimas_frame_free(&f);
    gsl_rng_free(rng);
}

/* KinEng of tests/data/liggghts/hopper_walls/log.hopper as LIGGGHTS printed
 * it: steps 0, 1 (the repeat of step 1 that starts the second run is left
 * out), 4000 .. 48000; timestep 1e-5 s */
static const double hopper_ke[14] = {
    0, 0.0014622611038532509, 0.0077575609691219859, 0.013296280114444428,
    0.00078774525510145945, 0.00027230065449804772, 0.00020235847978154623,
    0.0001152291574924805, 4.1127035088689219e-05, 1.2933185701052623e-05,
    3.5608523449930339e-06, 3.4338560053881137e-06, 2.9753425720775302e-06,
    1.9233712397864274e-06};

static void test_liggghts_log(void **state)
{
    (void)state;
    char path[4096];
    snprintf(path, sizeof path, "%s/data/liggghts/hopper_walls/log.hopper",
             getenv("TEST_SRCDIR") ? getenv("TEST_SRCDIR") : "../tests");
    mimas_energy_options o;
    mimas_energy_options_default(&o);
    mimas_energy e;
    mimas_error err;
    assert_int_equal(mimas_energy_of(path, &o, &e, &err), MIMAS_OK);
    assert_int_equal(e.frames, 14);
    const mimas_energy_stat *k = &e.q[MIMAS_ENERGY_KINETIC];
    assert_true(k->present && !e.q[MIMAS_ENERGY_TOTAL].present &&
                !e.q[MIMAS_ENERGY_ROTATIONAL].present);
    assert_close(k->mean, gsl_stats_mean(hopper_ke, 1, 14), 1e-15);
    assert_close(k->sd, gsl_stats_sd(hopper_ke, 1, 14), 1e-15);
    assert_close(e.to, 0.48, 1e-15);
    /* times from the log's "timestep 1.0e-5": t >= 0.1 s is steps 12000 .. 48000 */
    o.from = 0.1;
    assert_int_equal(mimas_energy_of(path, &o, &e, &err), MIMAS_OK);
    assert_int_equal(e.frames, 10);
    assert_close(e.q[MIMAS_ENERGY_KINETIC].mean, gsl_stats_mean(hopper_ke + 4, 1, 10), 1e-15);
    assert_close(e.from, 0.12, 1e-15);
    /* --timestep overrides it: 1e-6 s makes t >= 0.1 s the steps from 100000: none */
    o.dt = 1e-6;
    assert_int_equal(mimas_energy_of(path, &o, &e, &err), MIMAS_EDATA);
    /* a column for the total; a column the log does not have */
    mimas_energy_options_default(&o);
    o.columns[MIMAS_ENERGY_TOTAL] = "KinEng";
    o.columns[MIMAS_ENERGY_ROTATIONAL] = "rke";
    assert_int_equal(mimas_energy_of(path, &o, &e, &err), MIMAS_OK);
    assert_true(e.q[MIMAS_ENERGY_TOTAL].present && !e.q[MIMAS_ENERGY_ROTATIONAL].present);
    assert_close(e.q[MIMAS_ENERGY_TOTAL].mean, gsl_stats_mean(hopper_ke, 1, 14), 1e-15);
    mimas_energy_options_default(&o);
    o.columns[MIMAS_ENERGY_KINETIC] = "ke";
    assert_int_equal(mimas_energy_of(path, &o, &e, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "log.hopper: no thermo output with ke"));
}

static void test_log_layouts(void **state)
{
    (void)state;
    /* a Time column, runs of other columns, other output inside a run, no
     * timestep command */
    FILE *fp = fopen(scratch_path("log.lammps"), "w");
    fputs("LAMMPS (29 Oct 2020)\nthermo_style custom step time ke c_rke\n"
          "   Step          Time         KinEng            rke \n"
          "       0              0              1            0.5 \n"
          "WARNING: something (src/x.cpp:1)\n"
          "     100           0.01              3            0.5 \n"
          "Loop time of 0.1 on 1 procs for 100 steps with 10 atoms\n\n"
          "   Step         KinEng          Press \n"
          "     100              3             10 \n"
          "     200              5             11 \n"
          "Loop time of 0.1 on 1 procs for 100 steps with 10 atoms\n", fp);
    fclose(fp);
    mimas_energy_options o;
    mimas_energy_options_default(&o);
    o.columns[MIMAS_ENERGY_ROTATIONAL] = "rke";
    mimas_energy e;
    mimas_error err;
    assert_int_equal(mimas_energy_of(scratch_path("log.lammps"), &o, &e, &err), MIMAS_OK);
    assert_int_equal(e.frames, 3);
    const double ke[3] = {1, 3, 5}, tot[2] = {1.5, 3.5};
    assert_close(e.q[MIMAS_ENERGY_KINETIC].mean, gsl_stats_mean(ke, 1, 3), 1e-15);
    assert_close(e.q[MIMAS_ENERGY_KINETIC].sd, gsl_stats_sd(ke, 1, 3), 1e-15);
    /* rotational (and so the total) only in the first run's two rows */
    assert_int_equal(e.q[MIMAS_ENERGY_TOTAL].n, 2);
    assert_close(e.q[MIMAS_ENERGY_TOTAL].mean, gsl_stats_mean(tot, 1, 2), 1e-15);
    assert_true(isnan(e.to)); /* the second run has no Time column and no timestep */
    o.to = 1;
    assert_int_equal(mimas_energy_of(scratch_path("log.lammps"), &o, &e, &err), MIMAS_EUSAGE);
    assert_non_null(strstr(err.msg, "give --timestep"));
    o.dt = 1e-4;
    assert_int_equal(mimas_energy_of(scratch_path("log.lammps"), &o, &e, &err), MIMAS_OK);
    assert_close(e.to, 0.02, 1e-15);
    /* not a log */
    fp = fopen(scratch_path("other.txt"), "w");
    fputs("ITEM: TIMESTEP\n0\n", fp);
    fclose(fp);
    assert_int_equal(mimas_energy_of(scratch_path("other.txt"), &o, &e, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "neither a native file nor a LAMMPS or LIGGGHTS log"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_motion_and_linear_springs),
        cmocka_unit_test(test_hertz_spring),
        cmocka_unit_test(test_bridge_work),
        cmocka_unit_test(test_native_statistics),
        cmocka_unit_test(test_liggghts_log),
        cmocka_unit_test(test_log_layouts),
    };
    return cmocka_run_group_tests(tests, scratch_setup, scratch_teardown);
}
