/* src/sim/cohesion.h — cohesion laws (docs/theory.md §2.4; docs/contact-laws.md,
 * "Cohesion").  All SI units; forces are returned as magnitudes of the
 * ATTRACTIVE force (>= 0), acting along the line of centres. */
#ifndef MIMAS_SIM_COHESION_H
#define MIMAS_SIM_COHESION_H

/* JKR-type cohesion (Bierwisch 2009, eq. 2.4): sqrt(4 pi w E~) R*^(3/4) delta^(3/4) for
 * delta > 0, else 0.  w is Bierwisch's work of adhesion per unit contact area
 * (J/m^2; Bierwisch (2009): "the surface energy is w/2"), E_tilde = E/(1-nu^2),
 * R_eff = R*. */
double mimas_jkr_force(double w, double E_tilde, double R_eff, double delta);
/* The overlap at which Hertz repulsion (4/3) E* sqrt(R*) delta^(3/2) plus
 * the JKR attraction is least, for two identical spheres (E* = E~/2):
 * delta_min = ((9/4) pi (w/E~) sqrt(R*))^(2/3); the force there is
 * F_min = -(3/2) pi w R* (docs/theory.md §2.4 check values). */
double mimas_jkr_delta_min(double w, double E_tilde, double R_eff);

/* Liquid bridge, pendular regime (docs/theory.md §2.4; Uhlig 2012, Sec. 2.1/3.1).  r_p is
 * the sphere radius; for unequal spheres the caller passes r_p = 2 R* (the
 * harmonic mean radius, Derjaguin-type: for small bridges the force at
 * contact is then 2 pi gamma r_p cos(theta) = 4 pi gamma R* cos(theta), the
 * Derjaguin result for any pair of radii).  s is the surface gap; s < 0
 * (overlap) is treated as s = 0.  A bridge with volume <= 0 gives 0. */
typedef struct {
    double volume; /* V_B, m^3 */
    double gamma;  /* surface tension, N/m */
    double theta;  /* contact angle, rad */
} mimas_bridge;

/* Weigert's half-filling angle beta (Uhlig 2012, eq. 2.7, rad):
 * sin^4 beta = V_B / (0.96 r_p^3 (1 + 6 s/d_p) (1 + 1.1 sin theta)),
 * d_p = 2 r_p.  When the right-hand side is >= 1 (bridges of the order of
 * r_p^3 and more) beta is clamped to pi/2: the liquid covers the whole
 * facing hemisphere, the largest bridge a pendular ring can be; the force
 * stays finite and continuous in V_B and s. */
double mimas_bridge_half_angle(const mimas_bridge *b, double r_p, double s);
/* Lian's rupture distance (Uhlig 2012, eq. 2.1): s_c = (1 + theta/2) V_B^(1/3). */
double mimas_bridge_rupture_distance(const mimas_bridge *b);
/* Boundary method with a toroidal meniscus (Uhlig 2012, eq. 2.3, 2.4):
 * F = 2 pi gamma r_p sin(beta) sin(beta+theta) + pi r_p^2 p_K sin^2(beta),
 * p_K = gamma (1/R1 - 1/R2) the capillary suction (gas minus liquid
 * pressure; > 0 pulls the spheres together), R1 the meridian radius
 * (> 0 for a concave, waisted bridge), R2 the neck radius:
 * R1 = (r_p (1 - cos beta) + s/2) / cos(beta+theta),
 * R2 = r_p sin beta - R1 (1 - sin(beta+theta)).
 * 0 for s > s_c.  If the formula turns negative (only for contact angles
 * from about 61 deg with V_B ~ r_p^3, far outside the model's range)
 * 0 is returned. */
double mimas_bridge_force(const mimas_bridge *b, double r_p, double s);
/* Willett et al. 2000 (Langmuir 16, 9396; Uhlig 2012, eq. 2.8, appendix 8.1-8.4),
 * the reference for the model above: F = 2 pi gamma r_p F^ with
 * ln F^ = A1 - A2 exp(A3 ln S + A4 ln^2 S), S = (s/2) sqrt(r_p/V_B)
 * (Willett's half-separation; Uhlig's text prints s sqrt(r_p/V_B), see
 * docs/contact-laws.md).  Fitted for theta < 50 deg, V_B/r_p^3 < 0.1; no
 * rupture is applied (use mimas_bridge_rupture_distance); s <= 0 gives the
 * contact value F^ = exp(A1). */
double mimas_willett_force(const mimas_bridge *b, double r_p, double s);
/* Willett's coefficients A[0..3] = A1..A4 for contact angle theta (rad) and
 * L = ln(V_B/r_p^3). */
void mimas_willett_coefficients(double theta, double L, double A[4]);

#endif
