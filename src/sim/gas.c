/* The time step of the gas model (gas.h; docs/theory.md §4; Strauß 2005,
 * Sec. 3.2.2-3.2.3): the explicit source step, then Crank-Nicolson
 * diffusion direction by direction. */
#include <config.h>

#include "gas.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>

/* porosity as the coefficients take it */
static double phi_of(const sim_gas *g, size_t c)
{
    return fmin(1, fmax(0.2, g->porosity[c]));
}

/* grain velocity through face node q of direction d; along the tube the
 * grains enter with inlet_u and leave (never return) through the outlet,
 * the wall is closed */
static double face_u(const sim_gas *g, int d, size_t q, size_t along, double inlet_u)
{
    const sim_gas_faces *f = &g->f[d];
    if (along > 0 && along < f->m[d] - 1)
        return f->u[q];
    if (d < 2)
        return 0;
    return along == 0 ? inlet_u : fmax(0, f->u[q]);
}

/* the face nodes below and above cell (i, j, k) along d */
static void faces_of(const sim_gas *g, int d, const size_t idx[3], size_t *below, size_t *above)
{
    const size_t *m = g->f[d].m;
    size_t lo[3] = {idx[0], idx[1], idx[2]}, hi[3] = {idx[0], idx[1], idx[2]};
    hi[d]++;
    *below = lo[0] + m[0] * (lo[1] + m[1] * lo[2]);
    *above = hi[0] + m[0] * (hi[1] + m[1] * hi[2]);
}

/* The explicit source step: P -= (P0 dt/phi) div u (the sign fixed against
 * the print of Strauß' eq. 3.59), plus P0 A_t v_s dt/(phi V_s) in the inlet
 * layer and minus that in the outlet layer (eq. 3.53). */
static void source_step(sim_gas *g, double dt, double inlet_u)
{
    const double P0 = g->p.P0, At = M_PI * g->p.radius * g->p.radius;
    const double feed = P0 * At * g->p.v_s * dt / g->layer_volume;
    for (size_t k = 0; k < g->n[2]; k++)
        for (size_t j = 0; j < g->n[1]; j++)
            for (size_t i = 0; i < g->n[0]; i++) {
                size_t c = sim_gas_index(g, i, j, k), idx[3] = {i, j, k};
                double a = g->fraction[c];
                if (!(a > 0))
                    continue;
                double div = 0;
                for (int d = 0; d < 3; d++) {
                    size_t qb, qa;
                    faces_of(g, d, idx, &qb, &qa);
                    const double *fr = g->f[d].fraction;
                    div += (fr[qa] * face_u(g, d, qa, idx[d] + 1, inlet_u) -
                            fr[qb] * face_u(g, d, qb, idx[d], inlet_u)) /
                           (a * g->h[d]);
                }
                double phi = phi_of(g, c), dp = -P0 * dt * div / phi;
                if (k == 0)
                    dp += feed / phi;
                if (k == g->n[2] - 1)
                    dp -= feed / phi;
                g->pressure[c] += dp;
            }
}

/* cell of position p on line l of the lines along d (lines in a fixed order) */
static size_t line_cell(const sim_gas *g, int d, size_t l, size_t p)
{
    int e1 = d == 0 ? 1 : 0, e2 = d == 2 ? 1 : 2;
    size_t idx[3];
    idx[d] = p;
    idx[e1] = l % g->n[e1];
    idx[e2] = l / g->n[e1];
    return sim_gas_index(g, idx[0], idx[1], idx[2]);
}

/* Crank-Nicolson along d for all lines at once: one symmetric tridiagonal
 * system, each row of Strauß' eq. 3.64 multiplied by 1/g_j (g_j = P0 dt/(2
 * phi_j eta a_j h^2), a_j the cell's fraction inside the tube), which makes
 * it symmetric, and the lines uncoupled from each other. */
static void diffuse_along(sim_gas *g, int d, double dt)
{
    size_t nc = sim_gas_cells(g), m = g->n[d], lines = nc / m;
    double *diag = g->scratch, *off = diag + nc, *rhs = off + nc, *x = rhs + nc;
    const sim_gas_faces *f = &g->f[d];
    const double h = g->h[d], th = g->p.theta;
    size_t t = 0;
    for (size_t l = 0; l < lines; l++)
        for (size_t p = 0; p < m; p++, t++) {
            size_t c = line_cell(g, d, l, p);
            size_t cb = p > 0 ? line_cell(g, d, l, p - 1) : c;
            size_t ca = p + 1 < m ? line_cell(g, d, l, p + 1) : c;
            size_t idx[3] = {c % g->n[0], c / g->n[0] % g->n[1], c / (g->n[0] * g->n[1])};
            size_t qb, qa;
            faces_of(g, d, idx, &qb, &qa);
            double a = g->fraction[c];
            double Kb = f->fraction[qb] * f->kappa[qb], Ka = f->fraction[qa] * f->kappa[qa];
            if (!(g->fraction[cb] > 0))
                Kb = 0;
            if (!(g->fraction[ca] > 0))
                Ka = 0;
            off[t] = p + 1 < m ? -Ka : 0;
            if (!(a > 0)) {
                diag[t] = 1;
                rhs[t] = g->pressure[c];
                off[t] = 0;
                continue;
            }
            double inv_G = phi_of(g, c) * g->p.eta * a * h * h / (g->p.P0 * dt);
            const double *P = g->pressure;
            diag[t] = inv_G + th * (Kb + Ka);
            off[t] *= th;
            rhs[t] = inv_G * P[c] + (1 - th) * (Ka * (P[ca] - P[c]) - Kb * (P[c] - P[cb]));
        }
    gsl_vector_view vd = gsl_vector_view_array(diag, nc), vo = gsl_vector_view_array(off, nc - 1);
    gsl_vector_view vr = gsl_vector_view_array(rhs, nc), vx = gsl_vector_view_array(x, nc);
    gsl_linalg_solve_symm_tridiag(&vd.vector, &vo.vector, &vr.vector, &vx.vector);
    t = 0;
    for (size_t l = 0; l < lines; l++)
        for (size_t p = 0; p < m; p++, t++)
            g->pressure[line_cell(g, d, l, p)] = x[t];
}

static void update_gradients(sim_gas *g)
{
    for (int d = 0; d < 3; d++) {
        sim_gas_faces *f = &g->f[d];
        for (size_t k = 0; k < f->m[2]; k++)
            for (size_t j = 0; j < f->m[1]; j++)
                for (size_t i = 0; i < f->m[0]; i++) {
                    size_t q = i + f->m[0] * (j + f->m[1] * k), idx[3] = {i, j, k};
                    f->grad[q] = 0;
                    if (idx[d] == 0 || idx[d] == f->m[d] - 1)
                        continue;   /* closed: no normal gradient */
                    size_t hi = sim_gas_index(g, idx[0], idx[1], idx[2]);
                    idx[d]--;
                    size_t lo = sim_gas_index(g, idx[0], idx[1], idx[2]);
                    if (g->fraction[lo] > 0 && g->fraction[hi] > 0)
                        f->grad[q] = (g->pressure[hi] - g->pressure[lo]) / g->h[d];
                }
    }
}

void sim_gas_diffuse(sim_gas *g, double dt)
{
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    for (int d = 0; d < 3; d++)
        diffuse_along(g, d, dt);
    gsl_set_error_handler(old);
    update_gradients(g);
}

void sim_gas_step(sim_gas *g, double dt, double inlet_u)
{
    source_step(g, dt, inlet_u);
    sim_gas_diffuse(g, dt);
    /* gauge: the outlet layer at the ambient pressure */
    size_t k = g->n[2] - 1;
    double sum = 0, wsum = 0;
    for (size_t j = 0; j < g->n[1]; j++)
        for (size_t i = 0; i < g->n[0]; i++) {
            size_t c = sim_gas_index(g, i, j, k);
            sum += g->fraction[c] * g->pressure[c];
            wsum += g->fraction[c];
        }
    double shift = sum / wsum;
    for (size_t c = 0; c < sim_gas_cells(g); c++)
        g->pressure[c] -= shift;
}

void sim_gas_velocity(const sim_gas *g, double (*v)[3])
{
    for (size_t k = 0; k < g->n[2]; k++)
        for (size_t j = 0; j < g->n[1]; j++)
            for (size_t i = 0; i < g->n[0]; i++) {
                size_t c = sim_gas_index(g, i, j, k), idx[3] = {i, j, k};
                for (int d = 0; d < 3; d++) {
                    size_t qb, qa;
                    faces_of(g, d, idx, &qb, &qa);
                    const sim_gas_faces *f = &g->f[d];
                    v[c][d] = -(f->kappa[qb] * f->grad[qb] + f->kappa[qa] * f->grad[qa]) /
                              (2 * g->p.eta);
                }
            }
}
