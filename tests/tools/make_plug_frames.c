/* Writes frames of a tube with known plugs (tests/common/plug_frame.h) for
 * the plugs and radial CLI tests.  Usage:
 *   make_plug_frames -o FILE [--format native|lammps] [--frames F] [--dt DT]
 *       [--radius R] [--d D] [--length L] [--axis X0,Y0,Z0,DX,DY,DZ]
 *       [--dilute NU] [--seed S] [--plug BACK:LENGTH:V[:NU]]...
 *       [--split K:T:AT:V2]
 * Frame k is at time k DT (step 100 k).  --split makes plug K (from 0, in
 * the order given) leave its part below AT x length behind at V2 from time
 * T on.  The LAMMPS dump has ITEM: TIME. */
#include <config.h>

#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "native.h"
#include "plug_frame.h"

static int write_dump(FILE *fp, const mimas_frame *f)
{
    const mimas_particles *p = &f->particles;
    fprintf(fp, "ITEM: TIMESTEP\n%lld\nITEM: TIME\n%.17g\nITEM: NUMBER OF ATOMS\n%zu\n"
                "ITEM: BOX BOUNDS ff ff ff\n%.17g %.17g\n%.17g %.17g\n%.17g %.17g\n"
                "ITEM: ATOMS id type x y z vx vy vz radius mass\n",
            (long long)f->step, f->time, p->n, f->box.lo[0], f->box.hi[0], f->box.lo[1],
            f->box.hi[1], f->box.lo[2], f->box.hi[2]);
    for (size_t i = 0; i < p->n; i++)
        fprintf(fp, "%lld %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n",
                (long long)p->id[i], p->type[i], p->pos[i][0], p->pos[i][1], p->pos[i][2],
                p->vel[i][0], p->vel[i][1], p->vel[i][2], p->radius[i], p->mass[i]);
    return ferror(fp) ? -1 : 0;
}

int main(int argc, char **argv)
{
    const char *out = NULL, *format = "native", *axis = NULL;
    long frames = 10;
    double dt = 0.01;
    tube_spec t;
    tube_spec_default(&t);
    static const struct option opts[] = {
        {"output", required_argument, NULL, 'o'}, {"format", required_argument, NULL, 'F'},
        {"frames", required_argument, NULL, 'f'}, {"dt", required_argument, NULL, 't'},
        {"radius", required_argument, NULL, 'R'}, {"d", required_argument, NULL, 'd'},
        {"length", required_argument, NULL, 'L'}, {"axis", required_argument, NULL, 'a'},
        {"dilute", required_argument, NULL, 'u'}, {"seed", required_argument, NULL, 's'},
        {"plug", required_argument, NULL, 'p'}, {"split", required_argument, NULL, 'S'},
        {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "o:", opts, NULL)) != -1) {
        switch (c) {
        case 'o': out = optarg; break;
        case 'F': format = optarg; break;
        case 'f': frames = atol(optarg); break;
        case 't': dt = atof(optarg); break;
        case 'R': t.radius = atof(optarg); break;
        case 'd': t.d = atof(optarg); break;
        case 'L': t.length = atof(optarg); break;
        case 'a': axis = optarg; break;
        case 'u': t.dilute = atof(optarg); break;
        case 's': t.seed = (unsigned long)atol(optarg); break;
        case 'p': {
            plug_spec *q = &t.plugs[t.nplugs];
            q->nu = 0.55;
            if (t.nplugs == PLUG_MAX ||
                sscanf(optarg, "%lf:%lf:%lf:%lf", &q->back, &q->length, &q->v, &q->nu) < 3) {
                fprintf(stderr, "make_plug_frames: --plug BACK:LENGTH:V[:NU]\n");
                return 1;
            }
            t.nplugs++;
            break;
        }
        case 'S': {
            int k;
            double tt, at, v2;
            if (sscanf(optarg, "%d:%lf:%lf:%lf", &k, &tt, &at, &v2) != 4 || k < 0 ||
                (size_t)k >= t.nplugs) {
                fprintf(stderr, "make_plug_frames: --split K:T:AT:V2 after the plug K\n");
                return 1;
            }
            t.plugs[k].t_split = tt;
            t.plugs[k].split_at = at;
            t.plugs[k].v_split = v2;
            break;
        }
        default: fprintf(stderr, "make_plug_frames: bad option\n"); return 1;
        }
    }
    mimas_error err;
    if (!out || mimas_axis_parse(&t.axis, axis, &err)) {
        fprintf(stderr, "make_plug_frames: -o FILE is required (and a good --axis)\n");
        return 1;
    }
    mimas_frame f;
    mimas_frame_init(&f);
    int rc = 0;
    if (!strcmp(format, "lammps")) {
        FILE *fp = fopen(out, "w");
        for (long k = 0; fp && !rc && k < frames; k++)
            rc = plug_frame(&f, &t, (double)k * dt, 100 * k) || write_dump(fp, &f);
        rc |= !fp || fclose(fp) != 0;
    } else {
        mimas_writer_options o;
        mimas_writer_options_default(&o);
        o.atomic = 1;
        mimas_writer *w;
        rc = mimas_writer_open(&w, out, &o, &err);
        for (long k = 0; !rc && k < frames; k++)
            rc = plug_frame(&f, &t, (double)k * dt, 100 * k) || mimas_writer_append(w, &f, &err);
        rc = rc ? (mimas_writer_abort(w), 1) : mimas_writer_close(w, &err);
    }
    mimas_frame_free(&f);
    if (rc) {
        fprintf(stderr, "make_plug_frames: cannot write %s\n", out);
        return 2;
    }
    return 0;
}
