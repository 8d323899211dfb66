/* Benchmark of the DEM core on the split-bottom ring shear cell (docs/theory.md §7.1
 * contact law: linear, k_n = 110, k_t = 12, gamma_n = 2e-3, gamma_t = 0.5e-3,
 * mu = 0.01, d = 2 mm monodisperse, smooth walls, dt = 5e-6 s, skin 0.2 mm).
 * The cell is filled, settles (dt = 1e-5 s for --settle seconds), the
 * velocities are zeroed and the settled packing is written as a LAMMPS data
 * file (--data FILE) for bench/liggghts/run.sh; then --steps shear steps are
 * timed with 1 and 2 threads.  Prints particle-steps per second (wall) and
 * per CPU second.
 * With --packing FILE the settled packing is read from such a data file
 * instead (no settling), so both codes start from the same file.
 *   bench_simulate [--particles N] [--settle T] [--steps S] [--data FILE] [--packing FILE] */
#include <config.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "dem.h"
#include "setup.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double cpu(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return (double)u.ru_utime.tv_sec + 1e-6 * (double)u.ru_utime.tv_usec +
           (double)u.ru_stime.tv_sec + 1e-6 * (double)u.ru_stime.tv_usec;
}

static void write_data(const dem_system *s, const char *path)
{
    FILE *fp = fopen(path, "w");
    if (!fp) {
        perror(path);
        exit(1);
    }
    double zmax = 0;
    for (size_t k = 0; k < s->n; k++)
        if (s->x[k][2] + s->radius[k] > zmax)
            zmax = s->x[k][2] + s->radius[k];
    double R = s->walls[2].radius;
    fprintf(fp, "mimas settled ring shear packing\n\n%zu atoms\n1 atom types\n\n"
                "%.17g %.17g xlo xhi\n%.17g %.17g ylo yhi\n0 %.17g zlo zhi\n\nAtoms\n\n",
            s->n, -R, R, -R, R, zmax);
    for (size_t k = 0; k < s->n; k++)
        fprintf(fp, "%lld 1 %.17g %.17g %.17g %.17g %.17g\n", (long long)s->id[k],
                2 * s->radius[k], s->mass[k] / (4.0 / 3.0 * 3.141592653589793 * s->radius[k] *
                                                s->radius[k] * s->radius[k]),
                s->x[k][0], s->x[k][1], s->x[k][2]);
    fclose(fp);
}

/* replaces the particles by those of a LAMMPS data file (id type d rho x y z) */
static long read_packing(dem_system *s, const char *path)
{
    FILE *fp = fopen(path, "r");
    if (!fp) {
        perror(path);
        exit(1);
    }
    char line[512];
    int atoms = 0;
    s->n = 0;
    mimas_error err;
    while (fgets(line, sizeof line, fp)) {
        long long id;
        int type;
        double d, rho, x[3];
        if (!strncmp(line, "Atoms", 5))
            atoms = 1;
        else if (atoms && sscanf(line, "%lld %d %lf %lf %lf %lf %lf", &id, &type, &d, &rho, &x[0],
                                 &x[1], &x[2]) == 7) {
            if (dem_reserve(s, s->n + 1, &err))
                exit(1);
            dem_add_particle(s, 1, d / 2, rho, x);
        }
    }
    fclose(fp);
    return (long)s->n;
}

int main(int argc, char **argv)
{
    long n = 10000, steps = 2000;
    double settle = 0.08;
    const char *data = NULL, *packing = NULL;
    for (int k = 1; k + 1 < argc; k += 2) {
        if (!strcmp(argv[k], "--particles"))
            n = atol(argv[k + 1]);
        else if (!strcmp(argv[k], "--steps"))
            steps = atol(argv[k + 1]);
        else if (!strcmp(argv[k], "--settle"))
            settle = atof(argv[k + 1]);
        else if (!strcmp(argv[k], "--data"))
            data = argv[k + 1];
        else if (!strcmp(argv[k], "--packing"))
            packing = argv[k + 1];
    }
    sim_scenario sc;
    sim_scenario_defaults(&sc, SIM_RINGSHEAR);
    sc.diameter_spread = 0;
    sc.rough_bottom = 0;
    sc.count = n;
    /* the two cells of bench/liggghts/README.md */
    if (n <= 30000) {
        sc.r_in = 0.0059;
        sc.r_split = 0.034;
        sc.r_out = 0.044;
    }
    sc.dt = 1e-5;
    sc.settle_time = settle;
    mimas_error err;
    dem_system s;
    dem_init(&s);
    sim_plan plan;
    if (packing) {
        /* the cell of the packing's size; its particles replace the inserted ones */
        sc.count = 1;
        settle = 0;
        if (sim_setup(&s, &sc, &plan, &err) || (read_packing(&s, packing) < 1) ||
            dem_configure(&s, &sc, &err)) {
            fprintf(stderr, "bench_simulate: %s: no packing\n", packing);
            return 1;
        }
    }
    if ((!packing && sim_setup(&s, &sc, &plan, &err)) || dem_neighbours_build(&s, &err)) {
        fprintf(stderr, "bench_simulate: %s\n", err.msg);
        return 1;
    }
    dem_forces(&s);
    double t0 = now();
    long settle_steps = (long)(settle / sc.dt);
    for (long k = 0; k < settle_steps; k++)
        if (dem_step(&s, &err)) {
            fprintf(stderr, "bench_simulate: %s\n", err.msg);
            return 1;
        }
    printf("ring shear cell: %zu particles (r_in %g, r_split %g, r_out %g m), settled %g s "
           "in %.1f s\n", s.n, sc.r_in, sc.r_split, sc.r_out, settle, now() - t0);
    memset(s.v, 0, s.n * sizeof *s.v);
    memset(s.w, 0, s.n * sizeof *s.w);
    if (data) {
        write_data(&s, data);
        printf("settled packing written to %s\n", data);
    }
    s.dt = 5e-6;
    plan.move_from = 0;
    sim_plan_apply(&plan, &s);
    size_t builds0 = s.nl.builds;
    for (int threads = 1; threads <= 2; threads++) {
#ifdef _OPENMP
        omp_set_num_threads(threads);
#else
        if (threads > 1)
            break;
#endif
        double w0 = now(), c0 = cpu();
        for (long k = 0; k < steps; k++)
            dem_step(&s, &err);
        double w = now() - w0, c = cpu() - c0, ps = (double)s.n * (double)steps;
        size_t contacts = 0;
        for (size_t k = 0; k < s.nl.ne; k++)
            contacts += (s.nl.e[k].flags & DEM_TOUCH) != 0;
        printf("  %d thread%s: %ld steps in %.2f s: %.3g particle-steps/s, %.3g per CPU "
               "second (%.2f pairs listed and %.2f contacts per particle)\n", threads,
               threads > 1 ? "s" : " ", steps, w, ps / w, ps / c,
               (double)s.nl.ne / (double)s.n, (double)contacts / (double)s.n);
    }
    printf("  neighbour lists built %zu times during the timed steps\n", s.nl.builds - builds0);
    dem_free(&s);
    return 0;
}
