/* The contact force of one contact (docs/theory.md §2.1-§2.4), inline because the
 * pair loop of every step calls it once per contact. */
#ifndef MIMAS_SIM_CONTACT_FORCE_H
#define MIMAS_SIM_CONTACT_FORCE_H

#include <math.h>

#include "cohesion.h"
#include "contact_law.h"

static inline double dem_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void dem_cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* The force of one contact.  hist_xi is the tangential spring (updated),
 * bridge_volume > 0 if a liquid bridge acts (then the attraction acts also
 * across a gap).  Writes the force on i, the torques on i and j and returns
 * the repulsive normal force. */
static inline __attribute__((always_inline)) double dem_contact_force(const dem_law *L, const dem_contact_geom *g, double dt,
                         double xi[3], double bridge_volume, double f[3], double ti[3],
                         double tj[3])
{
    const double *n = g->n;
    double vn = dem_dot(g->vc, n);
    double fn = 0, attraction = 0;
    double ft[3] = {0, 0, 0};
    if (g->delta > 0) {
        double k_n, k_t, gamma_n, gamma_t;
        if (L->model == SIM_HERTZ) {
            /* LIGGGHTS' hertz form (docs/theory.md §2.2) */
            double sq = sqrt(g->R_eff * g->delta);
            double S_n = 2 * L->E_star * sq, S_t = 8 * L->G_star * sq;
            k_n = 4.0 / 3.0 * L->E_star * sq;
            k_t = S_t;
            gamma_n = -2 * sqrt(5.0 / 6.0) * L->beta * sqrt(S_n * g->m_eff);
            gamma_t = -2 * sqrt(5.0 / 6.0) * L->beta * sqrt(S_t * g->m_eff);
        } else {
            k_n = L->k_n;
            k_t = L->k_t;
            gamma_n = L->damping_factor > 0 ? L->damping_factor * sqrt(k_n * g->m_eff)
                                            : L->gamma_n;
            gamma_t = L->gamma_t;
        }
        /* never attractive (docs/theory.md §2.1; Strauß 2005, eq. 3.15) unless the clip is off */
        fn = k_n * g->delta - gamma_n * vn;
        if (fn < 0 && L->clip)
            fn = 0;
        if (L->w > 0)
            attraction += mimas_jkr_force(L->w, L->E_tilde, g->R_eff, g->delta);
        /* tangential history spring (docs/theory.md §2.3): turn xi into the current
         * tangent plane keeping its length, add v_t dt */
        double vt[3], len0sq = dem_dot(xi, xi), xn = dem_dot(xi, n);
        for (int k = 0; k < 3; k++) {
            vt[k] = g->vc[k] - vn * n[k];
            xi[k] -= xn * n[k];
        }
        double len1sq = dem_dot(xi, xi);
        if (len1sq > 0 && xn != 0) {
            double scale = sqrt(len0sq / len1sq);
            for (int k = 0; k < 3; k++)
                xi[k] *= scale;
        }
        for (int k = 0; k < 3; k++) {
            xi[k] += vt[k] * dt;
            ft[k] = -k_t * xi[k] - gamma_t * vt[k];
        }
        double ftm = sqrt(dem_dot(ft, ft)), lim = L->mu * (fn > 0 ? fn : 0);
        if (ftm > lim) {
            /* sliding: the spring is shortened so that k_t xi + gamma_t v_t
             * has the length mu |f_n| (as LIGGGHTS does) */
            double s = ftm > 0 ? lim / ftm : 0;
            for (int k = 0; k < 3; k++) {
                ft[k] *= s;
                xi[k] = k_t > 0 ? -(ft[k] + gamma_t * vt[k]) / k_t : 0;
            }
        }
    } else {
        xi[0] = xi[1] = xi[2] = 0;
    }
    if (bridge_volume > 0) {
        /* docs/theory.md §2.4: r_p = 2 R* for unequal spheres; gap s >= 0 */
        mimas_bridge b = {bridge_volume, L->surface_tension, L->contact_angle};
        double s = g->delta < 0 ? -g->delta : 0;
        attraction += mimas_bridge_force(&b, 2 * g->R_eff, s);
    }
    double fnet = fn - attraction;
    for (int k = 0; k < 3; k++)
        f[k] = fnet * n[k] + ft[k];
    /* torques: the tangential force acts at -r_i n on i and +r_j n on j */
    double nxft[3];
    dem_cross(n, ft, nxft);
    for (int k = 0; k < 3; k++) {
        ti[k] = -g->r_i * nxft[k];
        tj[k] = -g->r_j * nxft[k];
    }
    double wm = L->mu_r > 0 ? sqrt(dem_dot(g->w_rel, g->w_rel)) : 0;
    if (wm > 0 && g->delta > 0) {
        /* rolling friction (docs/theory.md §2.3; Bierwisch 2009, eq. 2.11) */
        for (int k = 0; k < 3; k++) {
            double tr = L->mu_r * (fn > 0 ? fn : 0) * g->w_rel[k] / wm;
            ti[k] -= tr;
            tj[k] += tr;
        }
    }
    return fn;
}

#endif
