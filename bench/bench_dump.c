/* Benchmark of the LAMMPS/LIGGGHTS dump reader: writes a dump series of
 * about SIZE MB (per-atom dump with the columns LIGGGHTS writes, plus a
 * pair/gran/local contact dump, numbers printed like LAMMPS' "%g"), then
 * streams it through mimas_reader and prints MB/s of text and the peak
 * resident memory.
 *   bench_dump [--mb SIZE] [--particles N] [--dir DIR] [--gzip] */
#include <config.h>

#include <getopt.h>
#include <gsl/gsl_rng.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

#include "reader.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double file_mb(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (double)st.st_size / 1e6 : 0;
}

/* One snapshot of n atoms (25 columns) and 3n contacts (41 columns). */
static void write_snapshot(FILE *fa, FILE *fc, long step, size_t n, gsl_rng *r)
{
    fprintf(fa, "ITEM: TIMESTEP\n%ld\nITEM: NUMBER OF ATOMS\n%zu\nITEM: BOX BOUNDS pp pp ff\n"
                "0 0.1\n0 0.1\n0 0.2\nITEM: ATOMS id type x y z ix iy iz vx vy vz fx fy fz "
                "omegax omegay omegaz radius mass c_stress[1] c_stress[2] c_stress[3] "
                "c_stress[4] c_stress[5] c_stress[6]\n", step, n);
    for (size_t k = 0; k < n; k++) {
        fprintf(fa, "%zu 1 %g %g %g 0 0 0", k + 1, 0.1 * gsl_rng_uniform(r),
                0.1 * gsl_rng_uniform(r), 0.2 * gsl_rng_uniform(r));
        for (int c = 0; c < 9; c++)
            fprintf(fa, " %g", gsl_rng_uniform(r) - 0.5);
        fprintf(fa, " 0.001 8.37758e-06");
        for (int c = 0; c < 6; c++)
            fprintf(fa, " %g", 1e-4 * (gsl_rng_uniform(r) - 0.5));
        fputc('\n', fa);
    }
    size_t m = 3 * n;
    fprintf(fc, "ITEM: TIMESTEP\n%ld\nITEM: NUMBER OF ENTRIES\n%zu\nITEM: BOX BOUNDS pp pp ff\n"
                "0 0.1\n0 0.1\n0 0.2\nITEM: ENTRIES", step, m);
    for (int c = 1; c <= 41; c++)
        fprintf(fc, " c_pgl[%d]", c);
    fputc('\n', fc);
    for (size_t k = 0; k < m; k++) {
        for (int c = 0; c < 12; c++)
            fprintf(fc, "%g ", gsl_rng_uniform(r));
        fprintf(fc, "%zu %zu 0", 1 + gsl_rng_uniform_int(r, n), 1 + gsl_rng_uniform_int(r, n));
        for (int c = 15; c < 41; c++)
            fprintf(fc, " %g", gsl_rng_uniform(r) - 0.5);
        fputc('\n', fc);
    }
}

int main(int argc, char **argv)
{
    double mb = 1000;
    size_t n = 100000;
    const char *dir = ".";
    int gz = 0;
    static const struct option opts[] = {{"mb", required_argument, NULL, 'm'},
                                         {"particles", required_argument, NULL, 'p'},
                                         {"dir", required_argument, NULL, 'd'},
                                         {"gzip", no_argument, NULL, 'g'},
                                         {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        switch (c) {
        case 'm': mb = atof(optarg); break;
        case 'p': n = (size_t)atol(optarg); break;
        case 'd': dir = optarg; break;
        case 'g': gz = 1; break;
        default: return 1;
        }
    }
    char atoms[512], pairs[512];
    snprintf(atoms, sizeof atoms, "%s/bench_dump.atoms", dir);
    snprintf(pairs, sizeof pairs, "%s/bench_dump.pgl", dir);
    FILE *fa = fopen(atoms, "w"), *fc = fopen(pairs, "w");
    if (!fa || !fc) {
        fprintf(stderr, "bench_dump: cannot write in %s\n", dir);
        return 2;
    }
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    double t0 = now();
    long frames = 0;
    while ((double)(ftell(fa) + ftell(fc)) / 1e6 < mb)
        write_snapshot(fa, fc, 1000 * frames++, n, r);
    fclose(fa);
    fclose(fc);
    double total = file_mb(atoms) + file_mb(pairs);
    printf("dump reader: %ld snapshots x (%zu atoms, %zu contacts), %.0f MB of text (written in "
           "%.0f s)\n", frames, n, 3 * n, total, now() - t0);
    if (gz) {
        char cmd[1200];
        snprintf(cmd, sizeof cmd, "gzip -1 -f '%s' '%s'", atoms, pairs);
        if (system(cmd) != 0)
            return 2;
        strcat(atoms, ".gz");
        strcat(pairs, ".gz");
        printf("  gzip -1: %.0f MB compressed\n", file_mb(atoms) + file_mb(pairs));
    }
    const char *inputs[1] = {atoms}, *contacts[1] = {pairs};
    mimas_reader_options o;
    mimas_reader_options_default(&o);
    o.contacts = contacts;
    o.ncontacts = 1;
    o.contact_columns = "pos,vel,id,force,force_normal,force_tangential,torque,torque_normal,"
                        "torque_tangential,history,contactArea,delta,contactPoint";
    mimas_reader *rd;
    mimas_error err;
    mimas_frame f;
    mimas_frame_init(&f);
    t0 = now();
    if (mimas_reader_open(&rd, inputs, 1, &o, &err)) {
        fprintf(stderr, "bench_dump: %s\n", err.msg);
        return 2;
    }
    long got = 0;
    int rc;
    while ((rc = mimas_reader_next(rd, &f, &err)) == MIMAS_OK)
        got++;
    double t = now() - t0;
    if (rc != MIMAS_END) {
        fprintf(stderr, "bench_dump: %s\n", err.msg);
        return 2;
    }
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    printf("  read %ld frames in %.2f s: %.0f MB/s of %s text on one core; peak resident "
           "memory %.0f MB\n", got, t, total / t, gz ? "gzipped" : "plain",
           (double)u.ru_maxrss / 1024.0);
    mimas_reader_close(rd);
    mimas_frame_free(&f);
    gsl_rng_free(r);
    unlink(atoms);
    unlink(pairs);
    return 0;
}
