/* The pull-off test (Uhlig 2012, Sec. 4.1): two equal particles joined by a liquid
 * bridge, initially touching, pulled apart along x at constant speed until
 * the gap is `distance` radii.  Both move kinematically; the frames record
 * the bridge force against the gap (compare with Willett, docs/theory.md §2.4). */
#include <config.h>

#include <math.h>

#include "setup.h"

int sim_setup_pulloff(dem_system *s, const sim_scenario *sc, sim_plan *plan, mimas_error *err)
{
    double r = sc->diameter * sc->coarse_grain / 2;
    int rc = dem_reserve(s, 2, err);
    if (rc)
        return rc;
    double x0[3] = {0, 0, 0}, x1[3] = {2 * r, 0, 0};
    size_t a = dem_add_particle(s, 1, r, sc->density, x0);
    size_t b = dem_add_particle(s, 1, r, sc->density, x1);
    s->nmotions = 2;
    s->motions[0] = (dem_motion){0};
    s->motions[1] = (dem_motion){.velocity = {sc->pull_speed, 0, 0}};
    s->glued[a] = 0;
    s->glued[b] = 1;
    for (int q = 0; q < 3; q++) {
        s->anchor[a][q] = x0[q];
        s->anchor[b][q] = x1[q];
    }
    s->glued_interact = 1;
    plan->total_steps = llround(sc->pull_distance * r / sc->pull_speed / sc->dt);
    double end = 2 * r + sc->pull_distance * r;
    plan->box = (mimas_box){.lo = {-r, -r, -r}, .hi = {end + r, r, r}};
    return MIMAS_OK;
}
