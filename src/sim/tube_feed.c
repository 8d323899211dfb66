/* The periodic block of the feed column (tube_feed.h). */
#include <config.h>

#include "tube_feed.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"

void sim_feed_block_free(sim_feed_block *b)
{
    free(b->x);
    memset(b, 0, sizeof *b);
}

/* largest overlap of any pair or with the wall, m */
static double worst_overlap(const dem_system *s)
{
    double worst = 0;
    for (size_t i = 0; i < s->n; i++) {
        for (size_t k = s->nl.start[i]; k < s->nl.start[i + 1]; k++) {
            size_t j = (size_t)s->nl.e[k].j;
            double d[3];
            dem_separation(s, s->x[i], s->x[j], d);
            double ov = s->radius[i] + s->radius[j] - sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (ov > worst)
                worst = ov;
        }
        double rho = hypot(s->x[i][0], s->x[i][1]), ov = rho + s->radius[i] - s->walls[0].radius;
        if (ov > worst)
            worst = ov;
    }
    return worst;
}

int sim_feed_block_make(sim_feed_block *b, const sim_scenario *sc, double R, double phi,
                        mimas_error *err)
{
    memset(b, 0, sizeof *b);
    double d = sc->diameter * sc->coarse_grain, r = d / 2, Vp = M_PI / 6 * d * d * d;
    double L = 10 * d;
    size_t n = (size_t)lround((1 - phi) * M_PI * R * R * L / Vp);
    if (n == 0)
        return mimas_error_set(err, MIMAS_EDATA, "[plugtube] the feed column holds no grains");
    /* the packing run: frictionless, strongly damped, no gravity, periodic in z */
    sim_scenario ps = *sc;
    memset(ps.gravity, 0, sizeof ps.gravity);
    ps.rotation = 0;
    ps.liquid_content = 0;
    for (int a = 0; a < SIM_MAX_TYPES; a++)
        for (int c = 0; c < SIM_MAX_TYPES; c++) {
            ps.contact[a][c].friction = 0;
            ps.contact[a][c].cohesion_energy = 0;
            if (ps.contact[a][c].model == SIM_LINEAR && ps.contact[a][c].restitution > 0.3)
                ps.contact[a][c].restitution = 0.3;
        }
    ps.dt_guard = 0;
    dem_system s;
    dem_init(&s);
    s.lo[2] = 0;
    s.hi[2] = L;
    s.periodic[2] = 1;
    dem_wall wall = {.kind = DEM_WALL_CYLINDER, .id = 1, .radius = R};
    int rc = dem_reserve(&s, n, err);
    if (!rc)
        rc = dem_add_wall(&s, &wall, err);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!rng && !rc)
        rc = mimas_error_set(err, MIMAS_EIO, "out of memory");
    if (rng)
        gsl_rng_set(rng, (unsigned long)sc->seed + 7919);
    /* random sequential addition at half the radius */
    const double r0 = 0.5 * r, room = R - r;
    for (size_t k = 0; k < n && !rc; k++) {
        int placed = 0;
        for (int tries = 0; tries < 100000 && !placed; tries++) {
            double x[3] = {room * (2 * gsl_rng_uniform(rng) - 1),
                           room * (2 * gsl_rng_uniform(rng) - 1), L * gsl_rng_uniform(rng)};
            if (hypot(x[0], x[1]) > room)
                continue;
            placed = 1;
            for (size_t j = 0; j < s.n && placed; j++) {
                double dd[3];
                dem_separation(&s, x, s.x[j], dd);
                placed = dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2] > 4 * r0 * r0;
            }
            if (placed)
                dem_add_particle(&s, 1, r, sc->density, x);
        }
        if (!placed)
            rc = mimas_error_set(err, MIMAS_EDATA, "[plugtube] cannot place the grains of the "
                                 "feed column (feed_porosity %g too low)", phi);
    }
    if (rng)
        gsl_rng_free(rng);
    if (!rc)
        rc = dem_configure(&s, &ps, err);
    /* growth from r0 to r, then relaxation with the velocities reset */
    const int grow = 3000, relax = 3000;
    for (int step = 0; step <= grow + relax && !rc; step++) {
        if (step <= grow) {
            double rr = r0 + (r - r0) * step / grow;
            for (size_t k = 0; k < s.n; k++)
                s.radius[k] = rr;
        }
        if (step % 50 == 0) {
            if (step > grow)
                memset(s.v, 0, s.n * sizeof *s.v);
            if (!(rc = dem_neighbours_build(&s, err)))
                dem_forces(&s);
        }
        if (!rc)
            rc = dem_step(&s, err);
    }
    if (!rc && !(rc = dem_neighbours_build(&s, err))) {
        double worst = worst_overlap(&s);
        if (worst > 0.01 * d)
            rc = mimas_error_set(err, MIMAS_EDATA, "[plugtube] the feed column does not pack at "
                                 "feed_porosity %g (overlaps of %.2g d remain)", phi, worst / d);
    }
    if (!rc) {
        b->x = malloc(n * sizeof *b->x);
        if (!b->x)
            rc = mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    if (!rc) {
        b->n = s.n;
        b->length = L;
        for (size_t k = 0; k < s.n; k++) {
            memcpy(b->x[k], s.x[k], sizeof b->x[k]);
            b->x[k][2] -= L * floor(b->x[k][2] / L);
            if (b->x[k][2] >= L)
                b->x[k][2] = 0;
        }
        b->porosity = 1 - (double)s.n * Vp / (M_PI * R * R * L);
    }
    dem_free(&s);
    return rc;
}
