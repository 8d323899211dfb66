/* Writes a native file of ring-shear-cell frames with a known shear band
 * (tests/common/ring_frame.h) for the shearband CLI tests.  Usage:
 *   make_band_frames -o FILE [--frames F] [--particles N] [--seed S]
 *                    [--rc RC] [--rc-slope K] [--width W] [--noise V] */
#include <config.h>

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>

#include "native.h"
#include "ring_frame.h"

int main(int argc, char **argv)
{
    const char *out = NULL;
    long frames = 4, seed = 1;
    ring_spec s;
    ring_spec_default(&s);
    s.particles = 20000;
    s.noise = 0.002;
    static const struct option opts[] = {
        {"output", required_argument, NULL, 'o'}, {"frames", required_argument, NULL, 'f'},
        {"particles", required_argument, NULL, 'p'}, {"seed", required_argument, NULL, 's'},
        {"rc", required_argument, NULL, 'r'}, {"rc-slope", required_argument, NULL, 'k'},
        {"width", required_argument, NULL, 'w'}, {"noise", required_argument, NULL, 'n'},
        {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "o:", opts, NULL)) != -1) {
        switch (c) {
        case 'o': out = optarg; break;
        case 'f': frames = atol(optarg); break;
        case 'p': s.particles = (size_t)atol(optarg); break;
        case 's': seed = atol(optarg); break;
        case 'r': s.rc = atof(optarg); break;
        case 'k': s.rc_slope = atof(optarg); break;
        case 'w': s.w = atof(optarg); break;
        case 'n': s.noise = atof(optarg); break;
        default: fprintf(stderr, "make_band_frames: bad option\n"); return 1;
        }
    }
    if (!out) {
        fprintf(stderr, "make_band_frames: -o FILE is required\n");
        return 1;
    }
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, (unsigned long)seed);
    mimas_writer_options o;
    mimas_writer_options_default(&o);
    o.atomic = 1;
    mimas_writer *w;
    mimas_error err;
    if (mimas_writer_open(&w, out, &o, &err)) {
        fprintf(stderr, "make_band_frames: %s\n", err.msg);
        return 2;
    }
    mimas_frame f;
    mimas_frame_init(&f);
    for (long k = 0; k < frames; k++)
        if (ring_frame(&f, rng, &s, 1000 * k) || mimas_writer_append(w, &f, &err)) {
            fprintf(stderr, "make_band_frames: %s\n", err.msg);
            mimas_writer_abort(w);
            return 2;
        }
    mimas_frame_free(&f);
    gsl_rng_free(rng);
    if (mimas_writer_close(w, &err)) {
        fprintf(stderr, "make_band_frames: %s\n", err.msg);
        return 2;
    }
    return 0;
}
