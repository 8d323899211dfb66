/* Contact laws (docs/theory.md §2.1-§2.5). */
#include <config.h>

#include "contact_law.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <string.h>

#include "cohesion.h"

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
    /* docs/theory.md §2.1: omega0^2 = k_n/m*, eta0 = gamma_n/(2 m*) */
    double eta0 = gamma_n / (2 * m_eff), w = sqrt(k_n / m_eff - eta0 * eta0);
    *t_c = clip ? (M_PI - 2 * atan(eta0 / w)) / w : M_PI / w;
    *e = exp(-eta0 * *t_c);
}

void dem_law_make(dem_law *law, const sim_contact_params *p, double alpha)
{
    memset(law, 0, sizeof *law);
    law->model = p->model;
    /* coarse graining (docs/theory.md §2.5): linear stiffness x alpha, damping x alpha^2,
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
        /* docs/theory.md §2.2, both sides of the same material */
        law->E_star = E / (2 * (1 - nu * nu));
        law->G_star = E / (4 * (2 - nu) * (1 + nu));
    }
    law->mu = p->friction;
    law->mu_r = p->rolling_friction * alpha;        /* a length */
    /* the attractions scale so that they too grow like alpha^2 (docs/theory.md §2.5) */
    law->w = p->cohesion_energy * alpha;
    law->E_tilde = p->youngs_modulus / (1 - p->poisson * p->poisson);
    law->surface_tension = p->surface_tension * alpha;
    law->contact_angle = p->contact_angle * M_PI / 180;
}
