/* The mimas data model (docs/format.md and docs/api.md, "Frame"): a frame is one snapshot with
 * its box, particles, particle-particle contacts and particle-wall contacts.
 *
 * Each of the three tables is a struct of arrays, sized per frame and owned by
 * the frame.  Which arrays exist is recorded in the table's `present` bit mask;
 * an absent quantity has a NULL array.  Every quantity is also described once
 * in a column table (name, type, components, unit, meaning); the generic table
 * functions below and the file writers and readers work from that description
 * instead of naming each array. */
#ifndef MIMAS_FRAME_H
#define MIMAS_FRAME_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mimas_elem_type {
    MIMAS_T_F64,   /* double */
    MIMAS_T_I64,   /* int64_t */
    MIMAS_T_I32,   /* int32_t */
    MIMAS_T_INDEX  /* size_t: index into this frame's particle arrays */
} mimas_elem_type;

typedef struct mimas_column_desc {
    const char *name;        /* name in files and messages, e.g. "velocity" */
    mimas_elem_type type;
    int ncomp;               /* components per row: 1 or 3 */
    size_t offset;           /* offsetof() the array pointer in its table struct */
    unsigned bit;            /* presence bit */
    const char *unit;        /* SI unit, "1" for dimensionless */
    const char *meaning;     /* one line */
} mimas_column_desc;

/* An optional named column of doubles (e.g. a dump's c_stress[1]). */
typedef struct mimas_extra {
    char *name;
    int ncomp;
    double *data;            /* n * ncomp values */
    char unit[16];           /* SI unit, "" if unknown (files: the "unit" attribute) */
} mimas_extra;

/* ---- particles ---- */
enum {
    MIMAS_P_ID = 1u << 0, MIMAS_P_TYPE = 1u << 1, MIMAS_P_RADIUS = 1u << 2,
    MIMAS_P_MASS = 1u << 3, MIMAS_P_POS = 1u << 4, MIMAS_P_VEL = 1u << 5,
    MIMAS_P_OMEGA = 1u << 6, MIMAS_P_FORCE = 1u << 7, MIMAS_P_IMAGE = 1u << 8,
    MIMAS_P_CG = 1u << 9, MIMAS_P_LIQUID = 1u << 10
};

typedef struct mimas_particles {
    size_t n, cap;
    unsigned present;
    int64_t *id;
    int32_t *type;
    double *radius;
    double *mass;
    double (*pos)[3];
    double (*vel)[3];
    double (*omega)[3];        /* angular velocity */
    double (*force)[3];
    int32_t (*image)[3];       /* periodic image flags */
    double *cg;                /* coarse-grain factor alpha (docs/theory.md §2.5) */
    double *liquid;            /* liquid content: volume of liquid carried */
    size_t n_extra;
    mimas_extra *extra;
} mimas_particles;

/* ---- particle-particle contacts ---- */
enum {
    MIMAS_C_I = 1u << 0, MIMAS_C_J = 1u << 1, MIMAS_C_POINT = 1u << 2,
    MIMAS_C_FORCE = 1u << 3, MIMAS_C_FORCE_N = 1u << 4, MIMAS_C_FORCE_T = 1u << 5,
    MIMAS_C_OVERLAP = 1u << 6
};

typedef struct mimas_contacts {
    size_t n, cap;
    unsigned present;
    size_t *i, *j;             /* indices into the particle arrays */
    double (*point)[3];        /* contact point */
    double (*force)[3];        /* force on i exerted by j (docs/theory.md §1) */
    double (*force_n)[3];      /* its normal part */
    double (*force_t)[3];      /* its tangential part */
    double *overlap;           /* R_i + R_j - |r_i - r_j| */
    size_t n_extra;
    mimas_extra *extra;        /* e.g. liquid-bridge volume */
} mimas_contacts;

/* ---- particle-wall contacts ---- */
enum {
    MIMAS_W_PARTICLE = 1u << 0, MIMAS_W_WALL = 1u << 1, MIMAS_W_POINT = 1u << 2,
    MIMAS_W_FORCE = 1u << 3, MIMAS_W_FORCE_N = 1u << 4, MIMAS_W_FORCE_T = 1u << 5,
    MIMAS_W_OVERLAP = 1u << 6
};

typedef struct mimas_wall_contacts {
    size_t n, cap;
    unsigned present;
    size_t *particle;          /* index into the particle arrays */
    int32_t *wall;             /* wall id */
    double (*point)[3];
    double (*force)[3];        /* force on the particle from the wall */
    double (*force_n)[3];
    double (*force_t)[3];
    double *overlap;
    size_t n_extra;
    mimas_extra *extra;
} mimas_wall_contacts;

typedef struct mimas_table_desc {
    const char *name;                  /* "particles", "contacts", "wall contacts" */
    const mimas_column_desc *columns;
    size_t ncolumns;
    unsigned required;                 /* bits every table of this kind has */
    size_t off_n, off_cap, off_present, off_n_extra, off_extra;
} mimas_table_desc;

extern const mimas_table_desc mimas_particles_desc;
extern const mimas_table_desc mimas_contacts_desc;
extern const mimas_table_desc mimas_walls_desc;

/* ---- box ---- */
/* LAMMPS convention: edge vectors a = (hi-lo)_x e_x, b = (xy, (hi-lo)_y, 0),
 * c = (xz, yz, (hi-lo)_z), origin lo. */
typedef struct mimas_box {
    double lo[3], hi[3];
    double xy, xz, yz;
    int periodic[3];
} mimas_box;

int mimas_box_is_triclinic(const mimas_box *b);
/* 1 if the two boxes have the same bounds, tilts and periodicity (values compared, not
 * bytes: -0 equals 0). */
int mimas_box_equal(const mimas_box *a, const mimas_box *b);
double mimas_box_volume(const mimas_box *b);
/* The fractional coordinates s of x along the box's edge vectors e (mimas_box_edges):
 * x = lo + s_0 e_0 + s_1 e_1 + s_2 e_2 (0 <= s < 1 inside the box). */
void mimas_box_fractional(const mimas_box *b, const double e[3][3], const double x[3],
                          double s[3]);
/* Rows are the edge vectors a, b, c. */
void mimas_box_edges(const mimas_box *b, double e[3][3]);
/* Replaces d by its minimum image along the periodic directions (docs/theory.md §1),
 * for orthogonal and triclinic boxes (LAMMPS' convention: the nearest image
 * in fractional coordinates). */
void mimas_box_min_image(const mimas_box *b, double d[3]);
/* The same, and k[e] the whole edge vectors e (a, b, c) taken off d: the
 * original d is the result plus k[0] a + k[1] b + k[2] c (k is 0 along
 * directions that are not periodic). */
void mimas_box_min_image_shift(const mimas_box *b, double d[3], double k[3]);

/* ---- tube geometry (tube-flow runs: plug conveying) ---- */
/* The tube a run flows through, as the native file records it (attributes of
 * /parameters/tube, docs/format.md) so that the tube analyses (mimas plugs,
 * radial) need no geometry options.  Axial coordinate s = (x - origin) .
 * direction, from 0 at the inlet to length at the outlet; radius r from the
 * axis. */
typedef struct mimas_tube {
    int present;             /* 0: the input does not say */
    double origin[3];        /* the axis point at the inlet (s = 0), m */
    double direction[3];     /* unit vector along the axis, inlet to outlet */
    double radius;           /* inner radius, m */
    double length;           /* m */
} mimas_tube;

/* ---- gas fields on a regular grid (plug conveying gas model) ---- */
/* Cell-centred values on nx x ny x nz cells of edge spacing[] whose lower
 * corner is origin; cell (i, j, k) is value index i + nx (j + ny k). */
typedef struct mimas_gas {
    int present;             /* 0: no gas fields in this frame */
    double origin[3], spacing[3];
    size_t cells[3];
    size_t cap;              /* cells allocated */
    double *pressure;        /* Pa */
    double *porosity;        /* void fraction, 1 */
    double (*velocity)[3];   /* superficial (Darcy) gas velocity, m/s */
} mimas_gas;

/* Sets the grid to nx x ny x nz cells, growing the arrays as needed, and
 * marks it present (values not initialised). */
int mimas_gas_resize(mimas_gas *g, size_t nx, size_t ny, size_t nz, mimas_error *err);
size_t mimas_gas_cells(const mimas_gas *g);
void mimas_gas_free(mimas_gas *g);

typedef struct mimas_frame {
    int64_t step;
    double time;
    mimas_box box;
    /* whether the source has contact / wall-contact data for this frame at
     * all (a frame can have contact data with zero contacts) */
    int has_contacts, has_walls;
    mimas_particles particles;
    mimas_contacts contacts;
    mimas_wall_contacts walls;
    mimas_tube tube;         /* the tube of a tube-flow run (present: the input says) */
    mimas_gas gas;           /* gas fields (present: this frame has them) */
} mimas_frame;

void mimas_frame_init(mimas_frame *f);
void mimas_frame_free(mimas_frame *f);
/* Sets every table to zero rows and no optional quantities; keeps the memory. */
void mimas_frame_clear(mimas_frame *f);

/* ---- particle selection by type (--types / --exclude-types) ---- */
/* Whether particle k is used: with ntypes == 0 every particle; else those
 * whose type is listed (exclude == 0) or not listed (exclude != 0).
 * Particles without types count as type 1. */
int mimas_particle_selected(const mimas_particles *p, size_t k, const int32_t *types,
                            size_t ntypes, int exclude);

/* ---- generic table operations (tab points to one of the three structs) ---- */
size_t mimas_elem_size(mimas_elem_type t);
size_t mimas_table_n(const void *tab, const mimas_table_desc *d);
unsigned mimas_table_present(const void *tab, const mimas_table_desc *d);
/* The array of a column (NULL when absent). */
void *mimas_table_column(const void *tab, const mimas_table_desc *d, size_t col);
const mimas_column_desc *mimas_table_find(const mimas_table_desc *d, const char *name);
/* Makes the quantities in bits present (allocating them) and keeps the others. */
int mimas_table_set_present(void *tab, const mimas_table_desc *d, unsigned bits,
                            mimas_error *err);
/* Sets the row count to n, growing every present array as needed. */
int mimas_table_resize(void *tab, const mimas_table_desc *d, size_t n, mimas_error *err);
/* Adds (or finds) an extra column of ncomp doubles; returns its index in *index. */
int mimas_table_add_extra(void *tab, const mimas_table_desc *d, const char *name,
                          int ncomp, size_t *index, mimas_error *err);
/* The same for a name the caller knows the table does not have yet (no
 * search: adding many columns takes linear time). */
int mimas_table_add_new_extra(void *tab, const mimas_table_desc *d, const char *name, int ncomp,
                              mimas_error *err);
void mimas_table_free(void *tab, const mimas_table_desc *d);
/* Frees the optional quantities not in bits (required ones always stay). */
void mimas_table_keep_only(void *tab, const mimas_table_desc *d, unsigned bits);
void mimas_table_drop_extras(void *tab, const mimas_table_desc *d);
/* MIMAS_OK if all quantities in bits are present, else MIMAS_EMISSING with a
 * message such as "contacts have no contact_point". */
int mimas_table_require(const void *tab, const mimas_table_desc *d, unsigned bits,
                        mimas_error *err);

/* ---- validation (src/frame_check.c): what every reader applies ---- */
/* MIMAS_EDATA unless the box bounds are finite and increasing and its tilts
 * finite. */
int mimas_box_check(const mimas_box *b, mimas_error *err);
/* MIMAS_EDATA with a message naming the particle or contact row unless every
 * standard quantity of the frame is usable: finite positions, velocities,
 * angular velocities, forces and contact vectors; positive radii, masses and
 * coarse-grain factors; liquid volumes >= 0; contact indices inside the
 * particle table; a time that is finite or NaN (unknown).  Extra columns are
 * not checked (NaN marks a value that is undefined there). */
int mimas_frame_check(const mimas_frame *f, mimas_error *err);
/* Moves positions outside the box along its periodic directions into it by
 * whole edge vectors, adding the shifts to the image flags when the frame has
 * them (the unwrapped position stays the same).  MIMAS_EDATA for a position
 * more than 1e9 box lengths away. */
int mimas_frame_wrap(mimas_frame *f, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
