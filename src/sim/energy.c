/* The energies of the current state (docs/simulate.md, "Energies"): what
 * mimas simulate writes per frame as the observables kinetic_energy,
 * rotational_energy, elastic_energy and bridge_energy. */
#include <config.h>

#include <gsl/gsl_integration.h>
#include <math.h>

#include "cohesion.h"
#include "contact_force.h"
#include "dem.h"

/* Gauss-Legendre points for the bridge work: the force is smooth in the gap
 * up to the rupture distance, where the integral ends */
#define BRIDGE_POINTS 20

/* The spring energy of a contact of overlap delta > 0 with tangential spring
 * xi: linear (1/2) k_n delta^2 + (1/2) k_t |xi|^2; Hertz the integral of
 * (4/3) E* sqrt(R*) delta^(3/2), (8/15) E* sqrt(R*) delta^(5/2), and
 * (1/2) k_t |xi|^2 with the current k_t = 8 G* sqrt(R* delta). */
static double spring_energy(const dem_law *L, double R_eff, double delta, const double xi[3])
{
    double xi2 = dem_dot(xi, xi);
    if (L->model == SIM_HERTZ) {
        double sq = sqrt(R_eff * delta);
        return 8.0 / 15.0 * L->E_star * sq * delta * delta + 0.5 * 8 * L->G_star * sq * xi2;
    }
    return 0.5 * L->k_n * delta * delta + 0.5 * L->k_t * xi2;
}

typedef struct bridge_ctx {
    mimas_bridge b;
    double r_p;
} bridge_ctx;

static double bridge_force_at(double s, void *ctx)
{
    const bridge_ctx *c = ctx;
    return mimas_bridge_force(&c->b, c->r_p, s);
}

double dem_bridge_energy(const mimas_bridge *b, double r_p, double s, const void *table)
{
    double sc = mimas_bridge_rupture_distance(b);
    if (s < 0)
        s = 0;
    if (!(b->volume > 0) || s >= sc)
        return 0;
    bridge_ctx c = {*b, r_p};
    gsl_function F = {bridge_force_at, &c};
    if (table)
        return gsl_integration_glfixed(&F, s, sc, table);
    gsl_integration_glfixed_table *own = gsl_integration_glfixed_table_alloc(BRIDGE_POINTS);
    double w = own ? gsl_integration_glfixed(&F, s, sc, own) : NAN;
    if (own)
        gsl_integration_glfixed_table_free(own);
    return w;
}

int dem_energies(const dem_system *s, dem_energy *e, mimas_error *err)
{
    e->kinetic = e->rotational = e->elastic = e->bridge = 0;
    gsl_integration_glfixed_table *table = gsl_integration_glfixed_table_alloc(BRIDGE_POINTS);
    if (!table)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    const dem_nlist *nl = &s->nl;
    for (size_t i = 0; i < s->n; i++) {
        int free_i = s->glued[i] < 0;
        if (free_i) {
            e->kinetic += 0.5 * s->mass[i] * dem_dot(s->v[i], s->v[i]);
            e->rotational += 0.5 * s->inertia[i] * dem_dot(s->w[i], s->w[i]);
        }
        for (size_t k = nl->start[i]; k < nl->start[i + 1]; k++) {
            const dem_entry *en = &nl->e[k];
            size_t j = (size_t)en->j;
            if (!en->flags)
                continue;
            double d[3];
            dem_separation(s, s->x[i], s->x[j], d);
            double ri = s->radius[i], rj = s->radius[j], R_eff = ri * rj / (ri + rj);
            double delta = ri + rj - sqrt(dem_dot(d, d));
            const dem_law *L = &s->law[s->type[i]][s->type[j]];
            if ((en->flags & DEM_TOUCH) && delta > 0)
                e->elastic += spring_energy(L, R_eff, delta, en->xi);
            if (en->flags & DEM_BRIDGE) {
                /* as in the force: r_p = 2 R*, the gap s = -delta (0 while touching) */
                mimas_bridge b = {nl->bv[k], L->surface_tension, L->contact_angle};
                e->bridge += dem_bridge_energy(&b, 2 * R_eff, -delta, table);
            }
        }
        for (int m = 0; free_i && m < s->nwalls; m++) {
            size_t slot = i * DEM_MAX_WALLS + (size_t)m;
            if (s->wall_delta[slot] > 0)
                e->elastic += spring_energy(&s->law[0][s->type[i]], s->radius[i],
                                            s->wall_delta[slot], s->wall_xi[slot]);
        }
    }
    gsl_integration_glfixed_table_free(table);
    return MIMAS_OK;
}
