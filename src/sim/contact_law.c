/* Contact laws (PHYSICS.md 2.1-2.5). */
#include <config.h>

#include "contact_law.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <string.h>

#include "cohesion.h"

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* -ln e of the clipped law as a function of x = eta0/omega, minus the target */
static double clipped_loss(double x, void *target)
{
    return x * (M_PI - 2 * atan(x)) - *(double *)target;
}

double dem_linear_damping_factor(double e, int clip)
{
    double l = -log(e);
    if (!clip)
        return 2 * l / sqrt(M_PI * M_PI + l * l);
    if (l >= 2)
        return -1;
    if (l == 0)
        return 0;
    /* x (pi - 2 atan x) rises monotonically from 0 to 2: bracket and solve */
    gsl_function F = {clipped_loss, &l};
    double lo = 0, hi = 1;
    while (clipped_loss(hi, &l) < 0)
        hi *= 2;
    gsl_root_fsolver *sv = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!sv)
        return -1;
    gsl_root_fsolver_set(sv, &F, lo, hi);
    double x = hi;
    for (int it = 0; it < 200; it++) {
        gsl_root_fsolver_iterate(sv);
        x = gsl_root_fsolver_root(sv);
        lo = gsl_root_fsolver_x_lower(sv);
        hi = gsl_root_fsolver_x_upper(sv);
        if (gsl_root_test_interval(lo, hi, 0, 1e-15) == GSL_SUCCESS)
            break;
    }
    gsl_root_fsolver_free(sv);
    return 2 * x / sqrt(1 + x * x);
}

void dem_linear_collision(double k_n, double gamma_n, double m_eff, int clip, double *t_c,
                          double *e)
{
    /* PHYSICS 2.1: omega0^2 = k_n/m*, eta0 = gamma_n/(2 m*) */
    double eta0 = gamma_n / (2 * m_eff), w = sqrt(k_n / m_eff - eta0 * eta0);
    *t_c = clip ? (M_PI - 2 * atan(eta0 / w)) / w : M_PI / w;
    *e = exp(-eta0 * *t_c);
}

void dem_law_make(dem_law *law, const sim_contact_params *p, double alpha)
{
    memset(law, 0, sizeof *law);
    law->model = p->model;
    /* coarse graining (PHYSICS 2.5): linear stiffness x alpha, damping x alpha^2,
     * so that forces scale with alpha^2; moduli, e and mu are unchanged */
    law->k_n = p->k_n * alpha;
    law->k_t = p->k_t * alpha;
    law->gamma_n = p->gamma_n * alpha * alpha;
    law->gamma_t = p->gamma_t * alpha * alpha;
    law->clip = p->normal_clip;
    if (p->restitution > 0 && p->model == SIM_LINEAR)
        law->damping_factor = dem_linear_damping_factor(p->restitution, p->normal_clip);
    if (p->model == SIM_HERTZ) {
        double l = log(p->restitution), E = p->youngs_modulus, nu = p->poisson;
        law->beta = p->restitution < 1 ? l / sqrt(l * l + M_PI * M_PI) : 0;
        /* PHYSICS 2.2, both sides of the same material */
        law->E_star = E / (2 * (1 - nu * nu));
        law->G_star = E / (4 * (2 - nu) * (1 + nu));
    }
    law->mu = p->friction;
    law->mu_r = p->rolling_friction * alpha;        /* a length */
    /* the attractions scale so that they too grow like alpha^2 (PHYSICS 2.5) */
    law->w = p->cohesion_energy * alpha;
    law->E_tilde = p->youngs_modulus / (1 - p->poisson * p->poisson);
    law->surface_tension = p->surface_tension * alpha;
    law->contact_angle = p->contact_angle * M_PI / 180;
}

double dem_contact_force(const dem_law *L, const dem_contact_geom *g, double dt,
                         double xi[3], double bridge_volume, double f[3], double ti[3],
                         double tj[3])
{
    const double *n = g->n;
    double vn = dot(g->vc, n);
    double fn = 0, attraction = 0;
    double ft[3] = {0, 0, 0};
    if (g->delta > 0) {
        double k_n, k_t, gamma_n, gamma_t;
        if (L->model == SIM_HERTZ) {
            /* LIGGGHTS' hertz form (PHYSICS 2.2) */
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
        /* never attractive (PHYSICS 2.1, 004 eq. 3.15) unless the clip is off */
        fn = k_n * g->delta - gamma_n * vn;
        if (fn < 0 && L->clip)
            fn = 0;
        if (L->w > 0)
            attraction += mimas_jkr_force(L->w, L->E_tilde, g->R_eff, g->delta);
        /* tangential history spring (PHYSICS 2.3): turn xi into the current
         * tangent plane keeping its length, add v_t dt */
        double vt[3], len0sq = dot(xi, xi), xn = dot(xi, n);
        for (int k = 0; k < 3; k++) {
            vt[k] = g->vc[k] - vn * n[k];
            xi[k] -= xn * n[k];
        }
        double len1sq = dot(xi, xi);
        if (len1sq > 0 && xn != 0) {
            double scale = sqrt(len0sq / len1sq);
            for (int k = 0; k < 3; k++)
                xi[k] *= scale;
        }
        for (int k = 0; k < 3; k++) {
            xi[k] += vt[k] * dt;
            ft[k] = -k_t * xi[k] - gamma_t * vt[k];
        }
        double ftm = sqrt(dot(ft, ft)), lim = L->mu * (fn > 0 ? fn : 0);
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
        /* PHYSICS 2.4: r_p = 2 R* for unequal spheres; gap s >= 0 */
        mimas_bridge b = {bridge_volume, L->surface_tension, L->contact_angle};
        double s = g->delta < 0 ? -g->delta : 0;
        attraction += mimas_bridge_force(&b, 2 * g->R_eff, s);
    }
    double fnet = fn - attraction;
    for (int k = 0; k < 3; k++)
        f[k] = fnet * n[k] + ft[k];
    /* torques: the tangential force acts at -r_i n on i and +r_j n on j */
    double nxft[3];
    cross(n, ft, nxft);
    for (int k = 0; k < 3; k++) {
        ti[k] = -g->r_i * nxft[k];
        tj[k] = -g->r_j * nxft[k];
    }
    double wm = L->mu_r > 0 ? sqrt(dot(g->w_rel, g->w_rel)) : 0;
    if (wm > 0 && g->delta > 0) {
        /* rolling friction (PHYSICS 2.3, 002 eq. 2.11) */
        for (int k = 0; k < 3; k++) {
            double tr = L->mu_r * (fn > 0 ? fn : 0) * g->w_rel[k] / wm;
            ti[k] -= tr;
            tj[k] += tr;
        }
    }
    return fn;
}
