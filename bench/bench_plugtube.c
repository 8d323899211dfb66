/* Benchmark of the plugtube scenario (docs/simulate.md): the standard set of
 * Strauß (2005, App. A) with the tube holding N grains (fill_count, placed on
 * a lattice and let fall for --warm steps; the tube horizontal, so that they
 * fall at most its diameter: the full tube upright would drop them 0.5 m, at
 * speeds the standard set's soft contacts do not stop), then --steps steps timed with
 * the gas-pressure model on and with no gas.  Prints particle-steps/s of
 * both, the simulated seconds per CPU hour, and the cost of the gas model
 * in a step: its three parts (deposit, gas step, drag) timed on their own
 * on the final state (the runs with and without gas differ in their
 * neighbour-list rebuilds, so their difference is not the gas's cost).
 * Times are CPU seconds of the process (all threads), which a loaded machine
 * disturbs far less than wall times; print `uptime` with the figures, and
 * compare instruction counts (valgrind --tool=callgrind) where it matters. */
#include <config.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "gas.h"
#include "setup.h"

/* the process's CPU time (all threads): robust on a loaded machine */
static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* seconds per step of the standard set with n grains and the given gas model */
static double run(long n, long warm, long steps, const char *gas, int every, double *dt,
                  size_t *particles, double *gas_cost)
{
    char text[512];
    snprintf(text, sizeof text,
             "[scenario]\ntype = plugtube\n[plugtube]\norientation = horizontal\n"
             "fill_count = %ld\ntime = 1e9\n"
             "[gas]\nmodel = %s\nevery = %d\n", n, gas, every);
    sim_scenario sc;
    mimas_error err;
    dem_system s;
    sim_plan plan;
    dem_init(&s);
    if (sim_scenario_load_string(&sc, text, "bench", &err) || sim_setup(&s, &sc, &plan, &err) ||
        dem_neighbours_build(&s, &err)) {
        fprintf(stderr, "bench_plugtube: %s\n", err.msg);
        exit(1);
    }
    dem_forces(&s);
    for (long k = 0; k < warm; k++)
        if (dem_step(&s, &err)) {
            fprintf(stderr, "bench_plugtube: %s\n", err.msg);
            exit(1);
        }
    double t0 = now();
    size_t sum = 0;
    for (long k = 0; k < steps; k++) {
        if (dem_step(&s, &err)) {
            fprintf(stderr, "bench_plugtube: %s\n", err.msg);
            exit(1);
        }
        sum += s.n;
    }
    double t = (now() - t0) / (double)steps;
    *dt = s.dt;
    *particles = sum / (size_t)steps;
    sim_gas *g = sim_tube_gas(plan.tube);
    if (g && gas_cost) {
        /* what the gas model adds to a step: deposit, gas step and the held
         * drag every `every` steps (dem_forces adds the held drag with gravity) */
        double t1 = now();
        for (long k = 0; k < steps; k += every) {
            sim_gas_deposit(g, &s);
            sim_gas_step(g, s.dt * every, 0);
            sim_gas_drag_held(g, &s, s.held);
        }
        *gas_cost = (now() - t1) / (double)steps;
    }
    sim_plan_free(&plan, &s);
    dem_free(&s);
    return t;
}

int main(int argc, char **argv)
{
    long n = 3000, warm = 20000, steps = 5000; /* the fill lattice holds 9 x 367 */
    int every = 1, threads = 1;
    for (int k = 1; k + 1 < argc; k += 2) {
        if (!strcmp(argv[k], "--particles"))
            n = atol(argv[k + 1]);
        else if (!strcmp(argv[k], "--warm"))
            warm = atol(argv[k + 1]);
        else if (!strcmp(argv[k], "--steps"))
            steps = atol(argv[k + 1]);
        else if (!strcmp(argv[k], "--every"))
            every = atoi(argv[k + 1]);
        else if (!strcmp(argv[k], "--threads"))
            threads = atoi(argv[k + 1]);
        else {
            fprintf(stderr, "usage: bench_plugtube [--particles N] [--warm STEPS] [--steps STEPS] "
                            "[--every K] [--threads T]\n");
            return 1;
        }
    }
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    double dt;
    size_t np_gas, np_none;
    double gas_cost = 0;
    double t_gas = run(n, warm, steps, "pressure", every, &dt, &np_gas, &gas_cost);
    double t_none = run(n, warm, steps, "none", every, &dt, &np_none, NULL);
    printf("plugtube standard set, %ld grains filled, %ld warm-up + %ld timed steps, dt = %.4g s, "
           "%d thread(s), gas every %d step(s)\n", n, warm, steps, dt, threads, every);
    printf("  gas model on:  %zu particles, %.4g CPU s/step, %.3g particle-steps/s, %.3g simulated "
           "s per CPU hour\n", np_gas, t_gas, (double)np_gas / t_gas, 3600 * dt / t_gas);
    printf("  no gas:        %zu particles, %.4g s/step, %.3g particle-steps/s\n", np_none, t_none,
           (double)np_none / t_none);
    printf("  gas model (deposit, step and drag every %d steps): %.4g s/step = %.1f %% "
           "of a step with gas, %.1f %% of the DEM part\n", every, gas_cost,
           100 * gas_cost / t_gas, 100 * gas_cost / (t_gas - gas_cost));
    return 0;
}
