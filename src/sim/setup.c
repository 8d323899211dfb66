/* Scenario set-up shared parts: dispatch, the plan, placing particles on a
 * jittered lattice without overlap. */
#include <config.h>

#include "setup.h"

#include <math.h>

int sim_setup(dem_system *s, const sim_scenario *sc, sim_plan *plan, mimas_error *err)
{
    *plan = (sim_plan){0};
    int rc = sc->type == SIM_RINGSHEAR ? sim_setup_ringshear(s, sc, plan, err)
             : sc->type == SIM_BOX     ? sim_setup_box(s, sc, plan, err)
                                       : sim_setup_pulloff(s, sc, plan, err);
    if (rc)
        return rc;
    s->has_domain = 1;
    for (int d = 0; d < 3; d++) {
        s->domain_lo[d] = plan->box.lo[d];
        s->domain_hi[d] = plan->box.hi[d];
    }
    return dem_configure(s, sc, err);
}

void sim_plan_apply(const sim_plan *plan, dem_system *s)
{
    double omega = s->step >= plan->move_from ? plan->omega : 0;
    for (int w = 0; w < s->nwalls; w++)
        if (plan->moving_walls & (1u << w))
            s->walls[w].omega = omega;
    for (int m = 0; m < s->nmotions; m++)
        if (plan->moving_motions & (1u << m))
            s->motions[m].omega = omega;
}
