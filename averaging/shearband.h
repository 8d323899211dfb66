/* The shear band of a split-bottom ring shear cell (PHYSICS 7, 000 eq. 2.11,
 * Fenistein & van Hecke 2003): per height layer, the angular velocity
 * profile omega(r)/Omega fitted by an error function,
 *   model 2:  0.5 + 0.5 erf((r - Rc)/W)
 *   model 4:  A + B erf((r - Rc)/W)
 * for the band centre Rc and width W.  docs/shearband.md describes the
 * conventions (weights, errors, status). */
#ifndef MIMAS_SHEARBAND_H
#define MIMAS_SHEARBAND_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "fieldset.h"
#include "fit.h"
#include "frame.h"
#include "grid.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Parameters of a band fit, in mimas_fit.p: */
enum { MIMAS_BAND_RC, MIMAS_BAND_W, MIMAS_BAND_A, MIMAS_BAND_B };

/* The profile of model 2 or 4 at r (p: Rc, W, and A, B for model 4). */
double mimas_band_profile(int model, const double *p, double r);

/* Fits one profile y(r) = omega/Omega (sigma its standard errors, or NULL
 * for an unweighted fit).  Invalid points (NaN) are skipped; fewer than
 * min_points valid ones give the status few_points.  Model 4 reports W > 0
 * (the sign of B says which side rotates); for model 2 a negative W (a
 * profile that falls with r: the sign of Omega is wrong) and, for both, an
 * error of Rc or W beyond the radial range of the data give the status
 * implausible. */
int mimas_band_fit(const double *r, const double *y, const double *sigma, size_t n, int model,
                   size_t min_points, mimas_fit *out, mimas_error *err);

typedef struct mimas_band_options {
    double omega;       /* the rotation rate Omega the profile is scaled by (rad/s) */
    int model;          /* 2 or 4 */
    size_t min_points;  /* valid radial cells a layer needs */
    int unweighted;     /* ignore the standard errors */
} mimas_band_options;

typedef struct mimas_band_layer {
    double z;                 /* the layer's centre */
    size_t nr;                /* radial cells */
    double *r, *y, *sigma;    /* cell centres, omega/Omega and its standard error (NaN: none) */
    mimas_fit fit;            /* Rc, W (, A, B) in metres; status */
} mimas_band_layer;

typedef struct mimas_band {
    int model;
    int weighted;             /* the fits used the standard errors */
    const char *velocity;     /* the field the profile came from: "omega" or "v_phi" */
    size_t nlayers;
    mimas_band_layer *layers; /* by increasing z */
    double *store;
} mimas_band;

/* Fits every layer of an r-z field set.  A Cartesian grid, a grid with
 * phi cells, or fields without omega and v_phi are MIMAS_EDATA with a
 * message naming the field set.  Weighted when the velocity has standard
 * errors (and not o->unweighted); a point without one is then skipped. */
int mimas_band_analyse(const mimas_fieldset *fs, const mimas_band_options *o, mimas_band **out,
                       mimas_error *err);
void mimas_band_free(mimas_band *b);

/* Fenistein & van Hecke's surface-layer prediction 1 - Rc/Rs = (H/Rs)^2.5:
 * Rc = Rs (1 - (H/Rs)^2.5) for split radius Rs and fill height H. */
double mimas_band_fenistein_rc(double rs, double h);

/* The r-z grid for raw particle input, chosen from a frame: the axis along
 * z through the centre of the box's x-y extent; r and z over the particles'
 * extent (centre -+ radius); cells of about two mean particle diameters.
 * spec gets the equivalent "--grid ... --axis ..." of mimas average. */
int mimas_band_choose_grid(const mimas_frame *f, mimas_grid *g, char *spec, size_t len,
                           mimas_error *err);

/* Draws omega/Omega against r for every layer with its fitted curve, and
 * Rc(z) with error bars, into png (gnuplot). */
int mimas_band_plot(const mimas_band *b, const char *png, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
