/* The split-bottom ring shear cell (PHYSICS.md 7, 000 Sec. 3.2): an annulus
 * between a static inner cylinder (r_in) and an outer cylinder (r_out) that
 * turns at Omega together with the bottom outside the split radius r_split.
 * Particles are inserted on a jittered lattice without overlap, settle under
 * gravity for settle_time, then the outer part turns for shear_time. */
#include <config.h>

#include <gsl/gsl_rng.h>
#include <math.h>

#include "setup.h"

/* mean of d^3 for d uniform in [d0 (1-s), d0 (1+s)] */
static double mean_cube(double d0, double spread)
{
    double a = d0 * (1 - spread), b = d0 * (1 + spread);
    return spread > 0 ? (pow(b, 4) - pow(a, 4)) / (4 * (b - a)) : d0 * d0 * d0;
}

/* glued particles on the bottom: a jittered square grid of spacing d,
 * resting on z = 0; static inside r_split, turning outside */
static int rough_bottom(dem_system *s, const sim_scenario *sc, double d, gsl_rng *rng,
                        mimas_error *err)
{
    double r = d / 2;
    int m = (int)ceil(sc->r_out / d);
    for (int iy = -m; iy <= m; iy++)
        for (int ix = -m; ix <= m; ix++) {
            double x[3] = {(ix + 0.5 * (gsl_rng_uniform(rng) - 0.5)) * d,
                           (iy + 0.5 * (gsl_rng_uniform(rng) - 0.5)) * d, r};
            double rho = hypot(x[0], x[1]);
            if (rho < sc->r_in + r || rho > sc->r_out - r)
                continue;
            if (dem_reserve(s, s->n + 1, err))
                return err->code;
            size_t k = dem_add_particle(s, 2, r, sc->density, x);
            s->glued[k] = rho >= sc->r_split;
            for (int q = 0; q < 3; q++)
                s->anchor[k][q] = x[q];
        }
    return MIMAS_OK;
}

int sim_setup_ringshear(dem_system *s, const sim_scenario *sc, sim_plan *plan,
                        mimas_error *err)
{
    double alpha = sc->coarse_grain, d = sc->diameter * alpha, spread = sc->diameter_spread;
    double rmax = d / 2 * (1 + spread);
    double area = M_PI * (sc->r_out * sc->r_out - sc->r_in * sc->r_in);
    long count = sc->count;
    if (count == 0)
        count = lround(0.6 * area * sc->fill_height / (M_PI / 6 * mean_cube(d, spread)));
    if (count < 1)
        return mimas_error_set(err, MIMAS_EDATA, "[ringshear] fill_height gives no particles");
    /* the insertion lattices count cells in int */
    if (!(sc->r_out / d <= 1e6) || !(0.6 * area * sc->fill_height / (M_PI / 6 * mean_cube(d, spread)) <= 1e9))
        return mimas_error_set(err, MIMAS_EDATA, "[ringshear] r_out = %g m is more than 10^6 "
                               "particle diameters, or the cell holds more than 10^9 particles",
                               sc->r_out);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!rng)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the random number generator");
    gsl_rng_set(rng, (unsigned long)sc->seed);
    s->motions[0] = (dem_motion){0};
    s->motions[1] = (dem_motion){0};
    s->nmotions = 2;
    int rc = MIMAS_OK;
    double z0 = rmax * 1.01;
    if (sc->rough_bottom) {
        rc = rough_bottom(s, sc, d, rng, err);
        z0 += d;
    }
    /* the free particles: one per cube of edge a, jittered inside it */
    double a = 2 * rmax * 1.02;
    int m = (int)ceil(sc->r_out / a);
    long placed = 0;
    double top = z0;
    for (int iz = 0; placed < count && !rc; iz++)
        for (int iy = -m; iy <= m && placed < count && !rc; iy++)
            for (int ix = -m; ix <= m && placed < count; ix++) {
                double c[3] = {ix * a, iy * a, z0 + iz * a}, rho = hypot(c[0], c[1]);
                if (rho < sc->r_in + a / 2 * 1.01 || rho > sc->r_out - a / 2 * 1.01)
                    continue;
                double r = d / 2 * (1 + spread * (2 * gsl_rng_uniform(rng) - 1));
                double room = a / 2 - r, x[3];
                for (int q = 0; q < 3; q++)
                    x[q] = c[q] + room * (2 * gsl_rng_uniform(rng) - 1);
                if ((rc = dem_reserve(s, s->n + 1, err)))
                    break;
                dem_add_particle(s, 1, r, sc->density, x);
                placed++;
                top = c[2] + a / 2;
            }
    gsl_rng_free(rng);
    if (rc)
        return rc;
    dem_wall bottom = {.kind = DEM_WALL_PLANE, .id = 1, .normal = {0, 0, 1},
                       .moving_from = sc->r_split};
    dem_wall inner = {.kind = DEM_WALL_CYLINDER, .id = 2, .radius = sc->r_in, .outside = 1};
    dem_wall outer = {.kind = DEM_WALL_CYLINDER, .id = 3, .radius = sc->r_out};
    if ((rc = dem_add_wall(s, &bottom, err)) || (rc = dem_add_wall(s, &inner, err)) ||
        (rc = dem_add_wall(s, &outer, err)))
        return rc;
    int64_t settle = llround(sc->settle_time / sc->dt), shear = llround(sc->shear_time / sc->dt);
    plan->total_steps = settle + shear;
    plan->move_from = settle;
    plan->output_from = sc->output_settle ? 0 : settle;
    plan->omega = sc->omega;
    plan->moving_walls = 1u << 0 | 1u << 2;     /* the bottom (outside r_split), the outer cylinder */
    plan->moving_motions = 1u << 1;
    mimas_box *b = &plan->box;
    *b = (mimas_box){.lo = {-sc->r_out, -sc->r_out, 0}, .hi = {sc->r_out, sc->r_out, top}};
    return MIMAS_OK;
}
