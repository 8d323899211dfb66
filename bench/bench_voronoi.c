/* Benchmark of the voro++ wrapper: cells per second of mimas_voro_cells on
 * 10^5 and 10^6 particles against a bare voro++ loop over the same points
 * (mimas_voro_reference: container, put, volume and face count of every
 * cell), with 1 and 2 threads.
 *
 * The packing is a jittered FCC lattice at solid fraction 0.6: lattice
 * constant 1, spheres of radius r with 16 pi r^3 / 3 = 0.6, each centre moved
 * uniformly within a ball of radius (1/sqrt 2 - 2 r)/2 so that no two
 * spheres overlap.  Boxes: periodic, and closed (non-periodic, where the
 * wrapper also flags the cells touching the box faces).
 *
 * Usage: bench_voronoi [--sizes 29,63] [--reps R] (sizes are FCC cells per
 * edge: 4 m^3 particles). */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_rng.h>

#include "voro_cells.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static size_t jittered_fcc(int m, double (*pos)[3], double *radius, gsl_rng *rng)
{
    static const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    double r = cbrt(0.6 * 3.0 / (16.0 * M_PI)), jitter = 0.5 * (M_SQRT1_2 - 2.0 * r);
    size_t n = 0;
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++)
            for (int k = 0; k < m; k++)
                for (int b = 0; b < 4; b++, n++) {
                    double d[3], d2;
                    do { /* uniform in the ball */
                        for (int c = 0; c < 3; c++)
                            d[c] = 2.0 * gsl_rng_uniform(rng) - 1.0;
                        d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                    } while (d2 > 1.0);
                    int idx[3] = {i, j, k};
                    for (int c = 0; c < 3; c++)
                        pos[n][c] = idx[c] + 0.25 + basis[b][c] + jitter * d[c];
                    radius[n] = r;
                }
    return n;
}

typedef struct run {
    const char *what;
    int threads; /* 0: the bare voro++ loop */
} run;

static double best_time(const run *rn, const mimas_box *box, size_t n, const double (*pos)[3],
                        const double *radius, double *vol, int *faces, unsigned char *surf,
                        int reps)
{
    double best = INFINITY;
    mimas_error err;
    for (int r = 0; r < reps; r++) {
        double t0 = now();
        int rc;
        if (rn->threads == 0) {
            rc = mimas_voro_reference(box, n, pos, radius, vol, faces, &err);
        } else {
            mimas_voro_options o = {radius, NULL, 0, 0, rn->threads, NULL};
            rc = mimas_voro_cells(box, n, pos, &o, vol, faces, surf, &err);
        }
        double t = now() - t0;
        if (rc) {
            fprintf(stderr, "bench_voronoi: %s\n", err.msg);
            exit(1);
        }
        best = t < best ? t : best;
    }
    return best;
}

int main(int argc, char **argv)
{
    const char *sizes = "29,63";
    int reps = 2;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--sizes") && i + 1 < argc)
            sizes = argv[++i];
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_voronoi [--sizes M1,M2,...] [--reps R]\n");
            return 1;
        }
    }
    if (reps < 1)
        reps = 1;
    static const run runs[] = {{"bare voro++ loop", 0},
                               {"mimas_voro_cells, 1 thread", 1},
                               {"mimas_voro_cells, 2 threads", 2}};
    char *list = strdup(sizes), *save = NULL;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    for (char *tok = strtok_r(list, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        int m = atoi(tok);
        if (m < 2)
            continue;
        size_t cap = 4 * (size_t)m * (size_t)m * (size_t)m;
        double (*pos)[3] = malloc(cap * sizeof *pos), *radius = malloc(cap * sizeof *radius);
        double *vol = malloc(cap * sizeof *vol);
        int *faces = malloc(cap * sizeof *faces);
        unsigned char *surf = malloc(cap);
        if (!pos || !radius || !vol || !faces || !surf) {
            fprintf(stderr, "bench_voronoi: out of memory for %zu particles\n", cap);
            return 1;
        }
        size_t n = jittered_fcc(m, pos, radius, rng);
        for (int closed = 0; closed < 2; closed++)
            for (int radical = 0; radical < 2; radical++) {
                int per = !closed;
                mimas_box box = {{0, 0, 0}, {m, m, m}, 0, 0, 0, {per, per, per}};
                printf("jittered FCC, nu = 0.6, %zu particles, %s box, %s:\n", n,
                       closed ? "closed" : "periodic", radical ? "radical" : "plain");
                double bare = 0;
                for (size_t r = 0; r < sizeof runs / sizeof runs[0]; r++) {
                    double t = best_time(&runs[r], &box, n, (const double (*)[3])pos,
                                         radical ? radius : NULL, vol, faces, surf, reps);
                    if (runs[r].threads == 0)
                        bare = t;
                    int cores = runs[r].threads > 1 ? runs[r].threads : 1;
                    printf("  %-28s %8.3f s  %10.0f cells/s  %10.0f cells/s/core", runs[r].what, t,
                           (double)n / t, (double)n / t / cores);
                    if (runs[r].threads)
                        printf("  time / bare %.3f", t / bare);
                    printf("\n");
                }
                double sum = 0;
                for (size_t k = 0; k < n; k++)
                    sum += vol[k];
                printf("  (cell volumes sum to %.12g of %d)\n", sum, m * m * m);
                fflush(stdout);
            }
        free(pos);
        free(radius);
        free(vol);
        free(faces);
        free(surf);
    }
    gsl_rng_free(rng);
    free(list);
    return 0;
}
