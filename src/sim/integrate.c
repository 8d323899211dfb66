/* Velocity Verlet (docs/theory.md §3; Bierwisch 2009, eq. 2.2; Strauß 2005, eq. 3.36-3.37) for the free
 * particles; glued particles follow their rigid motion exactly. */
#include <config.h>

#include <math.h>

#include "dem.h"

static void kick(dem_system *s, double half)
{
#pragma omp parallel for schedule(static) if (s->n >= DEM_PARALLEL_MIN)
    for (size_t k = 0; k < s->n; k++) {
        if (s->glued[k] >= 0)
            continue;
        double a = half / s->mass[k], b = half / s->inertia[k];
        for (int q = 0; q < 3; q++) {
            s->v[k][q] += a * s->f[k][q];
            if (s->rotation)
                s->w[k][q] += b * s->t[k][q];
        }
    }
}

static void drift(dem_system *s)
{
    double dt = s->dt;
    for (int m = 0; m < s->nmotions; m++) {
        dem_motion *mo = &s->motions[m];
        mo->angle += mo->omega * dt;
        mo->cos_angle = cos(mo->angle);
        mo->sin_angle = sin(mo->angle);
        for (int q = 0; q < 3; q++)
            mo->shift[q] += mo->velocity[q] * dt;
    }
#pragma omp parallel for schedule(static) if (s->n >= DEM_PARALLEL_MIN)
    for (size_t k = 0; k < s->n; k++) {
        if (s->glued[k] < 0) {
            for (int q = 0; q < 3; q++)
                s->x[k][q] += dt * s->v[k][q];
            continue;
        }
        const dem_motion *mo = &s->motions[s->glued[k]];
        double c = mo->cos_angle, sn = mo->sin_angle;
        double ax = s->anchor[k][0] - mo->axis[0], ay = s->anchor[k][1] - mo->axis[1];
        double rx = c * ax - sn * ay, ry = sn * ax + c * ay;
        s->x[k][0] = mo->axis[0] + rx + mo->shift[0];
        s->x[k][1] = mo->axis[1] + ry + mo->shift[1];
        s->x[k][2] = s->anchor[k][2] + mo->shift[2];
        s->v[k][0] = -mo->omega * ry + mo->velocity[0];
        s->v[k][1] = mo->omega * rx + mo->velocity[1];
        s->v[k][2] = mo->velocity[2];
        s->w[k][0] = s->w[k][1] = 0;
        s->w[k][2] = mo->omega;
        if (mo->release && s->x[k][0] * mo->release_normal[0] + s->x[k][1] * mo->release_normal[1] +
                                   s->x[k][2] * mo->release_normal[2] >= mo->release_offset) {
            s->glued[k] = -1;   /* free from here on, with the motion's velocity */
            if (mo->release_type > 0)
                s->type[k] = mo->release_type;
        }
    }
}

int dem_step(dem_system *s, mimas_error *err)
{
    kick(s, 0.5 * s->dt);
    drift(s);
    if (dem_neighbours_update(s, err) < 0)
        return err->code;
    s->force_step = s->step + 1;
    dem_forces(s);
    kick(s, 0.5 * s->dt);
    s->step++;
    return MIMAS_OK;
}
