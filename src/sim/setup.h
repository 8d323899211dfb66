/* Building the initial state of a scenario, and its plan: how many steps,
 * when the walls start to move, from when frames are written. */
#ifndef MIMAS_SIM_SETUP_H
#define MIMAS_SIM_SETUP_H

#include <stdint.h>

#include "dem.h"
#include "frame.h"
#include "scenario.h"

typedef struct sim_plan {
    int64_t total_steps;
    int64_t move_from;          /* moving walls and motions run from this step on */
    int64_t output_from;        /* first step with a frame */
    double omega;               /* angular velocity of the moving parts */
    unsigned moving_walls;      /* bit w: wall w turns at omega */
    unsigned moving_motions;    /* bit m: motion m turns at omega */
    mimas_box box;              /* the box written to the frames */
} sim_plan;

/* Fills s (particles, walls, laws) and the plan for the scenario. */
int sim_setup(dem_system *s, const sim_scenario *sc, sim_plan *plan, mimas_error *err);
int sim_setup_ringshear(dem_system *s, const sim_scenario *sc, sim_plan *plan,
                        mimas_error *err);
int sim_setup_box(dem_system *s, const sim_scenario *sc, sim_plan *plan, mimas_error *err);
int sim_setup_pulloff(dem_system *s, const sim_scenario *sc, sim_plan *plan,
                      mimas_error *err);
/* Sets the angular velocity of the moving parts for the coming step. */
void sim_plan_apply(const sim_plan *plan, dem_system *s);

/* The current state as a frame: all particles, the contacts (touching or
 * bridged pairs) and the wall contacts (sim_frame.c). */
int sim_frame_fill(const dem_system *s, const sim_plan *plan, mimas_frame *f,
                   mimas_error *err);

#endif
