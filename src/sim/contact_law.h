/* Contact laws of the DEM core (docs/theory.md §2): normal force (linear
 * spring-dashpot or Hertz-Mindlin), tangential history spring with Coulomb
 * truncation, rolling friction, JKR-type cohesion and pendular liquid
 * bridges.  The same function serves particle-particle and particle-wall
 * contacts (a wall is a partner of infinite mass and radius). */
#ifndef MIMAS_SIM_CONTACT_LAW_H
#define MIMAS_SIM_CONTACT_LAW_H

#include "scenario.h"

/* The law of one type pair, with the coarse-grain scaling applied (docs/theory.md §2.5). */
typedef struct dem_law {
    int model;                 /* SIM_LINEAR, SIM_HERTZ */
    double k_n, k_t, gamma_n, gamma_t;   /* linear */
    double damping_factor;     /* > 0: gamma_n = damping_factor * sqrt(k_n m*) (linear, from e) */
    int clip;                  /* normal force never attractive */
    double beta;               /* Hertz: ln e / sqrt(ln^2 e + pi^2) */
    double E_star, G_star;     /* Hertz: effective moduli of the pair */
    double mu, mu_r;
    double w, E_tilde;         /* JKR (w = 0: none) */
    double surface_tension, contact_angle;   /* bridges (angle in rad) */
} dem_law;

/* Builds the law of a pair from the scenario's parameters; alpha is the
 * coarse-grain factor.  Both sides are taken to be of the same material. */
void dem_law_make(dem_law *law, const sim_contact_params *p, double alpha);

/* gamma_n = factor * sqrt(k_n m*) gives restitution e for the linear law
 * (docs/theory.md §2.1).  Without clip: factor = 2 (-ln e)/sqrt(pi^2 + ln^2 e).  With
 * the clip the particles part when the force returns to zero, at
 * t_r = (pi - 2 atan(x))/omega with x = eta0/omega, and e = exp(-x (pi - 2 atan x))
 * (the velocity factor there is exactly 1); solved for x, factor = 2x/sqrt(1+x^2).
 * Returns -1 if no damping gives e (with the clip e >= exp(-2)). */
double dem_linear_damping_factor(double e, int clip);
/* Contact duration and restitution of the linear law for k_n, gamma_n, m*;
 * with clip, the duration of the repulsion t_r and its restitution. */
void dem_linear_collision(double k_n, double gamma_n, double m_eff, int clip, double *t_c,
                          double *e);

/* The geometry and kinematics of one contact. */
typedef struct dem_contact_geom {
    double n[3];       /* unit normal from j to i */
    double delta;      /* overlap R_i + R_j - |r_i - r_j| (< 0: gap) */
    double r_i, r_j;   /* radii (the lever arms of the torques); r_j = 0 for a wall */
    double R_eff, m_eff;
    double vc[3];      /* velocity of i's surface point minus that of j (docs/theory.md §1) */
    double w_rel[3];   /* w_i - w_j (rolling friction) */
} dem_contact_geom;

#endif
