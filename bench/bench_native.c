/* Benchmark of the native format: write and read F frames of N particles and
 * M contacts each; prints MB/s both ways and the peak resident memory, which
 * must not depend on F (the writer and the reader hold one frame).
 *   bench_native [--frames F] [--particles N] [--contacts M] [--deflate L] [--file PATH] */
#include <config.h>

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "native.h"
#include "random_frame.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double peak_mb(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return (double)u.ru_maxrss / 1024.0;
}

static double table_bytes(const void *tab, const mimas_table_desc *d)
{
    double b = 0;
    size_t n = mimas_table_n(tab, d);
    unsigned present = mimas_table_present(tab, d);
    for (size_t c = 0; c < d->ncolumns; c++)
        if (present & d->columns[c].bit)
            b += (double)n * d->columns[c].ncomp * (double)mimas_elem_size(d->columns[c].type);
    size_t ne = *(const size_t *)((const char *)tab + d->off_n_extra);
    const mimas_extra *x = *(mimas_extra *const *)((const char *)tab + d->off_extra);
    for (size_t e = 0; e < ne; e++)
        b += (double)n * x[e].ncomp * sizeof(double);
    return b;
}

int main(int argc, char **argv)
{
    long frames = 10, deflate = 1;
    random_frame_spec spec = {333333, 1000000, 0, 0, 0, 1, 0};
    const char *path = "bench_native.h5";
    static const struct option opts[] = {
        {"frames", required_argument, NULL, 'f'}, {"particles", required_argument, NULL, 'p'},
        {"contacts", required_argument, NULL, 'c'}, {"deflate", required_argument, NULL, 'd'},
        {"file", required_argument, NULL, 'o'}, {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        switch (c) {
        case 'f': frames = atol(optarg); break;
        case 'p': spec.particles = (size_t)atol(optarg); break;
        case 'c': spec.contacts = (size_t)atol(optarg); break;
        case 'd': deflate = atol(optarg); break;
        case 'o': path = optarg; break;
        default: fprintf(stderr, "bench_native: bad option\n"); return 1;
        }
    }
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    mimas_frame f;
    mimas_frame_init(&f);
    random_frame(&f, rng, &spec, 0);
    double bytes = table_bytes(&f.particles, &mimas_particles_desc) +
                   table_bytes(&f.contacts, &mimas_contacts_desc);
    mimas_error err;
    mimas_writer_options o;
    mimas_writer_options_default(&o);
    o.deflate = (int)deflate;
    mimas_writer *w;
    if (mimas_writer_open(&w, path, &o, &err)) {
        fprintf(stderr, "bench_native: %s\n", err.msg);
        return 2;
    }
    double t0 = now();
    for (long k = 0; k < frames; k++) {
        f.step = k;
        f.time = (double)k;
        if (mimas_writer_append(w, &f, &err)) {
            fprintf(stderr, "bench_native: %s\n", err.msg);
            return 2;
        }
    }
    if (mimas_writer_close(w, &err)) {
        fprintf(stderr, "bench_native: %s\n", err.msg);
        return 2;
    }
    double tw = now() - t0;
    double rss_write = peak_mb();
    struct stat st;
    stat(path, &st);

    mimas_frame g;
    mimas_frame_init(&g);
    mimas_native *r;
    t0 = now();
    if (mimas_native_open(&r, path, &err)) {
        fprintf(stderr, "bench_native: %s\n", err.msg);
        return 2;
    }
    for (size_t k = 0; k < mimas_native_frames(r); k++)
        if (mimas_native_read(r, k, &g, &err)) {
            fprintf(stderr, "bench_native: %s\n", err.msg);
            return 2;
        }
    mimas_native_close(r);
    double tr = now() - t0;
    double MB = bytes * (double)frames / 1e6;
    printf("native format: %ld frames x (%zu particles, %zu contacts), deflate %ld\n", frames,
           spec.particles, spec.contacts, deflate);
    printf("  frame data in memory %.1f MB; file %.1f MB (%.2f of the data)\n", bytes / 1e6,
           (double)st.st_size / 1e6, (double)st.st_size / (bytes * (double)frames));
    printf("  write %.2f s = %.0f MB/s    read %.2f s = %.0f MB/s\n", tw, MB / tw, tr, MB / tr);
    printf("  peak resident memory: %.0f MB after writing, %.0f MB after reading\n", rss_write,
           peak_mb());
    mimas_frame_free(&f);
    mimas_frame_free(&g);
    gsl_rng_free(rng);
    unlink(path);
    return 0;
}
