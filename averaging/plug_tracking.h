/* Plug tracking and the statistics built on it (mimas plugs; Strauß 2005,
 * Sec. 4.4, 5.4-5.5, 6.4-6.5; docs/theory.md §7.3, docs/plugs.md): the
 * sequential part of the plug analysis.  It takes each frame's plug list (in
 * time order) with the plugs' plug-centred profiles and keeps only what the
 * tracks still open need, so memory does not grow with the frame count:
 *   - plugs of consecutive frames are matched one to one; a plug of the new
 *     frame whose extent meets the predicted extents of two plugs (or whose
 *     predicted centre is within the gate of two) is a merge, two plugs
 *     from one a split, both event rows; a track ends at an event and the
 *     plugs after it start new tracks, so no plug belongs to two tracks;
 *   - per track: the plug velocity (least-squares slope of the centre's
 *     trajectory, with its error), front and back velocities, the mean
 *     particle velocity and length;
 *   - plug-centred profiles averaged over tracks (one sample per track);
 *   - statistics in windows along the tube (one sample per track and
 *     window) and the passage rate. */
#ifndef MIMAS_PLUG_TRACKING_H
#define MIMAS_PLUG_TRACKING_H

#include <stddef.h>

#include "error.h"
#include "plugs.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_tracking_options {
    double max_shift;        /* the gate (m); NaN: half the smallest centre distance */
    mimas_profile_bins bins; /* plug-centred profiles (bins.n = 0: none) */
    double v0, v1;           /* particle velocity window of the profiles (m/s) */
    double l0, l1;           /* length window of the profiles (m) */
    double stats_s0, stats_w;/* statistics windows along the axis */
    size_t stats_n;          /* 0: none */
} mimas_tracking_options;

typedef struct mimas_track_row {
    long track;
    double first_time, last_time;
    size_t frames;           /* frames the track was seen in */
    size_t fitted;           /* uncut frames used for the velocities */
    double plug_velocity, plug_velocity_err, front_velocity, back_velocity;
    double particle_velocity, length, mass;
} mimas_track_row;

enum { MIMAS_EVENT_MERGE, MIMAS_EVENT_SPLIT, MIMAS_EVENT_REGROUP };
typedef struct mimas_event {
    double time;
    double centre;           /* mass-weighted centre of the plugs after the event */
    int kind;
    size_t nbefore, nafter;
    long *tracks;            /* nbefore tracks that end, then nafter that start */
} mimas_event;
const char *mimas_event_kind_name(int kind);

/* Statistics quantities per window. */
enum { MIMAS_ST_PLUG_VELOCITY, MIMAS_ST_PARTICLE_VELOCITY, MIMAS_ST_LENGTH,
       MIMAS_ST_MIN_POROSITY, MIMAS_ST_WALL_PRESSURE, MIMAS_ST_N };
const char *mimas_stat_name(int q);
const char *mimas_stat_unit(int q);

typedef struct mimas_tracker mimas_tracker;

int mimas_tracker_create(mimas_tracker **t, const mimas_tracking_options *o, mimas_error *err);
/* The next frame (at time, which must exceed the previous frame's) and its
 * plugs, every frame even without plugs; profiles holds each plug's
 * plug-centred profile (n x bins.n x MIMAS_AX_NFIELDS values; may be NULL
 * without bins).  Sets each plug's track. */
int mimas_tracker_add(mimas_tracker *t, double time, mimas_plug_list *plugs,
                      const double *profiles, mimas_error *err);
/* Ends every open track.  Call once after the last frame. */
int mimas_tracker_finish(mimas_tracker *t, mimas_error *err);

/* Results (after finish). */
size_t mimas_tracker_ntracks(const mimas_tracker *t);
const mimas_track_row *mimas_tracker_track(const mimas_tracker *t, size_t k); /* by id order */
size_t mimas_tracker_nevents(const mimas_tracker *t);
const mimas_event *mimas_tracker_event(const mimas_tracker *t, size_t k);
/* Plug-centred profile of bin b, field f: mean over tracks, its standard
 * error (NaN with fewer than two tracks) and the track count. */
void mimas_tracker_profile(const mimas_tracker *t, size_t b, int f, double *mean, double *sem,
                           size_t *n);
/* Statistics of window w, quantity q (mean over tracks, standard error, count). */
void mimas_tracker_stat(const mimas_tracker *t, size_t w, int q, double *mean, double *sem,
                        size_t *n);
/* Net passages of plug centres through the window's centre plane (towards
 * the outlet minus back), the rate per second over the frames' time span,
 * and its Poisson error. */
void mimas_tracker_passages(const mimas_tracker *t, size_t w, long *passages, double *rate,
                            double *err);
/* Time span of the frames given (last - first time) and their count. */
double mimas_tracker_span(const mimas_tracker *t);
size_t mimas_tracker_frames(const mimas_tracker *t);
void mimas_tracker_free(mimas_tracker *t);

#ifdef __cplusplus
}
#endif
#endif
