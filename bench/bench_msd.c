/* Benchmark of mimas disperse.
 *
 * 1. The FFT mean-square displacement (averaging/msd.h) against the direct
 *    O(T^2) sum over every pair of frames, for random walks of three
 *    components at every lag, T = 1024, 4096 and 16384 frames: CPU seconds
 *    per particle and the speed-up (goal: at least 100 at T = 4096).  Both
 *    give the same numbers (checked to 1e-9 on the way).
 * 2. The whole command, mimas disperse, on a native file of N particles x
 *    T frames of random walks (written first, not timed): particle-frames/s
 *    and its peak resident memory (the child's rusage), with --memory as
 *    given (default: the command's, a quarter of the RAM).
 *
 *   bench_msd [--sizes T,T,...] [--particles N] [--frames T] [--memory BYTES]
 *             [--mimas PATH] [--file PATH] [--keep] [--skip-direct] [--skip-command]
 *
 * The defaults are the sizes (10^5 particles x 1024 frames: a 3 GB
 * file and 2.4 GB of trajectories); --particles 10000 is a quick run.  The
 * load average is printed beside the figures: other work on the machine
 * slows them; for a comparison that must hold under load, count
 * instructions (valgrind --tool=callgrind bench_msd --sizes 4096
 * --skip-command). */
#include <config.h>

#include <errno.h>
#include <getopt.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "msd.h"
#include "native.h"

extern char **environ;

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void load(void)
{
    double l[3] = {0, 0, 0};
    if (getloadavg(l, 3) == 3)
        printf("  (load average %.2f %.2f %.2f on %ld cores)\n", l[0], l[1], l[2],
               sysconf(_SC_NPROCESSORS_ONLN));
}

/* n random walks of T frames, three components */
static double *walks(size_t n, size_t T, gsl_rng *rng)
{
    double *x = malloc(n * T * 3 * sizeof *x);
    for (size_t j = 0; j < n; j++)
        for (size_t t = 0; t < T; t++)
            for (int c = 0; c < 3; c++)
                x[(j * T + t) * 3 + c] = (t ? x[(j * T + t - 1) * 3 + c] : 0.5) +
                                         gsl_ran_gaussian(rng, 1e-3);
    return x;
}

/* The direct MSD numerators of one particle at every lag. */
static void direct(const double *x, size_t T, double *num)
{
    for (size_t k = 1; k < T; k++) {
        double s = 0;
        for (size_t t = 0; t + k < T; t++)
            for (int c = 0; c < 3; c++) {
                double d = x[(t + k) * 3 + c] - x[t * 3 + c];
                s += d * d;
            }
        num[k] = s;
    }
}

static int compare_sizes(const char *sizes, int skip_direct)
{
    printf("FFT MSD against the direct O(T^2) sum (3 components, every lag), CPU s per "
           "particle:\n");
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    char *list = strdup(sizes), *save = NULL;
    int rc = 0;
    for (char *tok = strtok_r(list, ",", &save); tok && !rc; tok = strtok_r(NULL, ",", &save)) {
        size_t T = (size_t)atol(tok);
        if (T < 2)
            continue;
        size_t nfft_p = 64, ndirect = T <= 1024 ? 8 : T <= 4096 ? 2 : 1;
        double *x = walks(nfft_p, T, rng);
        mimas_msd *m;
        mimas_msd_sums s;
        mimas_error err;
        if (mimas_msd_create(&m, MIMAS_MSD_DISPLACEMENT, T, T - 1, 3, &err) ||
            mimas_msd_sums_init(&s, 3, 0, T, &err)) {
            fprintf(stderr, "bench_msd: %s\n", err.msg);
            return 1;
        }
        double c0 = cpu_seconds();
        mimas_msd_add(m, x, nfft_p, 3, &err);
        mimas_msd_flush(m, &s, 1, &err);
        double fft = (cpu_seconds() - c0) / (double)nfft_p;
        /* the direct sums of the first particles alone, for the check */
        mimas_msd_sums one;
        mimas_msd_sums_init(&one, 3, 0, T, &err);
        mimas_msd_add(m, x, ndirect, 3, &err);
        mimas_msd_flush(m, &one, 1, &err);
        double dir = NAN, worst = 0;
        if (!skip_direct) {
            double *num = calloc(T, sizeof *num), *acc = calloc(T, sizeof *acc);
            c0 = cpu_seconds();
            for (size_t j = 0; j < ndirect; j++) {
                direct(x + j * T * 3, T, num);
                for (size_t k = 1; k < T; k++)
                    acc[k] += num[k];
            }
            dir = (cpu_seconds() - c0) / (double)ndirect;
            for (size_t k = 1; k < T; k++) {
                double f = one.num[k] + one.num[T + k] + one.num[2 * T + k];
                double e = fabs(f - acc[k]) / acc[k];
                worst = e > worst ? e : worst;
            }
            free(num);
            free(acc);
            if (worst > 1e-9) {
                fprintf(stderr, "bench_msd: FFT and direct differ by %.3g at T = %zu\n", worst, T);
                rc = 1;
            }
        }
        printf("  T = %6zu: FFT %.3g s, direct %.3g s: %.0fx faster (largest relative difference "
               "%.1e)\n", T, fft, dir, dir / fft, worst);
        mimas_msd_sums_free(&s);
        mimas_msd_sums_free(&one);
        mimas_msd_free(m);
        free(x);
    }
    free(list);
    gsl_rng_free(rng);
    load();
    return rc;
}

/* A native file of n random walkers over T frames (0.01 s apart). */
static int write_input(const char *path, size_t n, size_t T)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    mimas_writer_options o;
    mimas_writer_options_default(&o);
    o.atomic = 1;
    mimas_writer *w;
    mimas_error err;
    if (mimas_writer_open(&w, path, &o, &err)) {
        fprintf(stderr, "bench_msd: %s\n", err.msg);
        return 1;
    }
    mimas_frame f;
    mimas_frame_init(&f);
    if (mimas_table_resize(&f.particles, &mimas_particles_desc, n, &err))
        return 1;
    for (size_t i = 0; i < n; i++) {
        f.particles.id[i] = (int64_t)i + 1;
        for (int c = 0; c < 3; c++)
            f.particles.pos[i][c] = gsl_rng_uniform(rng);
    }
    f.box = (mimas_box){{0, 0, 0}, {1, 1, 1}, 0, 0, 0, {0, 0, 0}};
    int rc = 0;
    for (size_t t = 0; t < T && !rc; t++) {
        f.step = (int64_t)t;
        f.time = 0.01 * (double)t;
        for (size_t i = 0; i < n && t; i++)
            for (int c = 0; c < 3; c++)
                f.particles.pos[i][c] += gsl_ran_gaussian(rng, 1e-3);
        rc = mimas_writer_append(w, &f, &err);
    }
    if (rc || mimas_writer_close(w, &err)) {
        fprintf(stderr, "bench_msd: %s\n", err.msg);
        return 1;
    }
    mimas_frame_free(&f);
    gsl_rng_free(rng);
    return 0;
}

static int run_command(const char *mimas, const char *path, size_t n, size_t T,
                       const char *memory)
{
    char table[4200];
    snprintf(table, sizeof table, "%s.tsv", path);
    char *argv[] = {(char *)mimas, "disperse", (char *)path, "--tsv", table, "-q",
                    memory ? "--memory" : NULL, (char *)memory, NULL};
    double w0 = wall_seconds();
    pid_t pid;
    if (posix_spawn(&pid, mimas, NULL, NULL, argv, environ) != 0) {
        fprintf(stderr, "bench_msd: cannot run %s: %s\n", mimas, strerror(errno));
        return 1;
    }
    int status;
    struct rusage u;
    while (wait4(pid, &status, 0, &u) < 0)
        if (errno != EINTR)
            return 1;
    double wall = wall_seconds() - w0;
    remove(table);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fprintf(stderr, "bench_msd: mimas disperse failed\n");
        return 1;
    }
    double cpu = (double)u.ru_utime.tv_sec + 1e-6 * (double)u.ru_utime.tv_usec +
                 (double)u.ru_stime.tv_sec + 1e-6 * (double)u.ru_stime.tv_usec;
    double pf = (double)n * (double)T;
    printf("mimas disperse on %zu particles x %zu frames%s%s:\n  %.3g s CPU (%.3g s wall): "
           "%.3g particle-frames/s of CPU; peak resident memory %.0f MB\n", n, T,
           memory ? " --memory " : "", memory ? memory : "", cpu, wall, pf / cpu,
           (double)u.ru_maxrss / 1024.0);
    load();
    return 0;
}

int main(int argc, char **argv)
{
    const char *sizes = "1024,4096,16384", *mimas = "./mimas", *file = NULL, *memory = NULL;
    long n = 100000, T = 1024;
    int skip_direct = 0, skip_command = 0, keep = 0;
    static const struct option opts[] = {
        {"sizes", required_argument, NULL, 's'},  {"particles", required_argument, NULL, 'n'},
        {"frames", required_argument, NULL, 'T'}, {"memory", required_argument, NULL, 'm'},
        {"mimas", required_argument, NULL, 'x'},  {"file", required_argument, NULL, 'f'},
        {"keep", no_argument, NULL, 'k'},         {"skip-direct", no_argument, NULL, 'd'},
        {"skip-command", no_argument, NULL, 'c'}, {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        switch (c) {
        case 's': sizes = optarg; break;
        case 'n': n = atol(optarg); break;
        case 'T': T = atol(optarg); break;
        case 'm': memory = optarg; break;
        case 'x': mimas = optarg; break;
        case 'f': file = optarg; break;
        case 'k': keep = 1; break;
        case 'd': skip_direct = 1; break;
        case 'c': skip_command = 1; break;
        default: fprintf(stderr, "bench_msd: bad option\n"); return 1;
        }
    }
    int rc = compare_sizes(sizes, skip_direct);
    if (rc || skip_command || n < 1 || T < 2)
        return rc;
    char path[4096];
    snprintf(path, sizeof path, "%s", file ? file : "bench-disperse.h5");
    if (!file || access(path, R_OK) != 0) {
        printf("writing %ld particles x %ld frames to %s ...\n", n, T, path);
        fflush(stdout);
        if (write_input(path, (size_t)n, (size_t)T))
            return 1;
    }
    rc = run_command(mimas, path, (size_t)n, (size_t)T, memory);
    if (!keep && !file)
        remove(path);
    return rc;
}
