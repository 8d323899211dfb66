/* One tube geometry for every tube analysis (mimas plugs, mimas radial):
 * the axis, the inner radius, the cylindrical coordinates (s, r, phi) of
 * points and vectors, axial slices, and the exact volumes of a sphere inside
 * a slice (spherical caps) and inside a probe sphere (lens); docs/plugs.md
 * and docs/overlap.md give the formulas.  No state, no output. */
#ifndef MIMAS_TUBE_H
#define MIMAS_TUBE_H

#include <stddef.h>

#include "axis.h"
#include "error.h"
#include "frame.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_tube_geom {
    mimas_axis axis;   /* origin: s = 0 (the inlet when the input says); e_z: inlet -> outlet */
    double radius;     /* inner radius R, m */
    double length;     /* NaN when unknown */
} mimas_tube_geom;

/* The geometry a command uses: axis_spec (--axis, NULL: not given) and
 * radius (--tube-radius, 0: not given) override the input's tube (from_file,
 * may be NULL or not present).  Without an axis from either, the z axis
 * through the origin; without a radius from either, MIMAS_EUSAGE naming
 * --tube-radius.  A radius <= 0 or not finite is MIMAS_EUSAGE. */
int mimas_tube_geom_resolve(mimas_tube_geom *g, const char *axis_spec, double radius,
                            const mimas_tube *from_file, mimas_error *err);

/* Cylindrical coordinates of the point x: s along the axis, r from it,
 * phi counterclockwise from the axis frame's e_x (radians, -pi..pi). */
void mimas_tube_coords(const mimas_tube_geom *g, const double x[3], double *s, double *r,
                       double *phi);
/* The components (s, r, phi) of the vector v at the point x; on the axis
 * (r = 0) e_r is the axis frame's e_x. */
void mimas_tube_vector(const mimas_tube_geom *g, const double x[3], const double v[3],
                       double out[3]);

/* Volume of the ball |x - c| <= a between the planes s = s0 and s = s1,
 * where c is the ball's axial coordinate (a spherical segment; exact). */
double mimas_tube_slab_volume(double c, double a, double s0, double s1);
/* Its first moment: the integral of s over that part of the ball, so that
 * moment / volume is the part's axial centre (exact); volume is that part's
 * volume (mimas_tube_slab_volume, computed once by the caller). */
double mimas_tube_slab_moment(double c, double a, double s0, double s1, double volume);
/* s and r of the point x and the components (s, r, phi) of the vector v
 * there, in one pass (no angle computed). */
void mimas_tube_point(const mimas_tube_geom *g, const double x[3], const double v[3], double *s,
                      double *r, double out[3]);

/* Regular slices of width w along the axis from s0: slice k is
 * [s0 + k w, s0 + (k + 1) w]. */
typedef struct mimas_slices {
    double s0, w;
    size_t n;
} mimas_slices;
/* The slices of [s0, s1] of width about w: n = max(1, round((s1 - s0)/w))
 * slices of equal width; MIMAS_EUSAGE if s1 <= s0 or w <= 0. */
int mimas_slices_set(mimas_slices *sl, double s0, double s1, double w, mimas_error *err);
double mimas_slice_centre(const mimas_slices *sl, size_t k);
/* The slice indices [*k0, *k1] that the interval [lo, hi] touches; 0 if none. */
int mimas_slices_range(const mimas_slices *sl, double lo, double hi, size_t *k0, size_t *k1);

/* Whether particle i of the frame lies inside the tube: its centre within
 * R of the axis (an overlap with the wall of up to its radius is accepted,
 * as mimas simulate's blow-up check does).  Otherwise MIMAS_EDATA naming
 * the particle's id, r and R. */
int mimas_tube_check_particle(const mimas_tube_geom *g, const mimas_frame *f, size_t i,
                              mimas_error *err);

/* The selected particles' extent along the axis (min s - a, max s + a) and
 * their mean diameter; MIMAS_EDATA when none is selected, MIMAS_EMISSING
 * without radii. */
int mimas_tube_extent(const mimas_tube_geom *g, const mimas_frame *f, const int32_t *types,
                      size_t ntypes, int exclude, double *s_min, double *s_max, double *diameter,
                      mimas_error *err);

/* What a tube command takes from its first frame: the geometry
 * (mimas_tube_geom_resolve with the frame's tube) and the selected
 * particles' extent and mean diameter (mimas_tube_extent; all three NaN
 * when the first frame has none of them -- a plug conveying run whose first
 * frame holds only the feed column -- and the command needs them only where
 * no option and no recorded tube length gives the value: see
 * mimas_tube_defaults_known); plain data, the same on every MPI rank once
 * rank 0 has decided it. */
typedef struct mimas_tube_setup {
    mimas_tube_geom geom;
    double s_min, s_max, diameter;
} mimas_tube_setup;
int mimas_tube_setup_from(mimas_tube_setup *s, const char *axis_spec, double radius,
                          const mimas_frame *f, const int32_t *types, size_t ntypes, int exclude,
                          mimas_error *err);
/* MIMAS_OK if the diameter d and the axial range s0..s1 a command goes on
 * with are known, else MIMAS_EDATA: no selected particles in the first frame
 * to take them from, and which options give them. */
int mimas_tube_defaults_known(double d, double s0, double s1, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
