/* Cohesion laws (docs/theory.md §2.4): JKR-type contact cohesion and pendular
 * liquid bridges, with Willett's fit as the reference.  The edge cases are
 * described in cohesion.h and docs/contact-laws.md. */
#include <config.h>

#include "cohesion.h"

#include <gsl/gsl_poly.h>
#include <math.h>

double mimas_jkr_force(double w, double E_tilde, double R_eff, double delta)
{
    return delta > 0 ? sqrt(4 * M_PI * w * E_tilde) * pow(R_eff * delta, 0.75) : 0;
}

double mimas_jkr_delta_min(double w, double E_tilde, double R_eff)
{
    return pow(2.25 * M_PI * w / E_tilde * sqrt(R_eff), 2.0 / 3.0);
}

double mimas_bridge_half_angle(const mimas_bridge *b, double r_p, double s)
{
    if (!(b->volume > 0))
        return 0;
    if (s < 0)
        s = 0;
    /* Uhlig (2012), eq. 2.7 with s* = s/d_p = s/(2 r_p) */
    double x = b->volume /
               (0.96 * r_p * r_p * r_p * (1 + 3 * s / r_p) * (1 + 1.1 * sin(b->theta)));
    return x >= 1 ? M_PI / 2 : asin(pow(x, 0.25));
}

double mimas_bridge_rupture_distance(const mimas_bridge *b)
{
    return (1 + b->theta / 2) * cbrt(b->volume);
}

double mimas_bridge_force(const mimas_bridge *b, double r_p, double s)
{
    if (s < 0)
        s = 0;
    if (!(b->volume > 0) || s > mimas_bridge_rupture_distance(b))
        return 0;
    double beta = mimas_bridge_half_angle(b, r_p, s), phi = beta + b->theta;
    /* h: axial distance from the contact line to the mid-plane, h = R1 cos(phi).
     * 1/R1 and R2 are written so that phi = pi/2 (straight meridian) needs no
     * special case: R1 (1 - sin phi) = h (1 - sin phi)/cos phi
     *                                 = h tan(pi/4 - phi/2). */
    double h = r_p * (1 - cos(beta)) + s / 2;
    double inv_R1 = cos(phi) / h;
    double R2 = r_p * sin(beta) - h * tan(M_PI / 4 - phi / 2);
    double p_K = b->gamma * (inv_R1 - 1 / R2);
    double sb = sin(beta);
    double F = 2 * M_PI * b->gamma * r_p * sb * sin(phi) + M_PI * r_p * r_p * p_K * sb * sb;
    return F < 0 ? 0 : F;
}

/* Willett et al. 2000, appendix (Uhlig 2012, appendix eq. 8.1-8.4):
 * A_k = sum_j (c_kj0 + c_kj1 theta + c_kj2 theta^2) L^j, theta in rad,
 * L = ln(V_B/r_p^3). */
static const double willett[4][4][3] = {
    {{-0.44507, 0.050832, -1.1466},
     {-0.1119, -0.000411, -0.1490},
     {-0.012101, -0.0036456, -0.01255},
     {-0.0005, -0.0003505, -0.00029076}},
    {{1.9222, -0.57473, -1.2918},
     {-0.0668, -0.1201, -0.22574},
     {-0.0013375, -0.0068988, -0.01137},
     {0, 0, 0}},
    {{1.268, -0.01396, -0.23566},
     {0.198, 0.092, -0.06418},
     {0.02232, 0.02238, -0.009853},
     {0.0008585, 0.001318, -0.00053}},
    {{-0.010703, 0.073776, -0.34742},
     {0.03345, 0.04543, -0.09056},
     {0.0018574, 0.004456, -0.006257},
     {0, 0, 0}},
};

void mimas_willett_coefficients(double theta, double L, double A[4])
{
    for (int k = 0; k < 4; k++) {
        double c[4];
        for (int j = 0; j < 4; j++)
            c[j] = gsl_poly_eval(willett[k][j], 3, theta);
        A[k] = gsl_poly_eval(c, 4, L);
    }
}

double mimas_willett_force(const mimas_bridge *b, double r_p, double s)
{
    if (!(b->volume > 0))
        return 0;
    double A[4];
    mimas_willett_coefficients(b->theta, log(b->volume / (r_p * r_p * r_p)), A);
    /* Willett's dimensionless half-separation S+ = (s/2) sqrt(r_p/V_B) */
    double S = s > 0 ? 0.5 * s * sqrt(r_p / b->volume) : 0, lnF = A[0];
    if (S > 0) {
        double l = log(S);
        lnF -= A[1] * exp(A[2] * l + A[3] * l * l);
    }
    return 2 * M_PI * b->gamma * r_p * exp(lnF);
}
