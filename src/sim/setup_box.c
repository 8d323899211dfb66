/* The box scenario: particles on a jittered lattice in a box, periodic or
 * walled in each direction, with random initial velocities (a granular gas,
 * or with gravity and a floor, a packing or an incline). */
#include <config.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <limits.h>
#include <math.h>

#include "setup.h"

int sim_setup_box(dem_system *s, const sim_scenario *sc, sim_plan *plan, mimas_error *err)
{
    double d = sc->diameter * sc->coarse_grain, spread = sc->diameter_spread;
    double rmax = d / 2 * (1 + spread), a = 2 * rmax * 1.02;
    int m[3];
    double sites = 1;   /* lattice sites, counted in double: a huge box overflows int */
    for (int q = 0; q < 3; q++) {
        s->lo[q] = 0;
        s->hi[q] = sc->box_size[q];
        s->periodic[q] = sc->box_periodic[q];
        double cells = floor(sc->box_size[q] / a);
        m[q] = cells > INT_MAX ? INT_MAX : (int)cells;
        sites *= cells;
    }
    if (sites < (double)sc->box_count)
        return mimas_error_set(err, MIMAS_EDATA, "[box] %ld particles of diameter up to %g m "
                               "do not fit into the box (at most %.0f)", sc->box_count, 2 * rmax,
                               sites);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!rng)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the random number generator");
    gsl_rng_set(rng, (unsigned long)sc->seed);
    int rc = dem_reserve(s, (size_t)sc->box_count, err);
    for (long k = 0; k < sc->box_count && !rc; k++) {
        long ix = k % m[0], iy = k / m[0] % m[1], iz = k / ((long)m[0] * m[1]);
        double r = d / 2 * (1 + spread * (2 * gsl_rng_uniform(rng) - 1)), room = a / 2 - r;
        double x[3] = {(ix + 0.5) * a, (iy + 0.5) * a, (iz + 0.5) * a};
        for (int q = 0; q < 3; q++)
            x[q] += room * (2 * gsl_rng_uniform(rng) - 1);
        size_t p = dem_add_particle(s, 1, r, sc->density, x);
        double dir[3], speed = sc->box_speed * gsl_rng_uniform(rng);
        gsl_ran_dir_3d(rng, &dir[0], &dir[1], &dir[2]);
        for (int q = 0; q < 3; q++)
            s->v[p][q] = speed * dir[q];
    }
    gsl_rng_free(rng);
    for (int q = 0; q < 3 && !rc; q++) {
        if (s->periodic[q])
            continue;
        dem_wall lo = {.kind = DEM_WALL_PLANE, .id = 2 * q + 1}, hi = lo;
        hi.id = 2 * q + 2;
        lo.normal[q] = 1;
        hi.normal[q] = -1;
        hi.point[q] = s->hi[q];
        if (!(rc = dem_add_wall(s, &lo, err)))
            rc = dem_add_wall(s, &hi, err);
    }
    if (rc)
        return rc;
    plan->total_steps = llround(sc->box_time / sc->dt);
    for (int q = 0; q < 3; q++) {
        plan->box.lo[q] = s->lo[q];
        plan->box.hi[q] = s->hi[q];
        plan->box.periodic[q] = s->periodic[q];
    }
    return MIMAS_OK;
}
