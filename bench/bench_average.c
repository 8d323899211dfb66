/* Benchmark of mimas average: 10^5 particles on a jittered simple cubic
 * lattice (d = 1 mm) with their 3x10^5 nearest-neighbour contacts; bins and
 * gauss (w = d) on an x-y-z grid of spacing d and on an r-z grid of spacing d.
 * The r-z grid of cases 2 and 3 has its axis on the periodic box's edge, so that its rings
 * pass through four periodic images of the box and each object is deposited about four
 * times; case 4 (gauss r-z, walls) is the geometry of a ring shear cell: the axis through
 * the lattice's middle, walls across x and y (periodic along z only, no contacts across
 * those faces, 287,776 of them), r = 0:33 mm covering the lattice, each object once.
 * Prints particles/s and contacts/s (contact time = time with contacts minus
 * time without), from the wall clock and, for one thread, from the process's
 * CPU time (which a loaded machine disturbs less): the shortest of F frames in
 * the steady state (after one untimed frame).
 * --scaling: how the time grows with the kernel width (gauss x-y-z, w = d/2 .. 4d, one
 * thread, a 20^3 lattice on a 20^3 grid), with the cells a particle touches for
 * comparison: the separable deposit grows like them, ~w^3.
 *   bench_average [--frames F] [--only CASE] [--threads N] [--scaling] */
#include <config.h>

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "average.h"

static double clock_of(clockid_t id)
{
    struct timespec t;
    clock_gettime(id, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct timing {
    double wall, cpu; /* seconds per frame */
} timing;

/* The jittered m^3 lattice and its nearest-neighbour contacts, in a periodic box, or with
 * walls across x and y (periodic along z only): then without the contacts across those
 * faces. */
static void build(mimas_frame *f, int m, double d, int walls)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    mimas_error err;
    size_t n = (size_t)m * m * m;
    mimas_table_set_present(&f->particles, &mimas_particles_desc,
                            MIMAS_P_RADIUS | MIMAS_P_MASS | MIMAS_P_VEL, &err);
    mimas_table_resize(&f->particles, &mimas_particles_desc, n, &err);
    mimas_particles *p = &f->particles;
    for (size_t k = 0; k < n; k++) {
        int idx[3] = {(int)(k % m), (int)(k / m % m), (int)(k / m / m)};
        p->id[k] = (int64_t)k + 1;
        for (int c = 0; c < 3; c++) {
            p->pos[k][c] = (idx[c] + 0.5 + 0.05 * (gsl_rng_uniform(rng) - 0.5)) * d;
            p->vel[k][c] = gsl_rng_uniform(rng) - 0.5;
        }
        p->radius[k] = 0.5 * d;
        p->mass[k] = 2000 * 4.0 / 3.0 * 3.14159265 * 0.125 * d * d * d;
    }
    mimas_table_set_present(&f->contacts, &mimas_contacts_desc, MIMAS_C_FORCE, &err);
    mimas_table_resize(&f->contacts, &mimas_contacts_desc, 3 * n, &err);
    size_t c = 0;
    for (size_t k = 0; k < n; k++)
        for (int dir = 0; dir < 3; dir++) {
            size_t stride = dir == 0 ? 1 : (dir == 1 ? (size_t)m : (size_t)m * m);
            if (walls && dir < 2 && (dir == 0 ? k % m : k / m % m) == (size_t)m - 1)
                continue; /* no neighbour beyond the wall */
            size_t j = (k + stride) % n; /* periodic: every particle has 3 contacts */
            f->contacts.i[c] = k;
            f->contacts.j[c] = j;
            for (int q = 0; q < 3; q++)
                f->contacts.force[c][q] = gsl_rng_uniform(rng) - 0.5;
            c++;
        }
    mimas_table_resize(&f->contacts, &mimas_contacts_desc, c, &err);
    f->has_contacts = 1;
    mimas_box box = {{0, 0, 0}, {m * d, m * d, m * d}, 0, 0, 0, {!walls, !walls, 1}};
    f->box = box;
    gsl_rng_free(rng);
}

static mimas_average *create(const char *grid, const char *axis, const char *weight,
                             int threads)
{
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    mimas_error err;
    mimas_average *a;
    if (mimas_grid_parse(&o.grid, grid, axis, &err) ||
        mimas_weight_parse(&o.weight, weight, &err) ||
        (o.threads = threads, mimas_average_create(&a, &o, &err))) {
        fprintf(stderr, "bench_average: %s\n", err.msg);
        exit(2);
    }
    return a;
}

/* One frame added to a, timed (the smaller of each clock kept in t). */
static void add_timed(mimas_average *a, const mimas_frame *f, timing *t)
{
    mimas_error err;
    double t0 = clock_of(CLOCK_MONOTONIC), c0 = clock_of(CLOCK_PROCESS_CPUTIME_ID);
    if (mimas_average_add(a, f, &err)) {
        fprintf(stderr, "bench_average: %s\n", err.msg);
        exit(2);
    }
    double wall = clock_of(CLOCK_MONOTONIC) - t0, cpu = clock_of(CLOCK_PROCESS_CPUTIME_ID) - c0;
    if (wall < t->wall)
        t->wall = wall;
    if (cpu < t->cpu)
        t->cpu = cpu;
}

/* The time of a frame: the shortest of `frames`, after one untimed frame, which
 * touches the fresh sums (their page faults, about 8 us a page on this virtual
 * machine, cost a first frame of a 46^3 grid 0.1-0.2 s).  On a shared machine
 * the time of a frame scatters by up to 1.5x from frame to frame; the shortest
 * is what the program takes when nothing else runs.  The frames with and
 * without contacts are timed one average after the other, not interleaved: a
 * real run adds its frames to one average, whose sums stay in the cache
 * (alternating two averages of 50 MB each made every frame 1.5x slower). */
static timing run(const mimas_frame *f, const char *grid, const char *axis, const char *weight,
                  int frames, int threads)
{
    mimas_average *a = create(grid, axis, weight, threads);
    timing untimed = {HUGE_VAL, HUGE_VAL}, t = {HUGE_VAL, HUGE_VAL};
    add_timed(a, f, &untimed);
    for (int q = 0; q < frames; q++)
        add_timed(a, f, &t);
    mimas_average_free(a);
    return t;
}

/* n objects over t seconds, or "n/a" where the difference of two times is not
 * above their scatter */
static void print_rate(double n, double t)
{
    if (t > 0)
        printf("%.3g /s", n / t);
    else
        printf("n/a");
}

/* The frame of an m^3 lattice with its contacts, and the same without contacts. */
static void build_pair(mimas_frame *f, mimas_frame *bare, int m, double d, int walls)
{
    mimas_frame_init(f);
    mimas_frame_init(bare);
    build(f, m, d, walls);
    build(bare, m, d, walls);
    bare->has_contacts = 0;
}

/* CPU time per frame against the width w, and the exponent between neighbours */
static int scaling(void)
{
    const int m = 20;
    const double d = 0.001, L = m * d;
    mimas_frame f, bare;
    build_pair(&f, &bare, m, d, 0);
    char grid[256];
    snprintf(grid, sizeof grid, "x=0:%g:%d,y=0:%g:%d,z=0:%g:%d", L, m, L, m, L, m);
    const double ws[5] = {0.5, 1, 2, 3, 4};
    double prev_p = 0, prev_c = 0;
    printf("gauss x-y-z, %zu particles, %zu contacts, spacing d, 1 thread, CPU time per frame:\n",
           f.particles.n, f.contacts.n);
    for (int k = 0; k < 5; k++) {
        char weight[64];
        snprintf(weight, sizeof weight, "gauss:w=%g", ws[k] * d);
        timing all = run(&f, grid, NULL, weight, 3, 1), p = run(&bare, grid, NULL, weight, 3, 1);
        double tp = p.cpu, tc = all.cpu - p.cpu, cells = pow(2 * 3 * ws[k] + 1, 3);
        printf("  w = %.1f d: particles %.3g s, contacts %.3g s (cells in reach ~%.0f)", ws[k], tp,
               tc, cells);
        if (k > 0)
            printf("  exponents %.2f, %.2f (cells %.2f)", log(tp / prev_p) / log(ws[k] / ws[k - 1]),
                   log(tc / prev_c) / log(ws[k] / ws[k - 1]),
                   log(cells / pow(2 * 3 * ws[k - 1] + 1, 3)) / log(ws[k] / ws[k - 1]));
        printf("\n");
        fflush(stdout);
        prev_p = tp;
        prev_c = tc;
    }
    mimas_frame_free(&f);
    mimas_frame_free(&bare);
    return 0;
}

int main(int argc, char **argv)
{
    int frames = 3, only = -1, max_threads = 2;
    for (int k = 1; k < argc; k++)
        if (!strcmp(argv[k], "--scaling"))
            return scaling();
    for (int k = 1; k + 1 < argc; k += 2) {
        if (!strcmp(argv[k], "--frames"))
            frames = atoi(argv[k + 1]);
        else if (!strcmp(argv[k], "--only"))
            only = atoi(argv[k + 1]); /* one case, for profiling */
        else if (!strcmp(argv[k], "--threads"))
            max_threads = atoi(argv[k + 1]);
    }
    const int m = 46; /* 97,336 particles, 292,008 contacts (287,776 with walls) */
    const double d = 0.001, L = m * d;
    mimas_frame frames_of[2][2]; /* [walls]: with contacts, bare */
    build_pair(&frames_of[0][0], &frames_of[0][1], m, d, 0);
    build_pair(&frames_of[1][0], &frames_of[1][1], m, d, 1);
    char xyz[256], rz[256], ring[256], axis[128];
    snprintf(xyz, sizeof xyz, "x=0:%g:%d,y=0:%g:%d,z=0:%g:%d", L, m, L, m, L, m);
    snprintf(rz, sizeof rz, "r=0:%g:%d,z=0:%g:%d", L, m, L, m);
    /* r up to 33 d > the half diagonal, 32.5 d: every object of the lattice inside */
    snprintf(ring, sizeof ring, "r=0:%g:%d,z=0:%g:%d", 33 * d, 33, L, m);
    snprintf(axis, sizeof axis, "%g,%g,0,0,0,1", 0.5 * L, 0.5 * L);
    struct {
        const char *name, *grid, *axis, *weight;
        int walls;
    } cases[] = {{"bins  x-y-z       ", xyz, NULL, "bins", 0},
                 {"gauss x-y-z       ", xyz, NULL, "gauss:w=0.001", 0},
                 {"bins  r-z         ", rz, NULL, "bins", 0},
                 {"gauss r-z         ", rz, NULL, "gauss:w=0.001", 0},
                 {"gauss r-z, walls  ", ring, axis, "gauss:w=0.001", 1}};
    printf("mimas average: %zu particles, %zu contacts per frame (%zu with walls), "
           "spacing = w = d = 1 mm\n",
           frames_of[0][0].particles.n, frames_of[0][0].contacts.n, frames_of[1][0].contacts.n);
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++)
        for (int threads = 1; threads <= max_threads; threads++) {
            if (only >= 0 && (size_t)only != k)
                continue;
            const mimas_frame *f = &frames_of[cases[k].walls][0];
            const mimas_frame *bare = &frames_of[cases[k].walls][1];
            timing t_all = run(f, cases[k].grid, cases[k].axis, cases[k].weight, frames, threads);
            timing t_p = run(bare, cases[k].grid, cases[k].axis, cases[k].weight, frames, threads);
            printf("  %s  %d thread%s  %.3f s/frame: particles ", cases[k].name, threads,
                   threads > 1 ? "s" : " ", t_all.wall);
            print_rate((double)f->particles.n, t_p.wall);
            printf(", contacts ");
            print_rate((double)f->contacts.n, t_all.wall - t_p.wall);
            printf(" (wall)");
            if (threads == 1) {
                printf("; ");
                print_rate((double)f->particles.n, t_p.cpu);
                printf(", ");
                print_rate((double)f->contacts.n, t_all.cpu - t_p.cpu);
                printf(" (cpu)");
            }
            printf("\n");
            fflush(stdout);
        }
    for (int w = 0; w < 2; w++)
        for (int k = 0; k < 2; k++)
            mimas_frame_free(&frames_of[w][k]);
    return 0;
}
