/* Particle <-> grid exchange of the gas model (docs/theory.md §4; Strauß
 * 2005, Sec. 3.3 with the factor V_i/V_cell that the print lacks): tent
 * weights F = f(x) f(y) f(z), f = 1 - |x/h|, about the cell centres (for
 * porosity and the drag) and about the face centres (for the staggered
 * porosity, grain velocity and pressure gradient).  At the tube wall the
 * weight of a node beyond the grid is folded back onto its mirror image (the
 * boundary node), so every particle deposits exactly its volume. */
#include <config.h>

#include "gas.h"

#include <math.h>
#include <string.h>

/* the two nodes along one direction and their weights */
typedef struct tent1 {
    size_t node[2];
    double w[2];
} tent1;

/* about the cell centres lo + (k + 1/2) h, k = 0..n-1, folded at the ends */
static tent1 centre_weights(double x, double lo, double h, size_t n)
{
    double q = (x - lo) / h - 0.5, c = floor(q), t = q - c;
    long c0 = (long)c, c1 = c0 + 1, last = (long)n - 1;
    tent1 r = {{(size_t)(c0 < 0 ? 0 : c0 > last ? last : c0),
                (size_t)(c1 < 0 ? 0 : c1 > last ? last : c1)},
               {1 - t, t}};
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
    tent1 r = {{(size_t)c0, (size_t)c0 + 1}, {1 - t, t}};
    return r;
}

/* the weights of a point for the cell grid (face = -1) or the face grid
 * normal to direction face */
static void weights3(const sim_gas *g, const double x[3], int face, tent1 t[3])
{
    for (int d = 0; d < 3; d++)
        t[d] = d == face ? face_weights(x[d], g->lo[d], g->h[d], g->n[d])
                         : centre_weights(x[d], g->lo[d], g->h[d], g->n[d]);
}

/* the 8 nodes (in a grid of dimensions m) and their weights */
static void nodes8(const tent1 t[3], const size_t m[3], size_t node[8], double w[8])
{
    int k = 0;
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            for (int c = 0; c < 2; c++, k++) {
                node[k] = t[0].node[a] + m[0] * (t[1].node[b] + m[1] * t[2].node[c]);
                w[k] = t[0].w[a] * t[1].w[b] * t[2].w[c];
            }
}

static int inside(const sim_gas *g, const dem_system *s, size_t k)
{
    return s->glued[k] < 0 && s->x[k][2] >= 0 && s->x[k][2] < g->p.length;
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
    /* serial: a fixed summation order, the same for any number of threads */
    for (size_t k = 0; k < s->n; k++) {
        if (!inside(g, s, k))
            continue;
        double r = s->radius[k], V = 4.0 / 3.0 * M_PI * r * r * r;
        tent1 t[3];
        size_t q[8];
        double w[8];
        weights3(g, s->x[k], -1, t);
        nodes8(t, g->n, q, w);
        for (int a = 0; a < 8; a++)
            g->solid[q[a]] += V * w[a];
        for (int d = 0; d < 3; d++) {
            sim_gas_faces *f = &g->f[d];
            double vd = s->v[k][d];
            weights3(g, s->x[k], d, t);
            nodes8(t, f->m, q, w);
            for (int a = 0; a < 8; a++) {
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

void sim_gas_drag(const sim_gas *g, dem_system *s)
{
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < s->n; k++) {
        if (!inside(g, s, k))
            continue;
        tent1 t[3];
        size_t q[8];
        double w[8], phi = 0, grad[3] = {0, 0, 0};
        weights3(g, s->x[k], -1, t);
        nodes8(t, g->n, q, w);
        for (int a = 0; a < 8; a++)
            phi += w[a] * g->porosity[q[a]];
        for (int d = 0; d < 3; d++) {
            const sim_gas_faces *f = &g->f[d];
            weights3(g, s->x[k], d, t);
            nodes8(t, f->m, q, w);
            for (int a = 0; a < 8; a++)
                grad[d] += w[a] * f->grad[q[a]];
        }
        /* the solid fraction carrying the pressure drop; at least 1 % */
        double solid = fmax(1 - phi, 0.01), r = s->radius[k];
        double c = -4.0 / 3.0 * M_PI * r * r * r / solid;
        for (int d = 0; d < 3; d++)
            s->f[k][d] += c * grad[d];
    }
}
