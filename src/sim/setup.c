/* Scenario set-up shared parts: resolving derived parameters, dispatch, the
 * plan. */
#include <config.h>

#include "setup.h"

#include <math.h>
#include <string.h>

int sim_scenario_resolve(const sim_scenario *sc, sim_scenario *r, mimas_error *err)
{
    *r = *sc;
    if (sc->type == SIM_PLUGTUBE) {
        memset(r->gravity, 0, sizeof r->gravity);
        r->gravity[sc->tube_orientation == SIM_TUBE_VERTICAL ? 2 : 0] = -sc->tube_gravity;
    }
    double g = sqrt(r->gravity[0] * r->gravity[0] + r->gravity[1] * r->gravity[1] +
                    r->gravity[2] * r->gravity[2]);
    double alpha = sc->coarse_grain, d = sc->diameter;
    double m = sc->density * M_PI / 6 * d * d * d;
    for (int a = 0; a < SIM_MAX_TYPES; a++)
        for (int b = 0; b < SIM_MAX_TYPES; b++) {
            sim_contact_params *c = &r->contact[a][b];
            if (c->model != SIM_LINEAR || !(c->resting_overlap > 0))
                continue;
            if (!(g > 0))
                return mimas_error_set(err, MIMAS_EDATA, "[contact] resting_overlap needs "
                                       "gravity");
            /* the particle before coarse graining; k_n then scales with alpha */
            c->k_n = m * g / (c->resting_overlap * d);
        }
    if (r->dt == 0) {
        double dmin = d * alpha * (1 - sc->diameter_spread);
        double mmin = sc->density * M_PI / 6 * dmin * dmin * dmin, dt = INFINITY;
        for (int a = 0; a < SIM_MAX_TYPES; a++)
            for (int b = a; b < SIM_MAX_TYPES; b++) {
                dem_law L;
                dem_law_make(&L, &r->contact[a][b], alpha);
                if (L.model != SIM_LINEAR)
                    continue;
                double tc = dem_law_contact_time(&L, a == 0 ? mmin : mmin / 2);
                if (tc > 0 && tc / 50 < dt)
                    dt = tc / 50;
            }
        if (!isfinite(dt))
            return mimas_error_set(err, MIMAS_EDATA, "[run] dt = 0 needs a linear contact law "
                                   "with a contact time (set dt)");
        r->dt = dt;
    }
    return MIMAS_OK;
}

int sim_setup(dem_system *s, const sim_scenario *scenario, sim_plan *plan, mimas_error *err)
{
    *plan = (sim_plan){0};
    sim_scenario sc;
    int rc = sim_scenario_resolve(scenario, &sc, err);
    /* the run's length in steps of the resolved dt */
    if (!rc && scenario->dt == 0)
        rc = sim_scenario_check(&sc, "the scenario", err);
    if (rc)
        return rc;
    rc = sc.type == SIM_RINGSHEAR ? sim_setup_ringshear(s, &sc, plan, err)
         : sc.type == SIM_BOX     ? sim_setup_box(s, &sc, plan, err)
         : sc.type == SIM_PULLOFF ? sim_setup_pulloff(s, &sc, plan, err)
                                  : sim_setup_plugtube(s, &sc, plan, err);
    if (rc)
        return rc;
    s->has_domain = 1;
    for (int d = 0; d < 3; d++) {
        s->domain_lo[d] = plan->box.lo[d];
        s->domain_hi[d] = plan->box.hi[d];
    }
    return dem_configure(s, &sc, err);
}

void sim_plan_free(sim_plan *plan, dem_system *s)
{
    if (plan->tube) {
        sim_tube_free(plan->tube);
        if (s)
            s->hooks = (dem_hooks){0};
    }
    plan->tube = NULL;
}

size_t sim_plan_state(const sim_plan *plan, sim_ck_chunk *chunks, size_t max)
{
    return plan->tube ? sim_tube_state(plan->tube, chunks, max) : 0;
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
