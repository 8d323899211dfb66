/* The fields of mimas average: primary sums per cell (what is deposited and
 * time-averaged) and the fields derived from them, described once in a table
 * (name, unit, meaning) that feeds the TSV header and docs/fields.md
 * (libvips-style: one description drives every output).  docs/theory.md §1
 * and §6 give the definitions; stress is compression-positive. */
#ifndef MIMAS_FIELDS_H
#define MIMAS_FIELDS_H

#include <stddef.h>

#include "field_table.h"

/* primary sums per cell, each already divided by volume (a density); a
 * particle adds the block S_N..S_K (and the gradients S_G..) in one sweep, a
 * contact the block S_C..S_W.  The sums every average uses come first, those
 * of some weights only after them (S_G: kernels with gradients, S_U: Shepard,
 * S_VC..: Voronoi), so that a frame's sums need only the leading ones
 * (sums_used() in average.c). */
enum {
    S_N,            /* sum phi: number density */
    S_M,            /* sum m phi */
    S_V,            /* sum V_p phi: solid fraction */
    S_D,            /* sum 2 R phi: diameters */
    S_Z,            /* sum c_p phi, c_p = contacts of particle p */
    S_ZN,           /* the same over particles with c_p >= 2 */
    S_NN,           /* sum phi over particles with c_p >= 2 */
    S_P,            /* 3: sum m v phi */
    S_K = S_P + 3,  /* 6: sum m v (x) v phi (symmetric: xx yy zz xy xz yz), so that a
                     * particle adds 16 sums, two cache lines */
    S_PARTICLE_END = S_K + 6,
    S_C = S_PARTICLE_END, /* 9: sum f (x) b psi, contact stress */
    S_F = S_C + 9,  /* 6: sum n (x) n psi, fabric (symmetric: xx yy zz xy xz yz), and a 0,
                     * so that a contact adds 16 sums, four vectors of 4 */
    S_W = S_F + 7,  /* 3: sum f_wall delta(r - c): wall force density */
    S_G = S_W + 3,  /* 12: per direction b, sum m d_b phi and sum m v_a d_b phi
                     * (kernels only): S_GM(b), S_GP(a, b) */
    S_U = S_G + 12, /* 3: sum v phi, for Shepard's ratio of sums */
    S_VC = S_U + 3, /* sum V_cell phi: Voronoi cell volumes (--weight voronoi) */
    S_VSC,          /* the same over particles with a stress */
    S_VS,           /* 9: sum V_cell sigma phi: per-particle Voronoi stresses */
    NSUMS = S_VS + 9
};
/* The place of component (a, b) in a symmetric block (S_K, S_F): xx yy zz xy xz yz */
static inline int mimas_sym_index(int a, int b)
{
    static const int at[3][3] = {{0, 3, 4}, {3, 1, 5}, {4, 5, 2}};
    return at[a][b];
}
#define S_GM(b) (S_G + 4 * (b))             /* sum m d_b phi */
#define S_GP(a, b) (S_G + 4 * (b) + 1 + (a)) /* sum m v_a d_b phi */

/* How the derived fields come from the sums: densities per unit volume,
 * Shepard's ratio of sums (per-particle means only), or per-particle Voronoi
 * values (densities per unit of the particles' cell volume). */
typedef enum mimas_fields_mode {
    MIMAS_FIELDS_DENSITY,
    MIMAS_FIELDS_SHEPARD,
    MIMAS_FIELDS_VORONOI
} mimas_fields_mode;

/* Computes every derived column from the sums of one cell; r is the cell
 * centre's radius (cylindrical grids).  Undefined values (velocity of an
 * empty cell, mu where p <= 0, ...) are NaN, as docs/fields.md says.  The
 * strain-rate columns are left NaN: they need the neighbouring cells
 * (mimas_fields_strain).  Shepard's ratio of sums (Bierwisch 2009, eq. 2.27) defines
 * only means of per-particle values (velocity as sum v phi / sum phi, Z, d,
 * the strain rates); the densities and stresses are NaN.  Voronoi: n, rho
 * and nu per total cell volume (nu = sum V_p / sum V_cell), the stress the
 * cell-volume weighted mean of the per-particle stresses; the kinetic and
 * contact parts, fabric, wall force and T are NaN. */
void mimas_fields_derive(const double *S, int cylindrical, double r, mimas_fields_mode mode,
                         double *out);
/* Fills shear_rate, shear_rate_luding, eta and I of one cell from the
 * velocity gradient L[a][b] = d V_a / d x_b in the cell's (x y z) or
 * physical cylindrical (r phi z) components, where for cylindrical grids
 * L[.][1] is (1/r) d/dphi and the curvature terms are added here.  I uses
 * diameter if it is > 0, else the cell's mean diameter d. */
void mimas_fields_strain(const double L[3][3], const double *S, int cylindrical, double r,
                         double diameter, double *out);

#endif
