/* Cohorts of mimas disperse (docs/disperse.md, "Cohorts"): sets of
 * particles followed together, after Strauß (2005, Sec. 5.7), whose grains
 * entering the tube together spread about their mean trajectory.
 *   all                      every selected particle
 *   types:L                  particles of the types in the comma list L
 *   ids:FILE                 the particle ids listed in FILE (whitespace or
 *                            commas between them, '#' starts a comment)
 *   inserted:T0:T1           particles first seen at a time T0 <= t <= T1
 *   region:SPEC@T            particles inside a region in the first frame at
 *                            or after time T; SPEC is
 *                              box:X0,Y0,Z0:X1,Y1,Z1   (lo <= x < hi)
 *                              slab:S0:S1              (S0 <= s < S1 along --axis)
 *                              cylinder:R[:S0:S1]      (within R of --axis)
 * Membership is decided while the frames stream in, from the positions as
 * read; a slot's membership is a bit mask (at most MIMAS_COHORTS_MAX
 * cohorts). */
#ifndef MIMAS_COHORT_H
#define MIMAS_COHORT_H

#include <stddef.h>
#include <stdint.h>

#include "axis.h"
#include "error.h"
#include "frame.h"
#include "id_index.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MIMAS_COHORTS_MAX 64

typedef enum mimas_cohort_kind {
    MIMAS_COHORT_ALL,
    MIMAS_COHORT_TYPES,
    MIMAS_COHORT_IDS,
    MIMAS_COHORT_INSERTED,
    MIMAS_COHORT_REGION
} mimas_cohort_kind;

typedef enum mimas_region_kind {
    MIMAS_REGION_BOX,
    MIMAS_REGION_SLAB,
    MIMAS_REGION_CYLINDER
} mimas_region_kind;

typedef struct mimas_region {
    mimas_region_kind kind;
    double lo[3], hi[3];   /* box */
    double radius;         /* cylinder */
    double s0, s1;         /* slab, cylinder: axial range (cylinder: -inf..inf if not given) */
} mimas_region;

/* 1 if x lies inside r (slabs and cylinders about axis). */
int mimas_region_contains(const mimas_region *r, const mimas_axis *axis, const double x[3]);

typedef struct mimas_cohort {
    char spec[256];          /* as given: the cohort's name in the tables */
    mimas_cohort_kind kind;
    int32_t types[64];
    size_t ntypes;
    double t0, t1;           /* inserted */
    mimas_region region;     /* region */
    double at;
    mimas_id_index ids;      /* ids */
    int64_t *id_list;
    /* what the frames decided */
    int decided;             /* region: the frame at T has been seen */
    double decided_time;
    size_t size;             /* members */
} mimas_cohort;

/* Parses one specification (an ids file is read here): MIMAS_EUSAGE for a
 * malformed one, MIMAS_EDATA for an unreadable or bad ids file. */
int mimas_cohort_parse(mimas_cohort *c, const char *spec, mimas_error *err);
void mimas_cohort_free(mimas_cohort *c);

typedef struct mimas_cohorts mimas_cohorts;

/* The cohorts of specs (n = 0: "all"). */
int mimas_cohorts_create(mimas_cohorts **cs, const char *const *specs, size_t n,
                         mimas_error *err);
size_t mimas_cohorts_count(const mimas_cohorts *cs);
const mimas_cohort *mimas_cohorts_get(const mimas_cohorts *cs, size_t k);
/* Decides the memberships the frame settles: slot_of[i] is particle i's
 * slot (SIZE_MAX: not selected), is_new[i] whether it is its first frame
 * (as mimas_traj_frame_slots/_new give them).  MIMAS_EMISSING when a types
 * cohort meets particles without types. */
int mimas_cohorts_frame(mimas_cohorts *cs, const mimas_frame *f, const size_t *slot_of,
                        const unsigned char *is_new, const mimas_axis *axis, mimas_error *err);
/* Bit k set: slot belongs to cohort k. */
uint64_t mimas_cohorts_mask(const mimas_cohorts *cs, size_t slot);
void mimas_cohorts_free(mimas_cohorts *cs);

#ifdef __cplusplus
}
#endif
#endif
