/* Blow-up detection of mimas simulate (see dem.h): a run whose state stops
 * being physical ends with a message instead of running on into overflows.
 * Checked before every neighbour-list build and every frame: a blowing-up
 * state moves particles further than the skin, so the next build comes at
 * once. */
#include <config.h>

#include <math.h>
#include <stdio.h>

#include "dem.h"

static double norm(const double v[3])
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static int blew_up(const dem_system *s, size_t k, mimas_error *err, const char *what)
{
    return mimas_error_set(err, MIMAS_EDATA, "step %lld: particle id %lld at (%.6g, %.6g, %.6g) "
                           "m %s: the simulation blew up; the likely cause is a time step too "
                           "large for the contact law (dt = %g s; lower it)",
                           (long long)s->step, (long long)s->id[k], s->x[k][0], s->x[k][1],
                           s->x[k][2], what, s->dt);
}

int dem_check_state(const dem_system *s, mimas_error *err)
{
    char what[160];
    for (size_t k = 0; k < s->n; k++) {
        double v = norm(s->v[k]), w = norm(s->w[k]);
        if (!isfinite(s->x[k][0]) || !isfinite(s->x[k][1]) || !isfinite(s->x[k][2]) ||
            !isfinite(v) || !isfinite(w))
            return blew_up(s, k, err, "has a position or velocity that is not finite");
        if (v * s->dt > s->radius[k]) {
            snprintf(what, sizeof what, "moves %.3g radii in one step (speed %.3g m/s)",
                     v * s->dt / s->radius[k], v);
            return blew_up(s, k, err, what);
        }
        for (int d = 0; d < 3 && s->has_domain; d++) {
            double size = s->domain_hi[d] - s->domain_lo[d];
            if (s->periodic[d])
                continue;
            if (s->x[k][d] < s->domain_lo[d] - size || s->x[k][d] > s->domain_hi[d] + size) {
                snprintf(what, sizeof what, "left the domain [%.6g, %.6g] m along %c by more "
                         "than its size", s->domain_lo[d], s->domain_hi[d], "xyz"[d]);
                return blew_up(s, k, err, what);
            }
        }
    }
    for (size_t k = 0; s->wall_delta && k < s->n; k++)
        for (int m = 0; m < s->nwalls; m++)
            if (s->wall_delta[k * DEM_MAX_WALLS + (size_t)m] > s->radius[k]) {
                snprintf(what, sizeof what, "overlaps wall %d by %.3g radii", s->walls[m].id,
                         s->wall_delta[k * DEM_MAX_WALLS + (size_t)m] / s->radius[k]);
                return blew_up(s, k, err, what);
            }
    const dem_nlist *nl = &s->nl;
    for (size_t i = 0; nl->start && nl->n == s->n && i < s->n; i++)
        for (size_t e = nl->start[i]; e < nl->start[i + 1]; e++) {
            if (!(nl->e[e].flags & DEM_TOUCH))
                continue;
            size_t j = (size_t)nl->e[e].j;
            double d[3];
            dem_separation(s, s->x[i], s->x[j], d);
            double delta = s->radius[i] + s->radius[j] - norm(d);
            double rmin = fmin(s->radius[i], s->radius[j]);
            if (delta > rmin) {
                snprintf(what, sizeof what, "overlaps particle id %lld by %.3g of the smaller "
                         "radius", (long long)s->id[j], delta / rmin);
                return blew_up(s, i, err, what);
            }
        }
    return MIMAS_OK;
}
