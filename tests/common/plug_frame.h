/* Synthetic tube-flow frames with known plugs, for the plug tests, the
 * test tool make_plug_frames and the benchmark.  A plug is a cylinder of
 * the tube's cross-section filled with spheres at a given solid fraction
 * (centres evenly spaced in [back, front] and r <= R - a, overlaps allowed:
 * only volumes matter; the solid fraction ramps from nu to 0 over a
 * diameter about each end), moving at its velocity.  A faster plug that
 * reaches the one ahead moves on with it (a merge at the moment of
 * contact); a plug with a split time leaves its part below split_at x
 * length behind at v_split from then on.  Deterministic: the same spec and
 * time give the same particles. */
#ifndef MIMAS_TEST_PLUG_FRAME_H
#define MIMAS_TEST_PLUG_FRAME_H

#include <stddef.h>
#include <stdint.h>

#include "axis.h"
#include "frame.h"

#define PLUG_MAX 16

typedef struct plug_spec {
    double back;      /* at t = 0, m */
    double length;    /* m */
    double v;         /* axial velocity, m/s */
    double nu;        /* solid fraction */
    double t_split;   /* > 0: time of a split */
    double split_at;  /* fraction of the length (from the back) where it splits */
    double v_split;   /* velocity of the part behind after the split */
} plug_spec;

typedef struct tube_spec {
    mimas_axis axis;  /* origin: s = 0 */
    double radius;    /* tube radius R */
    double d;         /* particle diameter */
    double density;   /* kg/m^3 */
    double length;    /* tube length (the extent of the dilute background) */
    double dilute;    /* solid fraction of a static background between 0 and length */
    unsigned long seed;
    size_t nplugs;
    plug_spec plugs[PLUG_MAX];  /* ordered by back */
} tube_spec;

/* R = 3.5 mm, d = 1.4 mm, density 937 (Strauß 2005's standard set), the z
 * axis, length 0.2 m, no background, no plugs. */
void tube_spec_default(tube_spec *t);
/* The axial shift of plug k's part (lower: the part below a split) at
 * time t, and its velocity then. */
void plug_motion(const tube_spec *t, size_t k, int lower, double time, double *shift,
                 double *v);
/* Fills f with the frame at time (step given); 0 on success. */
int plug_frame(mimas_frame *f, const tube_spec *t, double time, int64_t step);

#endif
