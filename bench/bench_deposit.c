/* Benchmark of the deposits alone: the weights one particle (a sphere) or one contact
 * (a branch segment) puts on the cells, without the sums they are then added to;
 * 20,000 objects at random in a periodic 46 mm box, a grid of 1 mm cells (46^3 x-y-z,
 * or r-z 46 x 46 about the box's z edge), branches 1 mm long (--length), spheres of
 * radius 0.5 mm.  Prints the time per object, the shortest of several passes over the
 * same objects (on a shared machine a pass scatters by up to 1.5x; the shortest is what
 * the deposit takes when nothing else runs), and the sum of all weights, which two
 * builds that give the same weights print to the last digit.
 *   bench_deposit [--only CASE] [--passes P] [--length L] [--weight W] */
#include <config.h>

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "deposit.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

enum { N_OBJECTS = 20000 };

static void run(const char *name, const char *grid, const char *weight, int segments,
                double len, int passes)
{
    const double L = 0.046;
    mimas_grid g;
    mimas_weight w;
    mimas_error err;
    if (mimas_grid_parse(&g, grid, NULL, &err) || mimas_weight_parse(&w, weight, &err)) {
        fprintf(stderr, "bench_deposit: %s\n", err.msg);
        exit(2);
    }
    mimas_box box = {{0, 0, 0}, {L, L, L}, 0, 0, 0, {1, 1, 1}};
    mimas_grid_fit_box(&g, &box);
    mimas_deposit dp;
    if (mimas_deposit_init(&dp, &g, &w, &box, 0, &err)) {
        fprintf(stderr, "bench_deposit: %s\n", err.msg);
        exit(2);
    }
    int with_grad = w.kind == MIMAS_WEIGHT_GAUSS || w.kind == MIMAS_WEIGHT_LUCY;
    double(*a)[3] = malloc(sizeof *a * N_OBJECTS), (*b)[3] = malloc(sizeof *b * N_OBJECTS);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937); /* the same objects on every machine */
    if (!a || !b || !rng) {
        fprintf(stderr, "bench_deposit: out of memory\n");
        exit(2);
    }
    for (int k = 0; k < N_OBJECTS; k++) {
        double u[3], n = 0;
        for (int d = 0; d < 3; d++) {
            a[k][d] = L * gsl_rng_uniform(rng);
            u[d] = gsl_rng_uniform(rng) - 0.5;
            n += u[d] * u[d];
        }
        for (int d = 0; d < 3; d++)
            b[k][d] = a[k][d] + len * u[d] / sqrt(n);
    }
    gsl_rng_free(rng);
    mimas_weights ws;
    memset(&ws, 0, sizeof ws);
    double best = HUGE_VAL, total = 0.0;
    for (int pass = 0; pass < passes; pass++) {
        double t0 = now();
        for (int k = 0; k < N_OBJECTS; k++) {
            ws.n = 0;
            int rc = segments ? mimas_deposit_segment(&dp, a[k], b[k], &ws)
                              : mimas_deposit_sphere(&dp, a[k], 0.5e-3, with_grad, &ws);
            if (rc) {
                fprintf(stderr, "bench_deposit: out of memory\n");
                exit(2);
            }
            if (pass == 0)
                for (size_t q = 0; q < ws.n; q++)
                    total += ws.w[q];
        }
        double t = now() - t0;
        if (t < best)
            best = t;
    }
    printf("  %-28s %9.0f ns/%s  %9.3g /s  (sum of the weights %.17g)\n", name,
           1e9 * best / N_OBJECTS, segments ? "contact " : "particle",
           N_OBJECTS / best, total);
    fflush(stdout);
    mimas_weights_free(&ws);
    free(a);
    free(b);
}

int main(int argc, char **argv)
{
    int only = -1, passes = 5;
    double len = 0.001;
    const char *gauss = "gauss:w=0.001";
    for (int k = 1; k + 1 < argc; k += 2) {
        if (!strcmp(argv[k], "--only"))
            only = atoi(argv[k + 1]);
        else if (!strcmp(argv[k], "--passes"))
            passes = atoi(argv[k + 1]);
        else if (!strcmp(argv[k], "--length"))
            len = atof(argv[k + 1]);
        else if (!strcmp(argv[k], "--weight"))
            gauss = argv[k + 1];
        else {
            fprintf(stderr, "bench_deposit: unknown option %s\n", argv[k]);
            return 2;
        }
    }
    if (passes < 1 || !(len > 0)) {
        fprintf(stderr, "bench_deposit: --passes must be >= 1 and --length > 0\n");
        return 2;
    }
    const char *xyz = "x=0:0.046:46,y=0:0.046:46,z=0:0.046:46", *rz = "r=0:0.046:46,z=0:0.046:46";
    struct {
        const char *name, *grid, *weight;
        int segments;
    } cases[] = {{"bins x-y-z particles", xyz, "bins", 0},
                 {"bins x-y-z contacts", xyz, "bins", 1},
                 {"kernel x-y-z particles", xyz, gauss, 0},
                 {"kernel x-y-z contacts", xyz, gauss, 1},
                 {"kernel r-z particles", rz, gauss, 0},
                 {"kernel r-z contacts", rz, gauss, 1},
                 {"bins r-z particles", rz, "bins", 0},
                 {"bins r-z contacts", rz, "bins", 1}};
    printf("deposits of %d objects, 1 mm cells, branches %g m, kernel %s, one thread, the "
           "shortest of %d passes:\n",
           N_OBJECTS, len, gauss, passes);
    for (int k = 0; k < (int)(sizeof cases / sizeof cases[0]); k++)
        if (only < 0 || only == k)
            run(cases[k].name, cases[k].grid, cases[k].weight, cases[k].segments, len, passes);
    return 0;
}
