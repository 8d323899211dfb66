/* Writes a native file of random frames (for the demonstration, the CLI tests
 * and the benchmark).  Usage:
 *   make_frames -o FILE [--frames F] [--particles N] [--contacts M] [--walls W]
 *               [--seed S] [--triclinic] [--vary] [--deflate L] */
#include <config.h>

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>

#include "native.h"
#include "random_frame.h"

int main(int argc, char **argv)
{
    const char *out = NULL;
    long frames = 3, seed = 1, deflate = 1;
    random_frame_spec spec = {1000, 3000, 100, 1, 0, 1, 1};
    int vary = 0;
    static const struct option opts[] = {
        {"output", required_argument, NULL, 'o'}, {"frames", required_argument, NULL, 'f'},
        {"particles", required_argument, NULL, 'p'}, {"contacts", required_argument, NULL, 'c'},
        {"walls", required_argument, NULL, 'w'}, {"seed", required_argument, NULL, 's'},
        {"triclinic", no_argument, NULL, 't'}, {"vary", no_argument, NULL, 'v'},
        {"deflate", required_argument, NULL, 'd'}, {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "o:", opts, NULL)) != -1) {
        switch (c) {
        case 'o': out = optarg; break;
        case 'f': frames = atol(optarg); break;
        case 'p': spec.particles = (size_t)atol(optarg); break;
        case 'c': spec.contacts = (size_t)atol(optarg); break;
        case 'w': spec.walls = (size_t)atol(optarg); break;
        case 's': seed = atol(optarg); break;
        case 't': spec.triclinic = 1; break;
        case 'v': vary = 1; break;
        case 'd': deflate = atol(optarg); break;
        default: fprintf(stderr, "make_frames: bad option\n"); return 1;
        }
    }
    if (!out) {
        fprintf(stderr, "make_frames: -o FILE is required\n");
        return 1;
    }
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, (unsigned long)seed);
    mimas_writer_options o;
    mimas_writer_options_default(&o);
    o.deflate = (int)deflate;
    o.atomic = 1;
    o.triclinic = spec.triclinic;
    mimas_writer *w;
    mimas_error err;
    if (mimas_writer_open(&w, out, &o, &err)) {
        fprintf(stderr, "make_frames: %s\n", err.msg);
        return 2;
    }
    mimas_frame f;
    mimas_frame_init(&f);
    size_t np = spec.particles, nc = spec.contacts, nw = spec.walls;
    for (long k = 0; k < frames; k++) {
        if (vary) {  /* particle and contact counts change from frame to frame */
            spec.particles = np / 2 + gsl_rng_uniform_int(rng, np + 1);
            spec.contacts = nc / 2 + gsl_rng_uniform_int(rng, nc + 1);
            spec.walls = nw / 2 + gsl_rng_uniform_int(rng, nw + 1);
        }
        if (random_frame(&f, rng, &spec, 1000 * k) || mimas_writer_append(w, &f, &err)) {
            fprintf(stderr, "make_frames: %s\n", err.msg);
            mimas_writer_abort(w);
            return 2;
        }
    }
    mimas_frame_free(&f);
    gsl_rng_free(rng);
    if (mimas_writer_close(w, &err)) {
        fprintf(stderr, "make_frames: %s\n", err.msg);
        return 2;
    }
    return 0;
}
