/* Building the initial state of a scenario, and its plan: how many steps,
 * when the walls start to move, from when frames are written. */
#ifndef MIMAS_SIM_SETUP_H
#define MIMAS_SIM_SETUP_H

#include <stdint.h>

#include "checkpoint.h"
#include "dem.h"
#include "frame.h"
#include "scenario.h"

typedef struct sim_tube_run sim_tube_run;   /* plugtube: feed, gas, tube (setup_plugtube.c) */

typedef struct sim_plan {
    int64_t total_steps;
    int64_t move_from;          /* moving walls and motions run from this step on */
    int64_t output_from;        /* first step with a frame */
    double omega;               /* angular velocity of the moving parts */
    unsigned moving_walls;      /* bit w: wall w turns at omega */
    unsigned moving_motions;    /* bit m: motion m turns at omega */
    mimas_box box;              /* the box written to the frames */
    sim_tube_run *tube;         /* plugtube: its running state (NULL otherwise) */
} sim_plan;

/* The scenario with what its keys leave to be derived: gravity of a tube,
 * stiffness_normal from resting_overlap, dt = 0 as t_c/50 of the stiffest
 * linear pair. */
int sim_scenario_resolve(const sim_scenario *sc, sim_scenario *out, mimas_error *err);
/* Fills s (particles, walls, laws) and the plan for the scenario (resolved
 * here with sim_scenario_resolve). */
int sim_setup(dem_system *s, const sim_scenario *sc, sim_plan *plan, mimas_error *err);
/* Frees what the set-up allocated for the plan (and unhooks it from s). */
void sim_plan_free(sim_plan *plan, dem_system *s);
/* The scenario's state beyond s, for checkpoints: up to max blocks; returns
 * their number. */
size_t sim_plan_state(const sim_plan *plan, sim_ck_chunk *chunks, size_t max);
int sim_setup_ringshear(dem_system *s, const sim_scenario *sc, sim_plan *plan,
                        mimas_error *err);
int sim_setup_box(dem_system *s, const sim_scenario *sc, sim_plan *plan, mimas_error *err);
int sim_setup_pulloff(dem_system *s, const sim_scenario *sc, sim_plan *plan,
                      mimas_error *err);
int sim_setup_plugtube(dem_system *s, const sim_scenario *sc, sim_plan *plan,
                       mimas_error *err);
void sim_tube_free(sim_tube_run *t);
size_t sim_tube_state(sim_tube_run *t, sim_ck_chunk *chunks, size_t max);
/* The gas-pressure model of a plugtube run (NULL for other gas models). */
struct sim_gas *sim_tube_gas(sim_tube_run *t);
/* The tube and gas fields of a plugtube run into the frame. */
int sim_tube_frame(const sim_tube_run *t, mimas_frame *f, mimas_error *err);
/* Sets the angular velocity of the moving parts for the coming step. */
void sim_plan_apply(const sim_plan *plan, dem_system *s);

/* The current state as a frame: all particles, the contacts (touching or
 * bridged pairs) and the wall contacts (sim_frame.c). */
int sim_frame_fill(const dem_system *s, const sim_plan *plan, mimas_frame *f,
                   mimas_error *err);

#endif
