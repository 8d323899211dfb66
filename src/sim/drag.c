/* Drag laws of a sphere in a fluid at rest (drag.h). */
#include <config.h>

#include "drag.h"

#include <math.h>

double sim_drag_cd_re(int law, double re)
{
    switch (law) {
    case DRAG_SCHILLER_NAUMANN:
        return 24 * (1 + 0.15 * pow(re, 0.687));
    case DRAG_HAIDER_LEVENSPIEL:
        return 24 * (1 + 0.1806 * pow(re, 0.6459)) + 0.4251 * re * re / (re + 6880.95);
    default:
        return 24;
    }
}

double sim_drag_wall_factor(int kind, double d, double D, double re)
{
    double x = d / D;
    if (kind == WALL_FACTOR_FRANCIS)
        return pow(1 - x, 2.25);
    if (kind == WALL_FACTOR_ATAIDE) {
        double r = fmin(310.7, fmax(0.38, re));
        return 1.092 / (1 + 0.1 * exp(8.54 * x) * pow(r, -0.042 - 0.939 * x));
    }
    return 1;
}

double sim_drag_force(const sim_drag *dr, double d, double u)
{
    if (!(u > 0))
        return 0;
    double fw = sim_drag_wall_factor(dr->wall_factor, d, dr->tube_diameter,
                                     dr->rho_f * d * u / dr->eta);
    double w = u / fw, re = dr->rho_f * d * w / dr->eta;
    /* pi d^2 rho_f w^2 C_D/8 = (pi/8) eta d w (C_D Re) */
    return M_PI / 8 * dr->eta * d * w * sim_drag_cd_re(dr->law, re);
}

void sim_drag_apply(const sim_drag *dr, dem_system *s)
{
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < s->n; k++) {
        if (s->glued[k] >= 0)
            continue;
        double r = s->radius[k], *v = s->v[k];
        double u = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        double F = sim_drag_force(dr, 2 * r, u), V = 4.0 / 3.0 * M_PI * r * r * r;
        for (int q = 0; q < 3; q++) {
            if (u > 0)
                s->f[k][q] -= F * v[q] / u;
            if (dr->buoyancy)
                s->f[k][q] -= dr->rho_f * V * s->gravity[q];
        }
    }
}
