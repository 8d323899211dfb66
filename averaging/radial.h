/* Radial profiles of a tube flow by probe spheres (mimas radial; Strauß
 * 2005, Sec. 4.2; docs/theory.md §7.4, docs/radial.md): probe spheres of one
 * diameter centred on circles about the axis in planes normal to it, each
 * particle weighted by the exact lens volume it shares with a probe; per
 * radius the values of a sample (a frame, or a plug) are averaged over the
 * probes of that radius, and the samples over the run. */
#ifndef MIMAS_RADIAL_H
#define MIMAS_RADIAL_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "frame.h"
#include "tube.h"

#ifdef __cplusplus
extern "C" {
#endif

enum mimas_radial_field {
    MIMAS_RAD_POROSITY, MIMAS_RAD_NU, MIMAS_RAD_VR, MIMAS_RAD_VPHI, MIMAS_RAD_VS, MIMAS_RAD_T,
    MIMAS_RAD_EROT, MIMAS_RAD_NFIELDS
};
typedef struct mimas_radial_field_desc {
    const char *name, *unit, *meaning;
} mimas_radial_field_desc;
const mimas_radial_field_desc *mimas_radial_field(int k);

typedef struct mimas_radial_options {
    mimas_tube_geom geom;
    double probe;          /* probe diameter, m */
    double dr;             /* radial step, m: radii 0, dr, ... up to R - probe/2 */
    unsigned temperature;  /* MIMAS_TEMP_* bits (axial_profile.h); 0: all three */
    const int32_t *types;
    size_t ntypes;
    int exclude;
    int check_inside;
} mimas_radial_options;

typedef struct mimas_radial mimas_radial;

int mimas_radial_create(mimas_radial **r, const mimas_radial_options *o, mimas_error *err);
size_t mimas_radial_nradii(const mimas_radial *r);
double mimas_radial_radius(const mimas_radial *r, size_t k);
/* Probes on radius k (the circle of radius r_k carries max(1, ceil(2 pi r_k
 * / probe)) probes evenly spaced). */
size_t mimas_radial_probes(const mimas_radial *r, size_t k);
/* One sample: the probe planes at the axial positions planes[0..n-1] in
 * frame f; its per-radius values go into the averages. */
int mimas_radial_sample(mimas_radial *r, const mimas_frame *f, const double *planes, size_t n,
                        mimas_error *err);
/* The same in two steps: the sample's per-radius values (nr x
 * MIMAS_RAD_NFIELDS, radius-major; mimas_radial_values, valid until the
 * next probe), then their addition to the averages (values from this or
 * another mimas_radial of the same options, e.g. on another MPI rank). */
int mimas_radial_probe(mimas_radial *r, const mimas_frame *f, const double *planes, size_t n,
                       mimas_error *err);
const double *mimas_radial_values(const mimas_radial *r);
void mimas_radial_add(mimas_radial *r, const double *values);
/* The last sample's value of field at radius k. */
double mimas_radial_last(const mimas_radial *r, size_t k, int field);
/* The average over samples, its standard error and the sample count. */
void mimas_radial_result(const mimas_radial *r, size_t k, int field, double *mean, double *sem,
                         size_t *n);
size_t mimas_radial_samples(const mimas_radial *r);
void mimas_radial_free(mimas_radial *r);

#ifdef __cplusplus
}
#endif
#endif
