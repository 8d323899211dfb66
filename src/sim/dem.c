/* DEM system: particle storage, walls, laws. */
#include <config.h>

#include "dem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cohesion.h"

void dem_init(dem_system *s)
{
    memset(s, 0, sizeof *s);
}

#define PARTICLE_ARRAYS(X)                                                                 \
    X(id) X(type) X(radius) X(mass) X(inertia) X(liquid) X(x) X(v) X(w) X(f) X(t) X(x_ref) \
    X(image) X(glued) X(anchor) X(bridges) X(wall_near) X(held)

void dem_free(dem_system *s)
{
#define FREE(a) free(s->a);
    PARTICLE_ARRAYS(FREE)
#undef FREE
    free(s->wall_xi);
    free(s->wall_f);
    free(s->wall_delta);
    free(s->nl.start);
    free(s->nl.e);
    free(s->nl.bv);
    free(s->nl.tstart);
    free(s->nl.tk);
    free(s->nl.tpos);
    free(s->nl.eft);
    memset(s, 0, sizeof *s);
}

static int grow(void **p, size_t elem, size_t old, size_t cap)
{
    void *q = realloc(*p, cap * elem);
    if (!q)
        return -1;
    memset((char *)q + old * elem, 0, (cap - old) * elem);
    *p = q;
    return 0;
}

static int grow_walls(dem_system *s, size_t old, size_t cap)
{
    size_t nw = DEM_MAX_WALLS;
    return grow((void **)&s->wall_xi, sizeof *s->wall_xi * nw, old, cap) ||
           grow((void **)&s->wall_f, sizeof *s->wall_f * nw, old, cap) ||
           grow((void **)&s->wall_delta, sizeof *s->wall_delta * nw, old, cap);
}

int dem_reserve(dem_system *s, size_t n, mimas_error *err)
{
    if (n <= s->cap)
        return MIMAS_OK;
    size_t cap = s->cap ? s->cap : 64;
    while (cap < n)
        cap *= 2;
    int bad = 0;
#define GROW(a) bad |= grow((void **)&s->a, sizeof *s->a, s->cap, cap);
    PARTICLE_ARRAYS(GROW)
#undef GROW
    bad |= grow_walls(s, s->cap, cap);
    if (bad)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for %zu particles", n);
    s->cap = cap;
    return MIMAS_OK;
}

size_t dem_add_particle(dem_system *s, int32_t type, double radius, double density,
                        const double x[3])
{
    size_t k = s->n++;
    s->id[k] = ++s->last_id;
    s->type[k] = type;
    s->radius[k] = radius;
    s->mass[k] = density * 4.0 / 3.0 * M_PI * radius * radius * radius;
    s->inertia[k] = 0.4 * s->mass[k] * radius * radius;
    memcpy(s->x[k], x, sizeof s->x[k]);
    memcpy(s->x_ref[k], x, sizeof s->x[k]);
    s->glued[k] = -1;
    memset(s->held[k], 0, sizeof s->held[k]);
    return k;
}

int dem_remove(dem_system *s, const uint8_t *drop, mimas_error *err)
{
    size_t n = s->n, m = 0;
    size_t *to = malloc((n ? n : 1) * sizeof *to);
    if (!to)
        return mimas_error_set(err, MIMAS_EIO, "out of memory removing particles");
    for (size_t k = 0; k < n; k++)
        to[k] = drop[k] ? SIZE_MAX : m++;
    if (m == n) {
        free(to);
        return MIMAS_OK;
    }
    const size_t nw = DEM_MAX_WALLS;
    for (size_t k = 0; k < n; k++) {
        size_t q = to[k];
        if (q == SIZE_MAX || q == k)
            continue;
#define MOVE(a) memcpy(&s->a[q], &s->a[k], sizeof *s->a);
        PARTICLE_ARRAYS(MOVE)
#undef MOVE
        memcpy(&s->wall_xi[q * nw], &s->wall_xi[k * nw], nw * sizeof *s->wall_xi);
        memcpy(&s->wall_f[q * nw], &s->wall_f[k * nw], nw * sizeof *s->wall_f);
        memcpy(&s->wall_delta[q * nw], &s->wall_delta[k * nw], nw * sizeof *s->wall_delta);
    }
    s->n = m;
    /* the list in the new numbering: entries of two staying particles */
    dem_nlist *nl = &s->nl;
    int rc = MIMAS_OK;
    if (nl->start && nl->n == n) {
        size_t ne = 0, *start = malloc((m + 1) * sizeof *start);
        if (!start) {
            free(to);
            return mimas_error_set(err, MIMAS_EIO, "out of memory removing particles");
        }
        start[0] = 0;
        for (size_t i = 0; i < n; i++) {
            if (to[i] == SIZE_MAX)
                continue;
            for (size_t k = nl->start[i]; k < nl->start[i + 1]; k++) {
                size_t j = to[nl->e[k].j];
                if (j == SIZE_MAX)
                    continue;
                nl->e[ne] = nl->e[k];
                nl->e[ne].j = (int32_t)j;
                nl->bv[ne] = nl->bv[k];
                ne++;
            }
            start[to[i] + 1] = ne;
        }
        free(nl->start);
        nl->start = start;
        nl->ne = ne;
        nl->n = m;
        rc = dem_neighbours_transpose(nl, err);
    }
    free(to);
    return rc;
}

int dem_add_wall(dem_system *s, const dem_wall *w, mimas_error *err)
{
    if (s->nwalls >= DEM_MAX_WALLS)
        return mimas_error_set(err, MIMAS_EUSAGE, "more than %d walls", DEM_MAX_WALLS);
    s->walls[s->nwalls++] = *w;
    return MIMAS_OK;
}

double dem_law_contact_time(const dem_law *L, double m_eff)
{
    double g = L->damping_factor > 0 ? L->damping_factor * sqrt(L->k_n * m_eff) : L->gamma_n;
    if (L->k_n / m_eff <= (g / (2 * m_eff)) * (g / (2 * m_eff)))
        return 0;   /* overdamped: no oscillation, no contact time */
    double tc, e;
    dem_linear_collision(L->k_n, g, m_eff, L->clip, &tc, &e);
    return tc;
}

int dem_configure(dem_system *s, const sim_scenario *sc, mimas_error *err)
{
    s->coarse_grain = sc->coarse_grain;
    s->any_periodic = s->periodic[0] || s->periodic[1] || s->periodic[2];
    s->dt = sc->dt;
    s->skin = sc->skin * sc->coarse_grain;
    memcpy(s->gravity, sc->gravity, sizeof s->gravity);
    s->rotation = sc->rotation;
    for (int a = 0; a < SIM_MAX_TYPES; a++)
        for (int b = 0; b < SIM_MAX_TYPES; b++)
            dem_law_make(&s->law[a][b], &sc->contact[a][b], sc->coarse_grain);
    /* liquid carried by each particle: V_L = D rho_p V_p / rho_f (docs/theory.md §2.4) */
    s->bridges_on = sc->liquid_content > 0;
    double vmax = 0;
    for (size_t k = 0; k < s->n; k++) {
        double vp = s->mass[k] / sc->density;
        s->liquid[k] = s->bridges_on ? sc->liquid_content * sc->density * vp / sc->liquid_density
                                     : 0;
        if (s->liquid[k] > vmax)
            vmax = s->liquid[k];
    }
    /* the longest bridge possible: two particles each with all their liquid in it */
    s->bridge_range = 0;
    if (s->bridges_on)
        for (int a = 1; a < SIM_MAX_TYPES; a++)
            for (int b = 1; b < SIM_MAX_TYPES; b++) {
                mimas_bridge br = {2 * vmax, s->law[a][b].surface_tension,
                                   s->law[a][b].contact_angle};
                double sc_ab = mimas_bridge_rupture_distance(&br);
                if (sc_ab > s->bridge_range)
                    s->bridge_range = sc_ab;
            }
    /* the time-step guard (docs/theory.md §3): dt <= t_c/50 for the linear laws */
    if (sc->dt_guard) {
        double mmin = INFINITY;
        for (size_t k = 0; k < s->n; k++)
            if (s->glued[k] < 0 && s->mass[k] < mmin)
                mmin = s->mass[k];
        for (int a = 0; a < SIM_MAX_TYPES && isfinite(mmin); a++)
            for (int b = a; b < SIM_MAX_TYPES; b++) {
                const dem_law *L = &s->law[a][b];
                if (L->model != SIM_LINEAR)
                    continue;
                double m_eff = a == 0 ? mmin : mmin / 2;
                double tc = dem_law_contact_time(L, m_eff);
                if (tc > 0 && s->dt > tc / 50)
                    return mimas_error_set(err, MIMAS_EDATA,
                                           "dt = %g s is larger than t_c/50 = %g s of the "
                                           "contact law (types %d-%d); lower dt or set "
                                           "dt_guard = no", s->dt, tc / 50, a, b);
            }
    }
    return MIMAS_OK;
}
