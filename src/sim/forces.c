/* Forces of one step: particle pairs of the Verlet list, walls, gravity.
 * Each list entry's force is computed on its own (in parallel over
 * particles) and then gathered per particle in a fixed order, so the result
 * is the same bit for bit for any number of threads. */
#include <config.h>

#include <math.h>
#include <string.h>

#include "cohesion.h"
#include "contact_force.h"
#include "dem.h"

/* overlap of entry k of particle i; the separation vector and distance in d, *dist */
static double pair_overlap(const dem_system *s, size_t i, size_t j, double d[3], double *dist)
{
    dem_separation(s, s->x[i], s->x[j], d);
    *dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    return s->radius[i] + s->radius[j] - *dist;
}

/* Liquid bridges, first pass (docs/theory.md §2.4): a bridge forms at first touch and
 * breaks beyond its rupture distance; then every particle counts its
 * bridges.  The second pass shares the liquid with these counts, so the
 * result does not depend on the order in which pairs are visited. */
static void update_bridges(dem_system *s)
{
    dem_nlist *nl = &s->nl;
#pragma omp parallel for schedule(dynamic, 256) if (s->n >= DEM_PARALLEL_MIN)
    for (size_t i = 0; i < s->n; i++)
        for (size_t k = nl->start[i]; k < nl->start[i + 1]; k++) {
            dem_entry *e = &nl->e[k];
            double d[3], dist, delta = pair_overlap(s, i, (size_t)e->j, d, &dist);
            int on = delta >= 0;
            if (!on && (e->flags & DEM_BRIDGE)) {
                const dem_law *L = &s->law[s->type[i]][s->type[e->j]];
                mimas_bridge b = {nl->bv[k], L->surface_tension, L->contact_angle};
                on = -delta <= mimas_bridge_rupture_distance(&b);
            }
            if (on)
                e->flags |= DEM_BRIDGE;
            else {
                e->flags &= ~DEM_BRIDGE;
                nl->bv[k] = 0;
            }
        }
#pragma omp parallel for schedule(static) if (s->n >= DEM_PARALLEL_MIN)
    for (size_t i = 0; i < s->n; i++) {
        int32_t c = 0;
        for (size_t k = nl->start[i]; k < nl->start[i + 1]; k++)
            c += (nl->e[k].flags & DEM_BRIDGE) != 0;
        for (size_t q = nl->tstart[i]; q < nl->tstart[i + 1]; q++)
            c += (nl->e[nl->tk[q]].flags & DEM_BRIDGE) != 0;
        s->bridges[i] = c;
    }
}

static void pair_forces(dem_system *s)
{
    dem_nlist *nl = &s->nl;
    const double dt = s->dt;
#pragma omp parallel for schedule(dynamic, 128) if (s->n >= DEM_PARALLEL_MIN)
    for (size_t i = 0; i < s->n; i++) {
        /* the forces on i are summed here, those on its partners go to their slots */
        double fi[3] = {0, 0, 0}, ti[3] = {0, 0, 0};
        for (size_t k = nl->start[i]; k < nl->start[i + 1]; k++) {
            dem_entry *e = &nl->e[k];
            dem_entry_force *eft = &nl->eft[nl->tpos[k]];
            size_t j = (size_t)e->j;
            int bridge = (e->flags & DEM_BRIDGE) != 0;
            double d[3], rsum = s->radius[i] + s->radius[j];
            dem_separation(s, s->x[i], s->x[j], d);
            double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (d2 >= rsum * rsum && !bridge) {
                if (e->flags) {
                    e->flags = 0;
                    memset(e->xi, 0, sizeof e->xi);
                }
                memset(eft, 0, sizeof *eft);
                continue;
            }
            double dist = sqrt(d2), delta = rsum - dist, inv = 1 / dist;
            dem_contact_geom g;
            double ri = s->radius[i], rj = s->radius[j], rw[3];
            for (int q = 0; q < 3; q++) {
                g.n[q] = d[q] * inv;
                rw[q] = ri * s->w[i][q] + rj * s->w[j][q];
            }
            double rwxn[3];
            dem_cross(rw, g.n, rwxn);
            for (int q = 0; q < 3; q++) {
                g.vc[q] = s->v[i][q] - s->v[j][q] - rwxn[q];
                g.w_rel[q] = s->w[i][q] - s->w[j][q];
            }
            g.delta = delta;
            g.r_i = ri;
            g.r_j = rj;
            g.R_eff = ri * rj / (ri + rj);
            g.m_eff = s->mass[i] * s->mass[j] / (s->mass[i] + s->mass[j]);
            double vb = 0;
            if (bridge) {
                /* the liquid of each particle is shared equally by its bridges */
                vb = s->liquid[i] / (s->bridges[i] > 0 ? s->bridges[i] : 1) +
                     s->liquid[j] / (s->bridges[j] > 0 ? s->bridges[j] : 1);
                nl->bv[k] = vb;
            }
            double f[3], t[3];
            dem_contact_force(&s->law[s->type[i]][s->type[j]], &g, dt, e->xi, vb, f, t, eft->t);
            for (int q = 0; q < 3; q++) {
                eft->f[q] = -f[q];
                fi[q] += f[q];
                ti[q] += t[q];
            }
            e->flags = (delta > 0 ? DEM_TOUCH : 0) | (bridge ? DEM_BRIDGE : 0);
        }
        memcpy(s->f[i], fi, sizeof fi);
        memcpy(s->t[i], ti, sizeof ti);
    }
}

/* The wall w seen from particle k: overlap, normal (wall -> particle) and the
 * contact point on the wall surface; returns the overlap. */
double dem_wall_geometry(const dem_wall *w, const double x[3], double radius, double n[3],
                         double c[3])
{
    double dist;
    if (w->kind == DEM_WALL_PLANE) {
        dist = 0;
        for (int q = 0; q < 3; q++)
            dist += (x[q] - w->point[q]) * w->normal[q];
        for (int q = 0; q < 3; q++) {
            n[q] = w->normal[q];
            c[q] = x[q] - dist * n[q];
        }
    } else {
        double ex = x[0] - w->axis[0], ey = x[1] - w->axis[1], rho = sqrt(ex * ex + ey * ey);
        if (rho == 0) {
            ex = 1;
            rho = 1;
            ey = 0;
        }
        double sign = w->outside ? 1 : -1;
        dist = sign * (rho - w->radius);
        n[0] = sign * ex / rho;
        n[1] = sign * ey / rho;
        n[2] = 0;
        c[0] = w->axis[0] + w->radius * ex / rho;
        c[1] = w->axis[1] + w->radius * ey / rho;
        c[2] = x[2];
    }
    return radius - dist;
}

/* velocity of the wall surface at point c */
void dem_wall_velocity(const dem_wall *w, const double c[3], double v[3])
{
    v[0] = v[1] = v[2] = 0;
    if (w->omega == 0)
        return;
    double rx = c[0] - w->axis[0], ry = c[1] - w->axis[1];
    if (w->kind == DEM_WALL_PLANE && rx * rx + ry * ry < w->moving_from * w->moving_from)
        return;
    v[0] = -w->omega * ry;
    v[1] = w->omega * rx;
}

static void wall_forces(dem_system *s, size_t i, double f[3], double t[3])
{
    for (int wi = 0; wi < s->nwalls; wi++) {
        if (!(s->wall_near[i] & (1u << wi)))
            continue;
        const dem_wall *w = &s->walls[wi];
        size_t slot = i * DEM_MAX_WALLS + (size_t)wi;
        dem_contact_geom g;
        double c[3], vw[3];
        g.delta = dem_wall_geometry(w, s->x[i], s->radius[i], g.n, c);
        if (g.delta <= 0) {   /* no contact: no history, nothing to output */
            memset(s->wall_xi[slot], 0, sizeof s->wall_xi[slot]);
            memset(s->wall_f[slot], 0, sizeof s->wall_f[slot]);
            s->wall_delta[slot] = 0;
            continue;
        }
        dem_wall_velocity(w, c, vw);
        double rw[3], rwxn[3], tj[3];
        for (int q = 0; q < 3; q++)
            rw[q] = s->radius[i] * s->w[i][q];
        dem_cross(rw, g.n, rwxn);
        for (int q = 0; q < 3; q++) {
            g.vc[q] = s->v[i][q] - rwxn[q] - vw[q];
            g.w_rel[q] = s->w[i][q];
        }
        g.r_i = s->radius[i];
        g.r_j = 0;
        g.R_eff = s->radius[i];
        g.m_eff = s->mass[i];
        double fw[3], tw[3];
        dem_contact_force(&s->law[0][s->type[i]], &g, s->dt, s->wall_xi[slot], 0, fw, tw, tj);
        memcpy(s->wall_f[slot], fw, sizeof fw);
        s->wall_delta[slot] = g.delta;
        for (int q = 0; q < 3; q++) {
            f[q] += fw[q];
            t[q] += tw[q];
        }
    }
}

void dem_forces(dem_system *s)
{
    dem_nlist *nl = &s->nl;
    if (s->bridges_on)
        update_bridges(s);
    pair_forces(s);
    if (s->hooks.body_forces)
        s->hooks.body_forces(s->hooks.ctx, s);
#pragma omp parallel for schedule(static) if (s->n >= DEM_PARALLEL_MIN)
    for (size_t i = 0; i < s->n; i++) {
        double f[3], t[3];
        memcpy(f, s->f[i], sizeof f);
        memcpy(t, s->t[i], sizeof t);
        for (size_t m = nl->tstart[i]; m < nl->tstart[i + 1]; m++) {
            const dem_entry_force *eft = &nl->eft[m];
            for (int q = 0; q < 3; q++) {
                f[q] += eft->f[q];
                t[q] += eft->t[q];
            }
        }
        if (s->glued[i] < 0) {
            wall_forces(s, i, f, t);
            for (int q = 0; q < 3; q++)
                f[q] += s->mass[i] * s->gravity[q] + s->held[i][q];
        }
        memcpy(s->f[i], f, sizeof f);
        memcpy(s->t[i], t, sizeof t);
    }
}
