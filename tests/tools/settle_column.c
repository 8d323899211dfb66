/* A static granular column in a vertical tube, settled with the mimas DEM
 * core, for the tests of the tube analyses (wall layering of the radial
 * porosity, the Janssen wall pressure, the force balance weight = bottom
 * force + wall friction).  Writes the last FRAMES frames (every 0.01 s)
 * with contacts and wall contacts to a native file.  Usage:
 *   settle_column -o FILE [--count N] [--d D] [--radius R] [--friction MU]
 *                 [--time T] [--frames F] [--seed S] [--kn K] [--dt DT]
 * Tube: the z axis, the cylinder wall of radius R (wall id 1), the bottom
 * plane z = 0 (wall id 2); dt = 3e-6 s; linear contacts k_n = 1000 N/m (or
 * --kn, --dt; dt must stay below t_c/50), k_t = 2/7 k_n,
 * restitution 0.3, friction MU for every pair and the walls; density
 * 2000 kg/m^3; gravity -9.81 m/s^2 along z.  The particles start on a loose
 * lattice inside the tube and fall. */
#include <config.h>

#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_rng.h>

#include "dem.h"
#include "native.h"
#include "setup.h"

int main(int argc, char **argv)
{
    const char *out = NULL;
    long count = 900, frames = 3, seed = 1;
    double d = 2e-3, R = 5e-3, mu = 0.5, T = 0.6, kn = 1000, dt = 3e-6;
    static const struct option opts[] = {
        {"output", required_argument, NULL, 'o'}, {"count", required_argument, NULL, 'n'},
        {"d", required_argument, NULL, 'd'}, {"radius", required_argument, NULL, 'R'},
        {"friction", required_argument, NULL, 'm'}, {"time", required_argument, NULL, 't'},
        {"frames", required_argument, NULL, 'f'}, {"seed", required_argument, NULL, 's'},
        {"kn", required_argument, NULL, 'k'}, {"dt", required_argument, NULL, 'D'},
        {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "o:", opts, NULL)) != -1) {
        switch (c) {
        case 'o': out = optarg; break;
        case 'n': count = atol(optarg); break;
        case 'd': d = atof(optarg); break;
        case 'R': R = atof(optarg); break;
        case 'm': mu = atof(optarg); break;
        case 't': T = atof(optarg); break;
        case 'f': frames = atol(optarg); break;
        case 's': seed = atol(optarg); break;
        case 'k': kn = atof(optarg); break;
        case 'D': dt = atof(optarg); break;
        default: fprintf(stderr, "settle_column: bad option\n"); return 1;
        }
    }
    if (!out) {
        fprintf(stderr, "settle_column: -o FILE is required\n");
        return 1;
    }
    sim_scenario sc;
    sim_scenario_defaults(&sc, SIM_BOX);
    sc.diameter = d;
    sc.density = 2000;
    sc.dt = dt;
    sc.gravity[2] = -9.81;
    sc.seed = seed;
    for (int i = 0; i < SIM_MAX_TYPES; i++)
        for (int j = 0; j < SIM_MAX_TYPES; j++) {
            sim_contact_params *p = &sc.contact[i][j];
            p->model = SIM_LINEAR;
            p->k_n = kn;
            p->k_t = kn * 2.0 / 7.0;
            p->restitution = 0.3;
            p->gamma_t = 0;
            p->friction = mu;
            p->normal_clip = 1;
        }
    mimas_error err;
    dem_system s;
    dem_init(&s);
    /* a loose lattice: layers of spacing 1.1 d, in each the points of a
     * square grid of spacing 1.1 d inside r <= R - 0.55 d, jittered */
    double a = 1.1 * d, rmax = R - 0.55 * d;
    int per = (int)floor(rmax / a);
    double height = a * (double)(count / 1 + 1);
    for (int q = 0; q < 2; q++) {
        s.lo[q] = -R - d;
        s.hi[q] = R + d;
    }
    s.lo[2] = -d;
    s.hi[2] = height;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, (unsigned long)seed);
    int rc = dem_reserve(&s, (size_t)count, &err);
    long placed = 0;
    for (int layer = 0; !rc && placed < count; layer++)
        for (int i = -per; i <= per && placed < count; i++)
            for (int j = -per; j <= per && placed < count; j++) {
                double x[3] = {i * a, j * a, 0.6 * d + layer * a};
                if (hypot(x[0], x[1]) > rmax)
                    continue;
                for (int q = 0; q < 2; q++)
                    x[q] += 0.04 * d * (2 * gsl_rng_uniform(rng) - 1);
                dem_add_particle(&s, 1, 0.5 * d, sc.density, x);
                placed++;
            }
    gsl_rng_free(rng);
    dem_wall tube = {.kind = DEM_WALL_CYLINDER, .id = 1, .radius = R};
    dem_wall bottom = {.kind = DEM_WALL_PLANE, .id = 2, .normal = {0, 0, 1}};
    if (!rc)
        rc = dem_add_wall(&s, &tube, &err);
    if (!rc)
        rc = dem_add_wall(&s, &bottom, &err);
    if (!rc)
        rc = dem_configure(&s, &sc, &err);
    sim_plan plan = {0};
    for (int q = 0; q < 3; q++) {
        plan.box.lo[q] = s.lo[q];
        plan.box.hi[q] = s.hi[q];
    }
    plan.total_steps = llround(T / sc.dt);
    plan.move_from = plan.total_steps + 1;
    long every = lround(0.01 / sc.dt);
    plan.output_from = plan.total_steps - (frames - 1) * every;
    mimas_writer_options o;
    mimas_writer_options_default(&o);
    o.atomic = 1;
    mimas_writer *w = NULL;
    if (!rc)
        rc = mimas_writer_open(&w, out, &o, &err);
    if (!rc)
        rc = dem_neighbours_build(&s, &err);
    if (!rc)
        dem_forces(&s);
    mimas_frame f;
    mimas_frame_init(&f);
    while (!rc && s.step < plan.total_steps) {
        if ((rc = dem_step(&s, &err)))
            break;
        if (s.step >= plan.output_from && (s.step - plan.output_from) % every == 0) {
            if (!(rc = sim_frame_fill(&s, &plan, &f, &err)))
                rc = mimas_writer_append(w, &f, &err);
        }
    }
    if (!rc)
        rc = mimas_writer_close(w, &err);
    else if (w)
        mimas_writer_abort(w);
    mimas_frame_free(&f);
    dem_free(&s);
    if (rc) {
        fprintf(stderr, "settle_column: %s\n", err.msg);
        return 2;
    }
    return 0;
}
