#include <config.h>

#include "fields.h"

#include <math.h>
#include <string.h>

/* column indices of the derived fields */
enum {
    F_N, F_RHO, F_NU, F_V, F_OMEGA = F_V + 3, F_STRESS, F_KSTRESS = F_STRESS + 6,
    F_CSTRESS = F_KSTRESS + 6, F_P = F_CSTRESS + 6, F_TAU, F_TAU_PHI, F_MU, F_T, F_Z, F_ZNR,
    F_FABRIC, F_D = F_FABRIC + 6, F_WALL, F_SHEAR = F_WALL + 3, F_SHEAR_L, F_ETA, F_I,
    NFIELDS
};

#define TENSOR(base, unit, meaning)                                                          \
    {base "_xx", base "_rr", unit, meaning}, {base "_yy", base "_phiphi", unit, meaning},    \
        {base "_zz", base "_zz", unit, meaning}, {base "_xy", base "_rphi", unit, meaning},  \
        {base "_xz", base "_rz", unit, meaning}, {base "_yz", base "_phiz", unit, meaning}

static const mimas_field_desc fields[NFIELDS] = {
    {"n", NULL, "m-3", "number density sum_i phi"},
    {"rho", NULL, "kg m-3", "mass density sum_i m_i phi"},
    {"nu", NULL, "1", "solid fraction sum_i V_i phi"},
    {"v_x", "v_r", "m s-1", "velocity j/rho, j = sum_i m_i v_i phi (undefined where rho = 0)"},
    {"v_y", "v_phi", "m s-1", "velocity j/rho (undefined where rho = 0)"},
    {"v_z", "v_z", "m s-1", "velocity j/rho (undefined where rho = 0)"},
    {"", "omega", "s-1", "angular velocity v_phi/r at the cell centre"},
    TENSOR("stress", "Pa", "total stress kstress + cstress (symmetric part), compression positive"),
    TENSOR("kstress", "Pa", "kinetic stress sum_i m_i (v_i - V)(x)(v_i - V) phi"),
    TENSOR("cstress", "Pa", "contact stress sum_c f_ij (x) (r_i - r_j) psi_ij (symmetric part)"),
    {"p", NULL, "Pa", "pressure tr(stress)/3"},
    {"tau", NULL, "Pa", "shear stress sqrt(s:s/2), s the deviator of stress"},
    {"", "tau_phi", "Pa",
     "shear stress sqrt(stress_rphi^2 + stress_phiz^2) (Uhlig 2012, eq. 2.15)"},
    {"mu", NULL, "1", "stress ratio tau/p (undefined where p <= 0)"},
    {"T", NULL, "J", "granular temperature tr(kstress)/(3 n) (undefined where n = 0)"},
    {"Z", NULL, "1", "coordination number sum_i c_i phi / sum_i phi"},
    {"Z_nr", NULL, "1", "coordination number without rattlers (particles with < 2 contacts)"},
    TENSOR("fabric", "m-3", "fabric sum_c n (x) n psi"),
    {"d", NULL, "m", "mean particle diameter sum_i 2 R_i phi / sum_i phi"},
    {"wall_force_x", "wall_force_r", "N m-3", "wall force density sum_w f_w delta(r - c_w)"},
    {"wall_force_y", "wall_force_phi", "N m-3", "wall force density"},
    {"wall_force_z", "wall_force_z", "N m-3", "wall force density"},
    {"shear_rate", NULL, "s-1", "sqrt(2 D':D'), D' the deviator of D = (grad V + grad V^T)/2"},
    {"", "shear_rate_luding", "s-1",
     "0.5 sqrt((dv_phi/dr - v_phi/r)^2 + (dv_phi/dz)^2) (Uhlig 2012, eq. 2.13)"},
    {"eta", NULL, "Pa s", "viscosity tau/shear_rate (undefined where shear_rate = 0)"},
    {"I", NULL, "1", "inertial number shear_rate d sqrt(rho_p/p), rho_p = rho/nu, d the "
                     "cell's d or --diameter (undefined where p <= 0)"},
};

size_t mimas_fields_count(void)
{
    return NFIELDS;
}

const mimas_field_desc *mimas_field(size_t k)
{
    return &fields[k];
}

const char *mimas_field_name(size_t k, int cylindrical)
{
    const char *name = cylindrical && fields[k].cname ? fields[k].cname : fields[k].name;
    return name[0] ? name : NULL;
}

int mimas_field_find(const char *name, int cylindrical, size_t *k)
{
    for (size_t c = 0; c < NFIELDS; c++) {
        const char *n = mimas_field_name(c, cylindrical);
        if (n && !strcmp(n, name)) {
            *k = c;
            return 1;
        }
    }
    return 0;
}

/* symmetric part of a 3x3 tensor into xx yy zz xy xz yz */
static void sym6(const double *T, double *out)
{
    out[0] = T[0];
    out[1] = T[4];
    out[2] = T[8];
    out[3] = 0.5 * (T[1] + T[3]);
    out[4] = 0.5 * (T[2] + T[6]);
    out[5] = 0.5 * (T[5] + T[7]);
}

static double ratio(double a, double b)
{
    return b != 0.0 ? a / b : NAN;
}

/* Pressure, shear stresses and stress ratio from the stress columns. */
static void stress_measures(int cylindrical, double *out)
{
    const double *s = &out[F_STRESS];
    double p = (s[0] + s[1] + s[2]) / 3.0;
    out[F_P] = p;
    double d0 = s[0] - p, d1 = s[1] - p, d2 = s[2] - p;
    double ss = d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    out[F_TAU] = sqrt(0.5 * ss);
    out[F_TAU_PHI] = cylindrical ? sqrt(s[3] * s[3] + s[5] * s[5]) : NAN;
    out[F_MU] = p > 0 ? out[F_TAU] / p : NAN;
}

/* The Voronoi fields (docs/theory.md §6; Bierwisch 2009, Sec. 2.2): densities over the cells'
 * volume, the stress the cell-volume weighted mean of the per-particle
 * stresses; no kinetic/contact split, fabric, wall force or temperature. */
static void voronoi_fields(const double *S, double *out)
{
    double vol = S[S_VC];
    out[F_N] = ratio(S[S_N], vol);
    out[F_RHO] = ratio(S[S_M], vol);
    out[F_NU] = ratio(S[S_V], vol);
    double T[9];
    for (int k = 0; k < 9; k++)
        T[k] = ratio(S[S_VS + k], S[S_VSC]);
    sym6(T, &out[F_STRESS]);
    for (int k = 0; k < 6; k++)
        out[F_KSTRESS + k] = out[F_CSTRESS + k] = out[F_FABRIC + k] = NAN;
    for (int k = 0; k < 3; k++)
        out[F_WALL + k] = NAN;
    out[F_T] = NAN;
}

void mimas_fields_derive(const double *S, int cylindrical, double r, mimas_fields_mode mode,
                         double *out)
{
    double rho = S[S_M];
    out[F_N] = S[S_N];
    out[F_RHO] = rho;
    out[F_NU] = S[S_V];
    double V[3];
    for (int k = 0; k < 3; k++)
        out[F_V + k] = V[k] = ratio(S[S_P + k], rho);
    out[F_OMEGA] = cylindrical ? ratio(V[1], r) : NAN;
    /* kinetic stress: momentum flux minus rho V (x) V (fluctuations about the
     * local mean, docs/theory.md §6); zero where there is no mass */
    double K[9];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            K[3 * a + b] = rho > 0 ? S[S_K + mimas_sym_index(a, b)] - rho * V[a] * V[b] : 0.0;
    double T[9];
    for (int k = 0; k < 9; k++)
        T[k] = K[k] + S[S_C + k];
    sym6(T, &out[F_STRESS]);
    sym6(K, &out[F_KSTRESS]);
    sym6(&S[S_C], &out[F_CSTRESS]);
    out[F_T] = ratio(K[0] + K[4] + K[8], 3.0 * S[S_N]);
    out[F_Z] = ratio(S[S_Z], S[S_N]);
    out[F_ZNR] = ratio(S[S_ZN], S[S_NN]);
    for (int k = 0; k < 6; k++)
        out[F_FABRIC + k] = S[S_F + k];
    out[F_D] = ratio(S[S_D], S[S_N]);
    for (int k = 0; k < 3; k++)
        out[F_WALL + k] = S[S_W + k];
    out[F_SHEAR] = out[F_SHEAR_L] = out[F_ETA] = out[F_I] = NAN;
    if (mode == MIMAS_FIELDS_VORONOI)
        voronoi_fields(S, out);
    stress_measures(cylindrical, out);
    if (mode == MIMAS_FIELDS_SHEPARD) {
        for (int k = 0; k < 3; k++)
            out[F_V + k] = ratio(S[S_U + k], S[S_N]);
        out[F_OMEGA] = cylindrical ? ratio(out[F_V + 1], r) : NAN;
        for (int k = 0; k < NFIELDS; k++) {
            int keep = (k >= F_V && k <= F_OMEGA) || k == F_Z || k == F_ZNR || k == F_D ||
                       k == F_SHEAR || k == F_SHEAR_L;
            if (!keep)
                out[k] = NAN;
        }
    }
}

size_t mimas_fields_velocity(void)
{
    return F_V;
}

void mimas_fields_strain(const double L[3][3], const double *S, int cylindrical, double r,
                         double diameter, double *out)
{
    double D[3][3];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            D[a][b] = 0.5 * (L[a][b] + L[b][a]);
    if (cylindrical) {
        /* physical components in (r, phi, z): the basis turns with phi,
         * D_phiphi += v_r/r and D_rphi -= v_phi/(2r) */
        double vr = out[F_V], vphi = out[F_V + 1];
        D[1][1] += vr / r;
        D[0][1] -= 0.5 * vphi / r;
        D[1][0] = D[0][1];
        out[F_SHEAR_L] = 0.5 * sqrt(pow(L[1][0] - vphi / r, 2) + pow(L[1][2], 2));
    }
    double tr = (D[0][0] + D[1][1] + D[2][2]) / 3.0, dd = 0;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double x = D[a][b] - (a == b ? tr : 0.0);
            dd += x * x;
        }
    double g = sqrt(2.0 * dd);
    out[F_SHEAR] = g;
    out[F_ETA] = g > 0 ? out[F_TAU] / g : NAN;
    double rho_p = S[S_V] > 0 ? S[S_M] / S[S_V] : NAN; /* NaN for Shepard: no I */
    double d = diameter > 0 ? diameter : out[F_D];
    out[F_I] = out[F_P] > 0 ? g * d * sqrt(rho_p / out[F_P]) : NAN;
}
