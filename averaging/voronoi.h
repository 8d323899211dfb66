/* Per-particle Voronoi quantities of a frame (docs/theory.md §6; Bierwisch 2009, Sec. 2.2 and
 * eq. 3.8): cell volume, local solid fraction, faces, surface flags and the
 * per-particle stress, stored in the frame as extra particle columns so that
 * the native writer keeps them and mimas average --weight voronoi reads them. */
#ifndef MIMAS_VORONOI_H
#define MIMAS_VORONOI_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "frame.h"
#include "voro_cells.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The extra particle columns (docs/format.md). */
#define MIMAS_VORONOI_VOLUME "voronoi_volume"   /* m3: cell volume V_cell */
#define MIMAS_VORONOI_NU "voronoi_nu"           /* 1: V_p / V_cell */
#define MIMAS_VORONOI_FACES "voronoi_faces"     /* 1: number of faces */
#define MIMAS_VORONOI_SURFACE "voronoi_surface" /* 1: flags, voro_cells.h (1 wall, 2 cut) */
#define MIMAS_VORONOI_STRESS "voronoi_stress"   /* Pa, 9: [3a+b] = sigma_ab */

typedef struct mimas_voronoi_options {
    int radical;                    /* radical (Laguerre) tessellation */
    const mimas_voro_wall *walls;   /* container walls */
    size_t nwalls;
    double max_extent;              /* > 0: cut cells to within this distance */
    double velocity_width;          /* Shepard Gaussian width for the mean velocity V
                                     * of the kinetic stress; 0: V = 0 */
    const int32_t *exclude;         /* types that take part but are not reported */
    size_t nexclude;
    int threads;                    /* OpenMP threads (0: OpenMP's default) */
} mimas_voronoi_options;

typedef struct mimas_voronoi mimas_voronoi;

int mimas_voronoi_create(mimas_voronoi **v, const mimas_voronoi_options *o, mimas_error *err);
/* Tessellates the frame (every particle takes part) and stores, for every
 * particle not of an excluded type, voronoi_volume, voronoi_nu,
 * voronoi_faces, voronoi_surface and, when the frame has contact data,
 * voronoi_stress:
 *   sigma_k = (1/V_cell) [ m (v - V) (x) (v - V) + sum_j f_kj (x) (r_k - c_kj)
 *                          + sum_w f_kw (x) (r_k - c_kw) ]
 * (compression positive; each particle of a contact takes its force with its
 * own branch to the contact point, so the two shares add up to
 * f_ij (x) (r_i - r_j); V the Shepard mean of the reported particles'
 * velocities at r_k).  Excluded particles get NaN; an empty cell has volume
 * 0 and NaN for nu and stress. */
int mimas_voronoi_frame(mimas_voronoi *v, mimas_frame *f, mimas_error *err);
/* Whether particle k is reported (not of an excluded type). */
int mimas_voronoi_reported(const mimas_voronoi *v, const mimas_particles *p, size_t k);
void mimas_voronoi_free(mimas_voronoi *v);

/* The Voronoi columns of a frame's particles (NULL where absent). */
typedef struct mimas_voronoi_values {
    const double *volume, *nu, *faces, *surface, *stress;
} mimas_voronoi_values;
void mimas_voronoi_values_of(const mimas_particles *p, mimas_voronoi_values *v);

#ifdef __cplusplus
}
#endif
#endif
