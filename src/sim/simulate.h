/* Running a scenario: set-up, the time loop, frames into the native format,
 * checkpoints and resuming (mimas simulate). */
#ifndef MIMAS_SIM_SIMULATE_H
#define MIMAS_SIM_SIMULATE_H

#include <stdint.h>

#include "error.h"
#include "scenario.h"

typedef struct sim_progress {
    int64_t step, total;
    double time;            /* simulated time, s */
    double steps_per_s;     /* since the start of this process */
    double eta;             /* s of wall time left */
    size_t particles, frames;
} sim_progress;

typedef struct sim_run_options {
    const char *output;     /* RUN.h5; the checkpoint is RUN.h5.ckpt */
    int resume;             /* continue from the checkpoint */
    int64_t stop_at;        /* > 0: stop after this step (leaving a checkpoint) */
    const char *provenance; /* recorded in the file */
    void (*progress)(void *ctx, const sim_progress *p);   /* every ~100 steps */
    void *ctx;
    const char *scenario;   /* the scenario file, named in blow-up messages (may be NULL) */
} sim_run_options;

int sim_run(const sim_scenario *sc, const sim_run_options *o, mimas_error *err);

#endif
