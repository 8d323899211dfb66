/* The plugtube scenario against analytic results: a sphere settling in a
 * fluid at rest reaches the terminal velocity of its drag law (Stokes: the
 * check value 0.02180 m/s of Uhlig 2012, Sec. 4.3; Schiller-Naumann,
 * Haider-Levenspiel and the wall factors: solved here by root finding), and
 * in a frictionless vertical conveying run the time-averaged pressure drop
 * carries the weight of the grains in the tube (Strauß 2005: within 5 %).
 * Also: particles come and go with unique ids and contact histories that
 * survive the renumbering; and plugs form in the standard set. */
#include <config.h>

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "assert_close.h"
#include "drag.h"
#include "setup.h"

static void load(sim_scenario *sc, const char *text)
{
    mimas_error err;
    if (sim_scenario_load_string(sc, text, "test", &err))
        fail_msg("%s", err.msg);
}

static void start(dem_system *s, const sim_scenario *sc, sim_plan *plan)
{
    mimas_error err;
    dem_init(s);
    if (sim_setup(s, sc, plan, &err))
        fail_msg("%s", err.msg);
    if (dem_neighbours_build(s, &err))
        fail_msg("%s", err.msg);
    dem_forces(s);
}

/* the vertical velocity of the one sphere after `time` of settling */
static double settle(double d, double rho_p, double rho_f, double eta, double D,
                     const char *law, const char *wall, double time)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[scenario]\ntype = plugtube\n[particles]\ndiameter = %.17g\ndensity = %.17g\n"
             "[plugtube]\ndiameter = %.17g\nlength = 1\nmass_flow = 0\nfill_count = 1\n"
             "time = %.17g\n[gas]\nmodel = fluid-at-rest\nfluid_density = %.17g\n"
             "viscosity = %.17g\ndrag_law = %s\nwall_factor = %s\n",
             d, rho_p, D, time, rho_f, eta, law, wall);
    sim_scenario sc;
    load(&sc, text);
    dem_system s;
    sim_plan plan;
    mimas_error err;
    start(&s, &sc, &plan);
    assert_int_equal(s.n, 1);
    while (s.step < plan.total_steps)
        if (dem_step(&s, &err))
            fail_msg("%s", err.msg);
    assert_int_equal(s.n, 1);
    double v = s.v[0][2];
    sim_plan_free(&plan, &s);
    dem_free(&s);
    return v;
}

typedef struct terminal_par {
    int law, wall;
    double d, D, rho_p, rho_f, eta;
} terminal_par;

/* drag at speed u (the wall factor at the bounded Re, the free law at u/f_W)
 * minus the weight less buoyancy, written out here from the formulas of
 * docs/theory.md §5 */
static double excess(double u, void *vp)
{
    const terminal_par *p = vp;
    double re = p->rho_f * p->d * u / p->eta, x = p->d / p->D, f = 1;
    if (p->wall == WALL_FACTOR_FRANCIS)
        f = pow(1 - x, 2.25);
    else if (p->wall == WALL_FACTOR_ATAIDE)
        f = 1.092 / (1 + 0.1 * exp(8.54 * x) * pow(fmin(310.7, fmax(0.38, re)), -0.042 - 0.939 * x));
    double w = u / f, rw = p->rho_f * p->d * w / p->eta, cd;
    if (p->law == DRAG_STOKES)
        cd = 24 / rw;
    else if (p->law == DRAG_SCHILLER_NAUMANN)
        cd = 24 / rw * (1 + 0.15 * pow(rw, 0.687));
    else
        cd = 24 / rw * (1 + 0.1806 * pow(rw, 0.6459)) + 0.4251 / (1 + 6880.95 / rw);
    double drag = M_PI * p->d * p->d * p->rho_f * w * w * cd / 8;
    return drag - (p->rho_p - p->rho_f) * M_PI / 6 * pow(p->d, 3) * 9.81;
}

static double terminal(const terminal_par *p)
{
    gsl_function F = {excess, (void *)p};
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_root_fsolver_set(s, &F, 1e-6, 10);
    double u = 0;
    for (int it = 0; it < 200; it++) {
        gsl_root_fsolver_iterate(s);
        u = gsl_root_fsolver_root(s);
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 0,
                                   1e-14) == GSL_SUCCESS)
            break;
    }
    gsl_root_fsolver_free(s);
    return u;
}

/* Uhlig's sphere (d = 0.04 m, rho_p = 1.5, rho_f = 1 kg/m^3, eta = 0.02 Pa s):
 * Stokes' terminal velocity d^2 g (rho_p - rho_f)/(18 eta) = 0.02180 m/s */
static void test_settling_stokes(void **state)
{
    (void)state;
    double v = settle(0.04, 1.5, 1, 0.02, 0.5, "stokes", "none", 0.3);
    print_message("# Stokes: settling velocity %.7f m/s (check value 0.02180)\n", -v);
    assert_close(-v, 0.02180, 5e-6);
    assert_close(-v, 0.04 * 0.04 * 9.81 * 0.5 / (18 * 0.02), 1e-9);
    /* Francis' wall factor in a tube of D = 0.2 m: (1 - 0.2)^2.25 of it */
    double vf = settle(0.04, 1.5, 1, 0.02, 0.2, "stokes", "francis", 0.3);
    print_message("# Stokes in a tube (Francis): %.7f m/s = %.6f of the free one\n", -vf, vf / v);
    assert_close(vf / v, pow(0.8, 2.25), 1e-7);
}

/* the transition regime (Uhlig's second sphere, d = 0.06 m, eta = 0.0105 Pa s,
 * Re about 0.5) and the wall factor of Ataide in Uhlig's container of D = 0.5 m */
static void test_settling_transition(void **state)
{
    (void)state;
    struct {
        const char *law, *wall;
        int l, w;
        double D;
    } cases[] = {{"schiller-naumann", "none", DRAG_SCHILLER_NAUMANN, WALL_FACTOR_NONE, 1},
                 {"haider-levenspiel", "none", DRAG_HAIDER_LEVENSPIEL, WALL_FACTOR_NONE, 1},
                 {"schiller-naumann", "ataide", DRAG_SCHILLER_NAUMANN, WALL_FACTOR_ATAIDE, 0.5}};
    for (int k = 0; k < 3; k++) {
        terminal_par p = {cases[k].l, cases[k].w, 0.06, cases[k].D, 1.5, 1, 0.0105};
        double u = terminal(&p), v = -settle(0.06, 1.5, 1, 0.0105, cases[k].D, cases[k].law,
                                             cases[k].wall, 1.0);
        print_message("# %s, wall %s: settling %.7f m/s, terminal velocity solved %.7f "
                      "(Re = %.3f)\n", cases[k].law, cases[k].wall, v, u, 0.06 * u / 0.0105);
        assert_close(v, u, 1e-6 * u);
    }
}

/* A frictionless vertical run in a short tube: after the tube has filled,
 * the time-averaged gas force on the tube, A (P_inlet - P_outlet), and the
 * push of the feed column on the grains balance the weight of the grains in
 * the tube plus the momentum they carry out minus in (without wall friction
 * nothing else acts along the tube), within 5 %; and, as Strauss (2005)
 * finds, the pressure drop alone equals the weight within 5 %. */
static void test_frictionless_balance(void **state)
{
    (void)state;
    sim_scenario sc;
    load(&sc, "[scenario]\ntype = plugtube\n[contact]\nfriction = 0\n[plugtube]\n"
              "length = 0.05\ntime = 3\n");
    dem_system s;
    sim_plan plan;
    mimas_error err;
    start(&s, &sc, &plan);
    mimas_frame f;
    mimas_frame_init(&f);
    const double t0 = 1.5, A = M_PI * 0.0035 * 0.0035, L = 0.05;
    int64_t *seen = calloc(1 << 20, sizeof *seen);   /* by id: 1 released, 2 gone out */
    double sum_dp = 0, sum_w = 0, sum_col = 0, p_out = 0, p_in = 0;
    long samples = 0;
    while (s.step < plan.total_steps) {
        if (dem_step(&s, &err))
            fail_msg("%s", err.msg);
        double t = (double)s.step * s.dt;
        for (size_t k = 0; k < s.n; k++) {
            int64_t id = s.id[k];
            assert_true(id < (1 << 20));
            if (s.glued[k] < 0 && !seen[id]) {
                seen[id] = 1;
                if (t >= t0)
                    p_in += s.mass[k] * s.v[k][2];
            }
            if (s.glued[k] < 0 && seen[id] == 1 && s.x[k][2] >= L) {
                seen[id] = 2;
                if (t >= t0)
                    p_out += s.mass[k] * s.v[k][2];
            }
        }
        if (t < t0 || s.step % 50)
            continue;
        if (sim_frame_fill(&s, &plan, &f, &err))
            fail_msg("%s", err.msg);
        /* the pressure at the inlet z = 0: the grid reaches below it into the
         * feed column; z = 0 is a face, between layers kb and kb + 1 */
        const mimas_gas *g = &f.gas;
        size_t layer = g->cells[0] * g->cells[1];
        long kb = lround(-g->origin[2] / g->spacing[2]) - 1;
        assert_true(kb >= 0 && fabs(g->origin[2] + (double)(kb + 1) * g->spacing[2]) < 1e-12);
        double pin = 0;
        for (size_t c = 0; c < layer; c++)
            pin += 0.5 * (g->pressure[(size_t)kb * layer + c] +
                          g->pressure[(size_t)(kb + 1) * layer + c]) / (double)layer;
        double w = 0;
        for (size_t k = 0; k < s.n; k++)
            if (s.glued[k] < 0 && s.x[k][2] >= 0 && s.x[k][2] < L)
                w += s.mass[k] * 9.81;
        /* the push of the feed column: contacts of a glued grain with a free one */
        double col = 0;
        for (size_t i = 0; i < s.n; i++)
            for (size_t k = s.nl.start[i]; k < s.nl.start[i + 1]; k++) {
                size_t j = (size_t)s.nl.e[k].j;
                double fj = s.nl.eft[s.nl.tpos[k]].f[2];   /* force on j; on i: -fj */
                if (s.glued[i] >= 0 && s.glued[j] < 0)
                    col += fj;
                else if (s.glued[i] < 0 && s.glued[j] >= 0)
                    col -= fj;
            }
        sum_dp += pin;
        sum_w += w;
        sum_col += col;
        samples++;
    }
    double T = (double)plan.total_steps * s.dt - t0, dp = sum_dp / samples, W = sum_w / samples;
    double flux = (p_out - p_in) / T, C = sum_col / samples;
    print_message("# frictionless, L = 0.05 m: A <dP> = %.5g N, feed column %.3g N, <weight> = "
                  "%.5g N (%.0f grains), momentum out - in %.3g N: (A dP + column)/(weight + "
                  "flux) = %.4f, A dP/weight = %.4f\n", A * dp, C, W,
                  W / (9.81 * s.mass[s.n - 1]), flux, (A * dp + C) / (W + flux), A * dp / W);
    assert_true(W > 0);
    assert_close(A * dp + C, W + flux, 0.05 * (W + flux));
    /* the gas flows through the feed column into the tube, so the column
     * barely pushes: the pressure drop alone carries the weight (Strauß) */
    assert_close(A * dp, W, 0.05 * W);
    free(seen);
    mimas_frame_free(&f);
    sim_plan_free(&plan, &s);
    dem_free(&s);
}

/* Removing particles keeps the others' contact histories; added ones get new ids. */
static void test_remove_keeps_history(void **state)
{
    (void)state;
    sim_scenario sc;
    load(&sc, "[scenario]\ntype = box\n[run]\ndt = 5e-6\ngravity_z = -9.81\n[contact]\n"
              "friction = 0.5\n[box]\ncount = 200\nperiodic_z = no\nspeed = 0.2\n");
    dem_system s;
    sim_plan plan;
    mimas_error err;
    start(&s, &sc, &plan);
    for (int k = 0; k < 30000; k++)   /* settled on the floor */
        assert_int_equal(dem_step(&s, &err), 0);
    /* the tangential springs of the touching pairs, by the ids of the pair */
    typedef struct { int64_t a, b; double xi[3]; } spring;
    spring *before = malloc(s.nl.ne * sizeof *before);
    size_t nb = 0;
    uint8_t *drop = calloc(s.n, 1);
    for (size_t k = 0; k < s.n; k += 3)
        drop[k] = 1;
    for (size_t i = 0; i < s.n; i++)
        for (size_t k = s.nl.start[i]; k < s.nl.start[i + 1]; k++) {
            size_t j = (size_t)s.nl.e[k].j;
            if ((s.nl.e[k].flags & DEM_TOUCH) && !drop[i] && !drop[j]) {
                before[nb] = (spring){s.id[i], s.id[j], {0}};
                memcpy(before[nb].xi, s.nl.e[k].xi, sizeof before[nb].xi);
                nb++;
            }
        }
    assert_true(nb > 20);
    int64_t last = s.last_id;
    size_t n0 = s.n;
    assert_int_equal(dem_remove(&s, drop, &err), 0);
    double x[3] = {0.001, 0.001, 0.019};
    size_t p = dem_add_particle(&s, 1, 0.001, 2000, x);
    assert_true(s.id[p] == last + 1);
    assert_int_equal(dem_neighbours_build(&s, &err), 0);
    assert_int_equal(s.n, n0 - (n0 + 2) / 3 + 1);
    size_t found = 0;
    for (size_t m = 0; m < nb; m++)
        for (size_t i = 0; i < s.n; i++)
            for (size_t k = s.nl.start[i]; k < s.nl.start[i + 1]; k++) {
                int64_t a = s.id[i], b = s.id[s.nl.e[k].j];
                double sign = a == before[m].a && b == before[m].b   ? 1
                              : a == before[m].b && b == before[m].a ? -1
                                                                     : 0;
                if (sign == 0)
                    continue;
                for (int q = 0; q < 3; q++)
                    assert_true(s.nl.e[k].xi[q] == sign * before[m].xi[q]);
                found++;
            }
    assert_int_equal(found, nb);
    free(before);
    free(drop);
    dem_free(&s);
}

/* volume of a sphere (centre z0, radius r) below the plane z */
static double sphere_below(double z0, double r, double z)
{
    double u = fmin(r, fmax(-r, z - z0));
    return M_PI * (r * r * (u + r) - (u * u * u + r * r * r) / 3);
}

/* Runs of at least `run` slices with porosity below `dense`, each after the
 * first separated from the previous one by at least `run` consecutive
 * slices above `loose` (a gap of nearly empty tube): their number. */
static int separated_dense_runs(const double *phi, int n, double dense, double loose, int run)
{
    int found = 0, len = 0, gap = 0, gap_ok = 0, counted = 0;
    for (int i = 0; i <= n; i++) {
        int is_dense = i < n && phi[i] < dense;
        if (is_dense) {
            len++;
            if (len >= run && !counted && (found == 0 || gap_ok)) {
                found++;
                counted = 1;
            }
            gap = 0;
            continue;
        }
        if (len > 0) {   /* a dense run ended */
            len = 0;
            if (counted)
                gap_ok = 0;
            counted = 0;
        }
        gap = i < n && phi[i] > loose ? gap + 1 : 0;
        if (gap >= run)
            gap_ok = 1;
    }
    return found;
}

/* Plugs form: the standard set (vertical, mu = 0.5) in a 0.1 m tube.  From
 * the start of the feed the grains entering the tube are lifted in packets
 * (Strauß 2005, Sec. 5.2): the axial porosity profile (slices of width d,
 * exact sphere-slab volumes, computed here from the particles) shows, in a
 * quarter of the frames between 0.3 and 0.8 s at least, two or more dense
 * runs (porosity < 0.6, at least 2 d long) separated by nearly empty tube
 * (porosity > 0.8 over at least 2 d).  A homogeneous fluidised bed (the
 * state of a gas grid with 2 x 2 cells across) shows one at most. */
static void test_plugs_form(void **state)
{
    (void)state;
    sim_scenario sc;
    load(&sc, "[scenario]\ntype = plugtube\n[plugtube]\nlength = 0.1\ntime = 0.8");
    dem_system s;
    sim_plan plan;
    mimas_error err;
    start(&s, &sc, &plan);
    const double R = 0.0035, d = 0.0014, L = 0.1, A = M_PI * R * R;
    enum { NS = 71 };   /* slices of width d over 0.1 m */
    double phi[NS];
    int frames = 0, with_plugs = 0;
    const long every = lround(0.025 / s.dt), from = lround(0.3 / s.dt);
    while (s.step < plan.total_steps) {
        if (dem_step(&s, &err))
            fail_msg("%s", err.msg);
        if (s.step < from || s.step % every)
            continue;
        double solid[NS] = {0};
        for (size_t k = 0; k < s.n; k++) {
            double z = s.x[k][2], r = s.radius[k];
            if (s.glued[k] >= 0 || z < -r || z > L + r)
                continue;
            for (int i = (int)floor((z - r) / d); i <= (int)floor((z + r) / d); i++)
                if (i >= 0 && i < NS)
                    solid[i] += sphere_below(z, r, (i + 1) * d) - sphere_below(z, r, i * d);
        }
        for (int i = 0; i < NS; i++)
            phi[i] = 1 - solid[i] / (A * d);
        int runs = separated_dense_runs(phi, NS, 0.6, 0.8, 2);
        frames++;
        with_plugs += runs >= 2;
        char line[NS + 1];
        for (int i = 0; i < NS; i++)
            line[i] = phi[i] < 0.5 ? '#' : phi[i] < 0.6 ? '=' : phi[i] < 0.8 ? '-' : ' ';
        line[NS] = 0;
        print_message("# t = %.2f s |%s| %d separated dense runs\n", (double)s.step * s.dt, line,
                      runs);
    }
    print_message("# %d of %d frames with two or more plugs\n", with_plugs, frames);
    assert_true(frames >= 20);
    assert_true(4 * with_plugs >= frames);   /* in a quarter of the frames at least */
    sim_plan_free(&plan, &s);
    dem_free(&s);
}

/* the run counter on profiles made by hand */
static void test_separated_runs(void **state)
{
    (void)state;
    const double a[] = {0.5, 0.5, 0.5, 0.9, 0.9, 0.9, 0.5, 0.5, 0.5};   /* two, gap 3 */
    const double b[] = {0.5, 0.5, 0.5, 0.7, 0.7, 0.7, 0.5, 0.5, 0.5};   /* no loose gap */
    const double c[] = {0.5, 0.5, 0.9, 0.9, 0.9, 0.9, 0.5, 0.5, 0.5};   /* first too short */
    const double e[] = {0.5, 0.5, 0.5, 0.9, 0.9, 0.7, 0.5, 0.5, 0.5};   /* gap too short */
    const double f[] = {0.5, 0.5, 0.5, 0.9, 0.9, 0.9, 0.5, 0.5, 0.5, 0.5, 0.9, 0.9, 0.9, 0.4,
                        0.4, 0.4};                                          /* three */
    assert_int_equal(separated_dense_runs(a, 9, 0.6, 0.8, 3), 2);
    assert_int_equal(separated_dense_runs(b, 9, 0.6, 0.8, 3), 1);
    assert_int_equal(separated_dense_runs(c, 9, 0.6, 0.8, 3), 1);
    assert_int_equal(separated_dense_runs(e, 9, 0.6, 0.8, 3), 1);
    assert_int_equal(separated_dense_runs(f, 16, 0.6, 0.8, 3), 3);
}

int main(void)
{
#ifdef _OPENMP
    omp_set_num_threads(1);
#endif
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_settling_stokes),
        cmocka_unit_test(test_settling_transition),
        cmocka_unit_test(test_remove_keeps_history),
        cmocka_unit_test(test_frictionless_balance),
        cmocka_unit_test(test_separated_runs),
        cmocka_unit_test(test_plugs_form),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
