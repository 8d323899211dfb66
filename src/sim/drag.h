/* Drag on a sphere moving through a fluid at rest (docs/theory.md §5; Uhlig
 * 2012, Sec. 2.2.3): the drag coefficients of Stokes, Schiller and Naumann
 * (1935) and Haider and Levenspiel (1989), buoyancy, and the wall factors of
 * Francis (1933) and Ataíde et al. (1999) for a sphere in a tube. */
#ifndef MIMAS_SIM_DRAG_H
#define MIMAS_SIM_DRAG_H

#include "dem.h"

enum { DRAG_STOKES = 0, DRAG_SCHILLER_NAUMANN = 1, DRAG_HAIDER_LEVENSPIEL = 2 };
enum { WALL_FACTOR_NONE = 0, WALL_FACTOR_FRANCIS = 1, WALL_FACTOR_ATAIDE = 2 };

typedef struct sim_drag {
    int law;                 /* DRAG_* */
    int wall_factor;         /* WALL_FACTOR_* */
    double rho_f, eta;       /* fluid density (kg/m^3) and viscosity (Pa s) */
    double tube_diameter;    /* D of the wall factors, m */
    int buoyancy;            /* add -rho_f V g */
} sim_drag;

/* C_D Re of the law at particle Reynolds number Re = rho_f d |u|/eta (finite
 * at Re = 0): 24 (Stokes), 24 (1 + 0.15 Re^0.687) (Schiller-Naumann),
 * 24 (1 + 0.1806 Re^0.6459) + 0.4251 Re/(1 + 6880.95/Re) (Haider-Levenspiel). */
double sim_drag_cd_re(int law, double re);
/* The wall factor f_W = u_bounded/u_free of a sphere of diameter d in a tube
 * of diameter D at (bounded) Reynolds number Re: Francis (1 - d/D)^2.25;
 * Ataíde 1.092/(1 + A1 Re^A2), A1 = 0.1 exp(8.54 d/D), A2 = -0.042 - 0.939 d/D,
 * with Re held to its range of validity 0.38..310.7; 1 without. */
double sim_drag_wall_factor(int kind, double d, double D, double re);
/* Magnitude of the drag on a sphere of diameter d moving at speed u:
 * pi d^2 rho_f u^2 C_D/8, taken at u/f_W in a tube so that the terminal
 * velocity is f_W times the free one. */
double sim_drag_force(const sim_drag *dr, double d, double u);
/* Adds drag (against the velocity) and buoyancy to the free particles. */
void sim_drag_apply(const sim_drag *dr, dem_system *s);

#endif
