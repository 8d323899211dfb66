/* Writes a native file of a generated tube flow for the disperse tests:
 * particles enter at the inlet (s = 0 on the axis) at a steady rate, move
 * along the axis at a mean speed with axial Brownian spread of a known D,
 * keep their place across the axis, and leave once past the tube's length.
 * Ids count up in the order of entry.  With --truth FILE every particle of
 * every frame is also written as text "time id x y z", for computations in
 * the test that are independent of mimas.  Usage:
 *   make_tube_flow -o FILE [--frames F] [--dt DT] [--rate R] [--stop T]
 *                  [--velocity V] [--D D] [--length L] [--radius R]
 *                  [--axis X0,Y0,Z0,DX,DY,DZ] [--seed S] [--truth FILE] */
#include <config.h>

#include <getopt.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "axis.h"
#include "native.h"

typedef struct walker {
    int64_t id;
    double s, a, b;   /* along the axis, and across it (e_x, e_y) */
} walker;

int main(int argc, char **argv)
{
    const char *out = NULL, *truth = NULL, *axis_spec = NULL;
    long frames = 200, rate = 10, seed = 1;
    double dt = 0.01, stop = INFINITY, v = 0.2, D = 1e-4, length = 0.5, radius = 0.01;
    static const struct option opts[] = {
        {"output", required_argument, NULL, 'o'}, {"frames", required_argument, NULL, 'f'},
        {"dt", required_argument, NULL, 't'},     {"rate", required_argument, NULL, 'r'},
        {"stop", required_argument, NULL, 'S'},   {"velocity", required_argument, NULL, 'v'},
        {"D", required_argument, NULL, 'D'},      {"length", required_argument, NULL, 'L'},
        {"radius", required_argument, NULL, 'R'}, {"axis", required_argument, NULL, 'a'},
        {"seed", required_argument, NULL, 's'},   {"truth", required_argument, NULL, 'T'},
        {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "o:", opts, NULL)) != -1) {
        switch (c) {
        case 'o': out = optarg; break;
        case 'f': frames = atol(optarg); break;
        case 't': dt = atof(optarg); break;
        case 'r': rate = atol(optarg); break;
        case 'S': stop = atof(optarg); break;
        case 'v': v = atof(optarg); break;
        case 'D': D = atof(optarg); break;
        case 'L': length = atof(optarg); break;
        case 'R': radius = atof(optarg); break;
        case 'a': axis_spec = optarg; break;
        case 's': seed = atol(optarg); break;
        case 'T': truth = optarg; break;
        default: fprintf(stderr, "make_tube_flow: bad option\n"); return 1;
        }
    }
    mimas_axis axis;
    mimas_error err;
    if (!out || mimas_axis_parse(&axis, axis_spec, &err)) {
        fprintf(stderr, "make_tube_flow: -o FILE is required (and --axis X0,Y0,Z0,DX,DY,DZ)\n");
        return 1;
    }
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, (unsigned long)seed);
    mimas_writer_options o;
    mimas_writer_options_default(&o);
    o.atomic = 1;
    mimas_writer *w;
    if (mimas_writer_open(&w, out, &o, &err)) {
        fprintf(stderr, "make_tube_flow: %s\n", err.msg);
        return 2;
    }
    FILE *tf = truth ? fopen(truth, "w") : NULL;
    size_t cap = (size_t)(rate * frames) + 1, n = 0;
    walker *p = malloc(cap * sizeof *p);
    int64_t next_id = 1;
    mimas_frame f;
    mimas_frame_init(&f);
    int rc = 0;
    for (long k = 0; k < frames && !rc; k++) {
        double time = k * dt;
        /* move, then drop those past the outlet, then let new ones in */
        size_t kept = 0;
        for (size_t i = 0; i < n; i++) {
            p[i].s += v * dt + gsl_ran_gaussian(rng, sqrt(2 * D * dt));
            if (p[i].s <= length)
                p[kept++] = p[i];
        }
        n = kept;
        for (long q = 0; q < rate && time <= stop + 1e-12; q++) {
            double r = radius * sqrt(gsl_rng_uniform(rng)), phi = 2 * M_PI * gsl_rng_uniform(rng);
            p[n++] = (walker){next_id++, 0.0, r * cos(phi), r * sin(phi)};
        }
        mimas_frame_clear(&f);
        f.step = 1000 * k;
        f.time = time;
        /* an open box around the tube */
        for (int d = 0; d < 3; d++) {
            f.box.lo[d] = axis.origin[d] - length - radius - 1;
            f.box.hi[d] = axis.origin[d] + length + radius + 1;
        }
        f.tube.present = 1;
        memcpy(f.tube.origin, axis.origin, sizeof f.tube.origin);
        memcpy(f.tube.direction, axis.ez, sizeof f.tube.direction);
        f.tube.radius = radius;
        f.tube.length = length;
        rc = mimas_table_set_present(&f.particles, &mimas_particles_desc,
                                     MIMAS_P_ID | MIMAS_P_POS | MIMAS_P_RADIUS | MIMAS_P_TYPE |
                                         MIMAS_P_VEL, &err) ||
             mimas_table_resize(&f.particles, &mimas_particles_desc, n, &err);
        for (size_t i = 0; i < n && !rc; i++) {
            f.particles.id[i] = p[i].id;
            f.particles.type[i] = 1 + (int32_t)(p[i].id % 2);
            f.particles.radius[i] = 1e-3;
            for (int d = 0; d < 3; d++) {
                f.particles.pos[i][d] = axis.origin[d] + p[i].a * axis.ex[d] +
                                        p[i].b * axis.ey[d] + p[i].s * axis.ez[d];
                f.particles.vel[i][d] = v * axis.ez[d];
            }
            if (tf)
                fprintf(tf, "%.17g %lld %.17g %.17g %.17g\n", time, (long long)p[i].id,
                        f.particles.pos[i][0], f.particles.pos[i][1], f.particles.pos[i][2]);
        }
        if (!rc)
            rc = mimas_writer_append(w, &f, &err);
    }
    if (tf && fclose(tf) != 0)
        rc = 1;
    mimas_frame_free(&f);
    free(p);
    gsl_rng_free(rng);
    if (rc) {
        fprintf(stderr, "make_tube_flow: %s\n", err.msg);
        mimas_writer_abort(w);
        return 2;
    }
    if (mimas_writer_close(w, &err)) {
        fprintf(stderr, "make_tube_flow: %s\n", err.msg);
        return 2;
    }
    return 0;
}
