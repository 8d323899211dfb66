/* Axial profiles of a tube flow (mimas plugs; docs/plugs.md): one frame's
 * particles, contacts and wall contacts cut into slices along the tube axis,
 * each particle weighted by the exact volume of its sphere inside the slice.
 * The per-frame part of the plug analysis: it knows nothing of other frames,
 * so frames can be computed anywhere (threads, ranks) and handed on. */
#ifndef MIMAS_AXIAL_PROFILE_H
#define MIMAS_AXIAL_PROFILE_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "frame.h"
#include "tube.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The fields of a slice, in the order of the axial table's columns. */
enum mimas_axial_field {
    MIMAS_AX_POROSITY, MIMAS_AX_NU, MIMAS_AX_N, MIMAS_AX_VS, MIMAS_AX_VR, MIMAS_AX_VPHI,
    MIMAS_AX_T, MIMAS_AX_STRESS_SS, MIMAS_AX_STRESS_RR, MIMAS_AX_WALL_P, MIMAS_AX_WALL_SHEAR,
    MIMAS_AX_WALL_FRICTION, MIMAS_AX_GAS_P, MIMAS_AX_KSTRESS_SS, MIMAS_AX_KSTRESS_RR,
    MIMAS_AX_CSTRESS_SS, MIMAS_AX_CSTRESS_RR, MIMAS_AX_NFIELDS
};

/* One description per field: feeds the table header, the HDF5 attributes
 * and docs/plugs.md. */
typedef struct mimas_axial_field_desc {
    const char *name;
    const char *unit;
    const char *meaning;
} mimas_axial_field_desc;
const mimas_axial_field_desc *mimas_axial_field(int k);

/* Primary sums per slice (extensive: they add over particles, and over
 * frames for time averages). */
enum mimas_axial_sum {
    MIMAS_AS_VOLUME,      /* solid volume inside the slice, m^3 */
    MIMAS_AS_MOMENT,      /* its mass-weighted first moment: sum rho_i int s dV, kg m */
    MIMAS_AS_N,           /* particles: sum of the volume fractions f_i */
    MIMAS_AS_MASS,        /* sum m_i f_i, kg */
    MIMAS_AS_P,           /* 3: sum m_i f_i v_i (s, r, phi components), kg m/s */
    MIMAS_AS_K = MIMAS_AS_P + 3, /* 3: sum m_i f_i v_i^2 per component, J (x 2) */
    MIMAS_AS_CSS = MIMAS_AS_K + 3, /* contact sum f_s b_s x branch fraction, N m */
    MIMAS_AS_CRR,
    MIMAS_AS_WALL_N,      /* normal force on the tube wall (outward), N */
    MIMAS_AS_WALL_T,      /* axial force on the tube wall (+s), N */
    MIMAS_AS_GAS_PW,      /* sum of cell pressure x weight */
    MIMAS_AS_GAS_W,       /* sum of the weights */
    MIMAS_AS_NSUMS
};

/* Granular temperature components (--temperature-components). */
enum { MIMAS_TEMP_S = 1, MIMAS_TEMP_R = 2, MIMAS_TEMP_PHI = 4 };

typedef struct mimas_axial_options {
    mimas_tube_geom geom;
    mimas_slices slices;
    unsigned temperature;  /* MIMAS_TEMP_* bits; 0: all three */
    const int32_t *types;  /* particle types used (or left out with exclude); NULL: all */
    size_t ntypes;
    int exclude;
    int check_inside;      /* error on particles outside the tube */
    double flow_at;        /* cross-section of the mass flow rate (NaN: none) */
} mimas_axial_options;

typedef struct mimas_axial mimas_axial;

int mimas_axial_create(mimas_axial **ax, const mimas_axial_options *o, mimas_error *err);
/* Computes the frame's sums and fields (replacing the previous frame's).
 * MIMAS_EMISSING when particles lack radii or positions, or wall contacts
 * their points or forces; MIMAS_EDATA for a particle outside the tube. */
int mimas_axial_compute(mimas_axial *ax, const mimas_frame *f, mimas_error *err);
const mimas_axial_options *mimas_axial_opts(const mimas_axial *ax);
/* Slice k's sum (enum mimas_axial_sum) and field (enum mimas_axial_field). */
double mimas_axial_sum(const mimas_axial *ax, size_t k, int which);
double mimas_axial_value(const mimas_axial *ax, size_t k, int field);
/* All fields of slice k, MIMAS_AX_NFIELDS values. */
const double *mimas_axial_row(const mimas_axial *ax, size_t k);
/* Whole-frame figures: particles whose centre lies in the tube ([0, L]
 * when the length is known, else the slices' range), their mass; the
 * solid mass flow rate through the cross-section at flow_at (sum m_i v_s,i
 * f_i / W over the slab of one slice width centred there; NaN without
 * flow_at); whether the frame had gas fields, and then the pressure drop:
 * the gas pressure of the first minus that of the last slice that has one
 * (NaN without gas fields). */
typedef struct mimas_axial_totals {
    double particles, mass, flow_rate;
    int gas;
    double pressure_drop;
} mimas_axial_totals;
mimas_axial_totals mimas_axial_frame_totals(const mimas_axial *ax);
/* Sets the fields (slices x MIMAS_AX_NFIELDS values, as mimas_axial_row
 * gives them) and whole-frame figures of a frame computed elsewhere with the
 * same options (another MPI rank); the sums are left as they were. */
void mimas_axial_load(mimas_axial *ax, const double *values, const mimas_axial_totals *t);
void mimas_axial_free(mimas_axial *ax);

#ifdef __cplusplus
}
#endif
#endif
