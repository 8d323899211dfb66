/* Particle <-> grid exchange of the gas model (docs/theory.md §4; Strauß
 * 2005, Sec. 3.3 with the factor V_i/V_cell that the print lacks): tent
 * weights F = f(x) f(y) f(z), f = 1 - |x/h|, about the cell centres (for
 * porosity and the drag) and about the face centres (for the staggered
 * porosity, grain velocity and pressure gradient).  At the tube wall the
 * weight of a node beyond the grid is folded back onto its mirror image (the
 * boundary node), so every particle deposits exactly its volume.  The 1-d
 * weights are computed once per particle and direction; nodes that fold
 * onto one are one node, and the faces along a direction with one cell
 * (closed at both ends) take nothing. */
#include <config.h>

#include "gas.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* the nodes along one direction (two, or one where both fold onto the same
 * node) and their weights */
typedef struct tent1 {
    size_t node[2];
    double w[2];
    int count;
} tent1;

/* about the cell centres lo + (k + 1/2) h, k = 0..n-1, folded at the ends */
static tent1 centre_weights(double x, double lo, double h, size_t n)
{
    double q = (x - lo) / h - 0.5, c = floor(q), t = q - c;
    long c0 = (long)c, c1 = c0 + 1, last = (long)n - 1;
    tent1 r = {{(size_t)(c0 < 0 ? 0 : c0 > last ? last : c0),
                (size_t)(c1 < 0 ? 0 : c1 > last ? last : c1)},
               {1 - t, t}, 2};
    if (r.node[0] == r.node[1]) {   /* beyond the first or last centre: all on one */
        r.w[0] = 1;
        r.count = 1;
    }
    return r;
}

/* about the faces lo + k h, k = 0..n */
static tent1 face_weights(double x, double lo, double h, size_t n)
{
    double q = (x - lo) / h, c = floor(q), t = q - c;
    long c0 = (long)c;
    if (c0 < 0) {
        c0 = 0;
        t = 0;
    } else if (c0 >= (long)n) {
        c0 = (long)n - 1;
        t = 1;
    }
    tent1 r = {{(size_t)c0, (size_t)c0 + 1}, {1 - t, t}, 2};
    return r;
}

/* The 1-d weights of a point, once per direction: about the cell centres
 * and about the faces.  The weights of the cell grid take the centre
 * weights in all three directions, those of the face grid normal to d the
 * face weights along d. */
typedef struct sim_gas_tents {
    tent1 centre[3], face[3];
} sim_gas_tents;

static void tents_of(const sim_gas *g, const double x[3], sim_gas_tents *w)
{
    for (int d = 0; d < 3; d++) {
        if (g->n[d] == 1) {   /* one cell: all on it; its faces take nothing */
            w->centre[d] = (tent1){{0, 0}, {1, 0}, 1};
            continue;
        }
        w->centre[d] = centre_weights(x[d], g->lo[d], g->h[d], g->n[d]);
        w->face[d] = face_weights(x[d], g->lo[d], g->h[d], g->n[d]);
    }
}

/* the weights for the cell grid (face = -1) or the face grid normal to face */
static void grid_tents(const sim_gas_tents *w, int face, const tent1 *t[3])
{
    for (int d = 0; d < 3; d++)
        t[d] = d == face ? &w->face[d] : &w->centre[d];
}

/* the nodes (at most 8, in a grid of dimensions m) and their weights; returns
 * their number */
static int nodes8(const tent1 *const t[3], const size_t m[3], size_t node[8], double w[8])
{
    int k = 0;
    for (int a = 0; a < t[0]->count; a++)
        for (int b = 0; b < t[1]->count; b++) {
            size_t ab = t[0]->node[a] + m[0] * t[1]->node[b];
            double wab = t[0]->w[a] * t[1]->w[b];
            for (int c = 0; c < t[2]->count; c++, k++) {
                node[k] = ab + m[0] * m[1] * t[2]->node[c];
                w[k] = wab * t[2]->w[c];
            }
        }
    return k;
}

/* on the grid: start <= z < length */
static int on_grid(const sim_gas *g, const dem_system *s, size_t k)
{
    return s->x[k][2] >= g->p.start && s->x[k][2] < g->p.length;
}

void sim_gas_deposit(sim_gas *g, const dem_system *s)
{
    size_t nc = sim_gas_cells(g);
    memset(g->solid, 0, nc * sizeof *g->solid);
    for (int d = 0; d < 3; d++) {
        size_t nf = g->f[d].m[0] * g->f[d].m[1] * g->f[d].m[2];
        memset(g->f[d].phi, 0, nf * sizeof *g->f[d].phi);   /* sum of V w */
        memset(g->f[d].u, 0, nf * sizeof *g->f[d].u);       /* sum of V w v_d */
    }
    /* the weights are kept for sim_gas_drag_held at the same positions (when
     * the cache cannot grow, that function computes them again: the same
     * numbers) */
    if (s->n > g->tents_cap) {
        void *c = realloc(g->tents, s->n * sizeof(sim_gas_tents));
        if (c) {
            g->tents = c;
            g->tents_cap = s->n;
        }
    }
    sim_gas_tents *cache = s->n <= g->tents_cap ? g->tents : NULL;
    g->tents_n = cache ? s->n : 0;
    /* serial: a fixed summation order, the same for any number of threads */
    for (size_t k = 0; k < s->n; k++) {
        if (!on_grid(g, s, k))
            continue;
        double r = s->radius[k], V = 4.0 / 3.0 * M_PI * r * r * r;
        sim_gas_tents own, *wkp = cache ? &cache[k] : &own;
        tents_of(g, s->x[k], wkp);
        const tent1 *t[3];
        size_t q[8];
        double w[8];
        grid_tents(wkp, -1, t);
        int nq = nodes8(t, g->n, q, w);
        for (int a = 0; a < nq; a++)
            g->solid[q[a]] += V * w[a];
        for (int d = 0; d < 3; d++) {
            if (g->n[d] == 1)
                continue;   /* both faces along d are the closed wall: nothing to carry */
            sim_gas_faces *f = &g->f[d];
            double vd = s->v[k][d];
            grid_tents(wkp, d, t);
            nq = nodes8(t, f->m, q, w);
            for (int a = 0; a < nq; a++) {
                f->phi[q[a]] += V * w[a];
                f->u[q[a]] += V * w[a] * vd;
            }
        }
    }
    double vcell = g->h[0] * g->h[1] * g->h[2];
    for (size_t c = 0; c < nc; c++)
        g->porosity[c] = g->fraction[c] > 0 ? 1 - g->solid[c] / (g->fraction[c] * vcell) : 1;
    for (int d = 0; d < 3; d++) {
        sim_gas_faces *f = &g->f[d];
        size_t nf = f->m[0] * f->m[1] * f->m[2];
        for (size_t q = 0; q < nf; q++) {
            double sv = f->phi[q];
            f->u[q] = sv > 0 ? f->u[q] / sv : 0;
            f->phi[q] = f->cv_fraction[q] > 0 ? 1 - sv / (f->cv_fraction[q] * vcell) : 1;
        }
    }
    sim_gas_update_permeability(g);
}

/* the drag -V grad P/(1 - phi) on a sphere of radius r with weights w */
static void drag_of(const sim_gas *g, const sim_gas_tents *wk, double r, double out[3])
{
    const tent1 *t[3];
    size_t q[8];
    double w[8], phi = 0, grad[3] = {0, 0, 0};
    grid_tents(wk, -1, t);
    int nq = nodes8(t, g->n, q, w);
    for (int a = 0; a < nq; a++)
        phi += w[a] * g->porosity[q[a]];
    for (int d = 0; d < 3; d++) {
        if (g->n[d] == 1)
            continue;   /* closed faces only: no gradient along d */
        const sim_gas_faces *f = &g->f[d];
        grid_tents(wk, d, t);
        nq = nodes8(t, f->m, q, w);
        for (int a = 0; a < nq; a++)
            grad[d] += w[a] * f->grad[q[a]];
    }
    /* the solid fraction carrying the pressure drop; at least 1 % */
    double solid = fmax(1 - phi, 0.01);
    double c = -4.0 / 3.0 * M_PI * r * r * r / solid;
    for (int d = 0; d < 3; d++)
        out[d] = c * grad[d];
}

static int drag_applies(const sim_gas *g, const dem_system *s, size_t k)
{
    return s->glued[k] < 0 && on_grid(g, s, k);   /* the feed column moves as it is pushed */
}

void sim_gas_drag(const sim_gas *g, dem_system *s)
{
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < s->n; k++) {
        if (!drag_applies(g, s, k))
            continue;
        sim_gas_tents wk;
        double F[3];
        tents_of(g, s->x[k], &wk);
        drag_of(g, &wk, s->radius[k], F);
        for (int d = 0; d < 3; d++)
            s->f[k][d] += F[d];
    }
}

void sim_gas_drag_held(const sim_gas *g, const dem_system *s, double (*held)[3])
{
    const sim_gas_tents *cache = s->n <= g->tents_n ? g->tents : NULL;
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < s->n; k++) {
        held[k][0] = held[k][1] = held[k][2] = 0;
        if (!drag_applies(g, s, k))
            continue;
        sim_gas_tents own;
        const sim_gas_tents *wk = cache ? &cache[k] : &own;
        if (!cache)
            tents_of(g, s->x[k], &own);
        drag_of(g, wk, s->radius[k], held[k]);
    }
}
