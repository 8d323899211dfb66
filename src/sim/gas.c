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
                    size_t qb = g->face_below[d][c], qa = g->face_above[d][c];
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

/* Crank-Nicolson along d for all lines at once: one symmetric tridiagonal
 * system, each row of Strauß' eq. 3.64 multiplied by 1/g_j (g_j = P0 dt/(2
 * phi_j eta a_j h^2), a_j the cell's fraction inside the tube), which makes
 * it symmetric, and the lines uncoupled from each other. */
static void diffuse_along(sim_gas *g, int d, double dt)
{
    size_t nc = sim_gas_cells(g), m = g->n[d];
    double *diag = g->scratch, *off = diag + nc, *rhs = off + nc, *x = rhs + nc;
    const sim_gas_faces *f = &g->f[d];
    const double h = g->h[d], th = g->p.theta, *P = g->pressure;
    const double c0 = g->p.eta * h * h / (g->p.P0 * dt);
    const size_t *order = g->line_order[d], *fb = g->face_below[d], *fa = g->face_above[d];
    for (size_t t = 0; t < nc; t++) {
        size_t p = t % m, c = order[t];
        size_t cb = p > 0 ? order[t - 1] : c, ca = p + 1 < m ? order[t + 1] : c;
        double a = g->fraction[c];
        if (!(a > 0)) {
            diag[t] = 1;
            rhs[t] = P[c];
            off[t] = 0;
            continue;
        }
        double Kb = g->fraction[cb] > 0 ? f->fraction[fb[c]] * f->kappa[fb[c]] : 0;
        double Ka = g->fraction[ca] > 0 ? f->fraction[fa[c]] * f->kappa[fa[c]] : 0;
        double inv_G = phi_of(g, c) * a * c0;
        off[t] = p + 1 < m ? -th * Ka : 0;
        diag[t] = inv_G + th * (Kb + Ka);
        rhs[t] = inv_G * P[c] + (1 - th) * (Ka * (P[ca] - P[c]) - Kb * (P[c] - P[cb]));
    }
    gsl_vector_view vd = gsl_vector_view_array(diag, nc), vo = gsl_vector_view_array(off, nc - 1);
    gsl_vector_view vr = gsl_vector_view_array(rhs, nc), vx = gsl_vector_view_array(x, nc);
    gsl_linalg_solve_symm_tridiag(&vd.vector, &vo.vector, &vr.vector, &vx.vector);
    for (size_t t = 0; t < nc; t++)
        g->pressure[order[t]] = x[t];
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
                size_t c = sim_gas_index(g, i, j, k);
                for (int d = 0; d < 3; d++) {
                    size_t qb = g->face_below[d][c], qa = g->face_above[d][c];
                    const sim_gas_faces *f = &g->f[d];
                    v[c][d] = -(f->kappa[qb] * f->grad[qb] + f->kappa[qa] * f->grad[qa]) /
                              (2 * g->p.eta);
                }
            }
}
