/* Cohesion laws (PHYSICS 2.4): JKR-type and pendular liquid bridges. */
#ifndef MIMAS_SIM_COHESION_H
#define MIMAS_SIM_COHESION_H
double mimas_jkr_force(double w, double E_tilde, double R_eff, double delta);
double mimas_jkr_delta_min(double w, double E_tilde, double R_eff);
typedef struct { double volume, gamma, theta; } mimas_bridge;
double mimas_bridge_half_angle(const mimas_bridge *b, double r_p, double s);
double mimas_bridge_rupture_distance(const mimas_bridge *b);
double mimas_bridge_force(const mimas_bridge *b, double r_p, double s);
#endif
