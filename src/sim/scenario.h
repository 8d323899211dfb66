/* The parameters of a simulation scenario (mimas simulate), read from an INI
 * file.  Every key is declared once in a table (scenario.c) with its section,
 * type, default, range, unit and meaning; the parser, the error messages,
 * `--print-defaults` and docs/simulate.md all come from that table. */
#ifndef MIMAS_SIM_SCENARIO_H
#define MIMAS_SIM_SCENARIO_H

#include <stddef.h>
#include <stdio.h>

#include "error.h"
#include "parameters.h"

enum { SIM_RINGSHEAR = 0, SIM_BOX = 1, SIM_PULLOFF = 2, SIM_PLUGTUBE = 3 };
#define SIM_SCENARIO_TYPES 4
/* plugtube: the tube's orientation and the fluid model ([gas] model) */
enum { SIM_TUBE_VERTICAL = 0, SIM_TUBE_HORIZONTAL = 1 };
enum { SIM_GAS_PRESSURE = 0, SIM_GAS_FLUID_AT_REST = 1, SIM_GAS_NONE = 2 };
enum { SIM_LINEAR = 0, SIM_HERTZ = 1 };

/* Material types: 0 stands for the walls, 1.. for particle types. */
#define SIM_MAX_TYPES 4

/* Contact-law parameters of one pair of types (docs/theory.md §2). */
typedef struct sim_contact_params {
    int model;                 /* SIM_LINEAR or SIM_HERTZ */
    double k_n, k_t;           /* linear stiffnesses, N/m */
    double gamma_n, gamma_t;   /* linear damping, N s/m */
    double restitution;        /* > 0: gamma_n derived from it (linear) / Hertz damping */
    int normal_clip;           /* the normal force is never attractive (docs/theory.md §2.1) */
    double youngs_modulus, poisson;
    double friction;           /* Coulomb mu */
    double rolling_friction;   /* mu_r, a length (m) */
    double cohesion_energy;    /* JKR work of adhesion w (twice the surface energy), J/m^2 */
    double surface_tension;    /* liquid bridges, N/m */
    double contact_angle;      /* degrees */
    double resting_overlap;    /* > 0: k_n such that a particle resting on a wall overlaps
                                  this fraction of its diameter (linear) */
} sim_contact_params;

typedef struct sim_scenario {
    int type;                  /* SIM_RINGSHEAR, SIM_BOX, SIM_PULLOFF */
    long seed;
    /* [run] */
    double dt, skin, gravity[3];
    long output_every, checkpoint_every;
    int output_settle, dt_guard;
    /* [particles] */
    double diameter, diameter_spread, density, liquid_content, liquid_density, coarse_grain;
    int rotation;
    /* [contact] and [contact A-B]: by type pair, 0 = wall */
    sim_contact_params contact[SIM_MAX_TYPES][SIM_MAX_TYPES];
    sim_contact_params contact_all;   /* [contact] itself: the pairs no [contact A-B] sets */
    /* [ringshear] */
    double r_in, r_split, r_out, fill_height, omega, settle_time, shear_time;
    long count;
    int rough_bottom;
    /* [box] */
    double box_size[3], box_speed, box_time;
    int box_periodic[3], box_bottom_wall;
    long box_count;
    /* [pulloff] */
    double pull_speed, pull_distance;
    /* [plugtube] */
    int tube_orientation;      /* SIM_TUBE_* */
    double tube_gravity, tube_diameter, tube_length, tube_time;
    double mass_flow, feed_speed, feed_porosity;
    long fill_count;
    /* [gas] */
    int gas_model;             /* SIM_GAS_* */
    double gas_velocity, gas_pressure, gas_viscosity, gas_reynolds, gas_cell_length, gas_theta;
    long gas_cells_across, gas_every;
    double fluid_density;
    int drag_law, wall_factor, buoyancy;
} sim_scenario;

/* Defaults of the scenario type (SIM_*). */
void sim_scenario_defaults(sim_scenario *s, int type);
/* Reads an INI file.  Unknown sections or keys, bad numbers and values out of
 * range are MIMAS_EDATA errors "FILE:LINE: ...". */
int sim_scenario_load(sim_scenario *s, const char *path, mimas_error *err);
/* Reads INI text (for tests); name is used in messages. */
int sim_scenario_load_string(sim_scenario *s, const char *text, const char *name,
                             mimas_error *err);
/* Checks the combination of values (e.g. r_in < r_split < r_out); MIMAS_EDATA. */
int sim_scenario_check(const sim_scenario *s, const char *name, mimas_error *err);
/* Writes a complete INI file with every key of the scenario type, its value,
 * unit and meaning. */
void sim_scenario_print(const sim_scenario *s, FILE *out);
/* Every key of the scenario type with its value and unit, as run parameters
 * (section "scenario", "run", ...; [contact] keys in section "contact", and a
 * section "contact A-B" or "contact wall-B" for each key a type pair sets
 * otherwise), for the native file's /parameters/scenario. */
int sim_scenario_parameters(const sim_scenario *s, mimas_parameters *ps, mimas_error *err);
/* The scenario type for a name ("ringshear"...), or -1. */
int sim_scenario_type(const char *name);
/* Markdown table of every key (docs/simulate.md is checked against it). */
void sim_scenario_print_doc(FILE *out);

#endif
