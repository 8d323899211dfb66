/* The state of a DEM simulation (mimas simulate): particles, walls, the
 * contact laws of every type pair and the Verlet neighbour list with the
 * contact history.  docs/theory.md §2 and §3. */
#ifndef MIMAS_SIM_DEM_H
#define MIMAS_SIM_DEM_H

#include <stddef.h>
#include <stdint.h>

#include "cohesion.h"
#include "contact_law.h"
#include "error.h"
#include "scenario.h"

#define DEM_MAX_WALLS 8
/* Systems smaller than this run their loops on one thread: waking the
 * others would cost more than the work (a loaded machine makes it worse). */
#define DEM_PARALLEL_MIN 1000

enum { DEM_WALL_PLANE = 0, DEM_WALL_CYLINDER = 1 };

/* A wall.  Moving walls turn about the z axis through (axis[0], axis[1]) at
 * angular velocity omega; their shape does not change (rotationally
 * symmetric), only the velocity of their surface. */
typedef struct dem_wall {
    int kind;
    int32_t id;              /* wall id in the output */
    double point[3];         /* plane: a point on it */
    double normal[3];        /* plane: unit normal pointing into the domain */
    double radius;           /* cylinder (axis parallel to z through axis[]) */
    int outside;             /* cylinder: particles are outside it (an inner wall) */
    double axis[2];
    double omega;            /* angular velocity of the surface about the z axis */
    double moving_from;      /* plane: only the part at r >= moving_from moves (split bottom) */
} dem_wall;

/* A rigid motion that glued particles follow: rotation about the z axis
 * through axis[] at omega plus a translation at velocity. */
typedef struct dem_motion {
    double omega, axis[2], velocity[3];
    double angle, shift[3];  /* turned and moved so far */
    double cos_angle, sin_angle;   /* of angle, once per step for all its particles */
    /* release plane (a feed): with release set, a particle of this motion
     * becomes free (keeping its velocity) once release_normal . x >=
     * release_offset, and takes the type release_type (0: keeps its own) */
    int release;
    double release_normal[3], release_offset;
    int32_t release_type;
} dem_motion;
#define DEM_MAX_MOTIONS 4

/* Flags of a neighbour-list entry */
enum { DEM_TOUCH = 1, DEM_BRIDGE = 2 };

/* One pair (i, j) of the Verlet list with its contact history. */
typedef struct dem_entry {
    int32_t j;
    int32_t flags;           /* DEM_TOUCH while overlapping, DEM_BRIDGE while a bridge exists */
    double xi[3];            /* tangential spring of i relative to j (docs/theory.md §2.3) */
} dem_entry;                 /* 32 bytes: two per cache line */

/* What one entry contributes to one of its particles: force and torque. */
typedef struct dem_entry_force {
    double f[3], t[3];
} dem_entry_force;

typedef struct dem_nlist {
    size_t n;                /* particles the list was built for */
    size_t *start;           /* n + 1: entries of i are start[i] .. start[i+1]-1 */
    dem_entry *e;
    double *bv;              /* per entry: V_B of its bridge (docs/theory.md §2.4), 0 without */
    size_t ne, cap;
    size_t *tstart;          /* transposed: entries where particle j is the second one */
    size_t *tk;              /* entry of each transposed slot */
    size_t *tpos;            /* transposed slot of each entry */
    dem_entry_force *eft;    /* per transposed slot: force and torque on j (the force on i
                                is the negative); written by the pair loop, read in order */
    size_t builds;           /* how many times it was built */
} dem_nlist;

/* Hooks of a scenario into the time step (all optional).  edit runs before
 * every neighbour-list build that dem_neighbours_update decides on: it may
 * remove particles (dem_remove) and append new ones (dem_add_particle); the
 * contact histories of the particles that stay carry over.  body_forces runs
 * in dem_forces after the pair forces, before each particle's forces are
 * summed: it adds forces to s->f of the free particles (a fluid: drag,
 * buoyancy) or sets the held forces s->held, which the sum adds to the free
 * particles every step. */
typedef struct dem_system dem_system;
typedef struct dem_hooks {
    void *ctx;
    int (*edit)(void *ctx, dem_system *s, mimas_error *err);
    void (*body_forces)(void *ctx, dem_system *s);
} dem_hooks;

struct dem_system {
    /* particles (struct of arrays) */
    size_t n, cap;
    int64_t *id;
    int32_t *type;
    double *radius, *mass, *inertia;   /* inertia = (2/5) m R^2 */
    double *liquid;                    /* liquid volume V_L carried (docs/theory.md §2.4) */
    double (*x)[3], (*v)[3], (*w)[3], (*f)[3], (*t)[3];
    double (*x_ref)[3];                /* positions when the list was built */
    int32_t (*image)[3];
    int32_t *glued;                    /* -1: free; else the motion it follows */
    double (*anchor)[3];               /* glued: position at angle 0 and shift 0 */
    int32_t *bridges;                  /* bridges of each particle, this step */
    uint8_t *wall_near;                /* bit w: within reach of wall w until the next list build */
    double (*held)[3];                 /* a force a scenario holds between its updates (the gas
                                        * drag between gas steps), N; 0 for a new particle */
    /* walls; wall-contact history and forces, n x nwalls */
    dem_wall walls[DEM_MAX_WALLS];
    int nwalls;
    double (*wall_xi)[3];
    double (*wall_f)[3];
    double *wall_delta;
    /* box: lo/hi, periodic flags (orthogonal) */
    double lo[3], hi[3];
    int periodic[3];
    int any_periodic;
    /* laws by type pair (0 = wall) */
    dem_law law[SIM_MAX_TYPES][SIM_MAX_TYPES];
    int bridges_on;
    double bridge_range;               /* largest rupture distance possible */
    double coarse_grain;
    /* integration */
    double dt, skin, gravity[3];
    int rotation;
    int64_t step;
    dem_motion motions[DEM_MAX_MOTIONS];
    int nmotions;
    int glued_interact;                /* glued particles interact with each other */
    dem_nlist nl;
    int64_t last_id;                   /* ids are never reused: the next is last_id + 1 */
    int64_t force_step;                /* the step whose positions dem_forces works on */
    dem_hooks hooks;
    /* the region a run stays in (the box of its frames), for dem_check_state */
    int has_domain;
    double domain_lo[3], domain_hi[3];
};

void dem_init(dem_system *s);
void dem_free(dem_system *s);
/* Makes room for n particles (arrays zeroed beyond the old size). */
int dem_reserve(dem_system *s, size_t n, mimas_error *err);
/* Adds a free particle of type, radius, density at x (returns its index);
 * its id is one more than the last id given. */
size_t dem_add_particle(dem_system *s, int32_t type, double radius, double density,
                        const double x[3]);
/* Removes the particles k with drop[k] != 0, keeping the order of the others,
 * their wall histories and their entries in the neighbour list (renumbered). */
int dem_remove(dem_system *s, const uint8_t *drop, mimas_error *err);
int dem_add_wall(dem_system *s, const dem_wall *w, mimas_error *err);
/* Duration of a collision of the linear law L for effective mass m_eff (with
 * its clip: the time of repulsion), or 0 if the contact is overdamped. */
double dem_law_contact_time(const dem_law *L, double m_eff);
/* Sets laws, dt, skin, gravity, rotation, liquid from the scenario. */
int dem_configure(dem_system *s, const sim_scenario *sc, mimas_error *err);

/* Neighbour list (neighbour.c): rebuild when needed; returns 1 if rebuilt. */
int dem_neighbours_update(dem_system *s, mimas_error *err);
int dem_neighbours_build(dem_system *s, mimas_error *err);
/* Builds the transposed index of the list and the force arrays (after the
 * entries were built or restored). */
int dem_neighbours_transpose(dem_nlist *nl, mimas_error *err);

/* Forces (forces.c): contact, wall and body forces into f and t. */
void dem_forces(dem_system *s);

/* Wall geometry (forces.c): overlap of a sphere at x with the wall, the unit
 * normal from the wall to the particle and the contact point on the wall. */
double dem_wall_geometry(const dem_wall *w, const double x[3], double radius, double n[3],
                         double c[3]);
/* Velocity of the wall surface at point c. */
void dem_wall_velocity(const dem_wall *w, const double c[3], double v[3]);

/* Energies (energy.c, docs/simulate.md "Energies"): the motion of the free
 * particles (glued particles move with the walls) and the springs and
 * bridges of every contact of the list (glued pairs are in it only where
 * they interact, as in the pull-off test). */
typedef struct dem_energy {
    double kinetic;      /* sum (1/2) m v^2 */
    double rotational;   /* sum (1/2) I w^2 */
    double elastic;      /* the springs of the touching contacts, particle and wall */
    double bridge;       /* the work the liquid bridges would do until they rupture */
} dem_energy;
int dem_energies(const dem_system *s, dem_energy *e, mimas_error *err);
/* The work of a liquid bridge from gap s to its rupture distance s_c,
 * int_s^s_c F(s') ds' (0 for s >= s_c), by 20-point Gauss-Legendre
 * quadrature; table is a gsl_integration_glfixed_table of 20 points or NULL. */
double dem_bridge_energy(const mimas_bridge *b, double r_p, double s, const void *table);
/* Blow-up detection (blowup.c): MIMAS_EDATA naming the step, the particle
 * and the likely cause when the state is no longer physical: a position,
 * velocity or angular velocity that is not finite, a particle that moves
 * more than its radius in one step, one that left the domain by more than
 * the domain's size, an overlap larger than the smaller radius. */
int dem_check_state(const dem_system *s, mimas_error *err);

/* One velocity-Verlet step (integrate.c). */
int dem_step(dem_system *s, mimas_error *err);

/* Minimum-image separation x_i - x_j. */
static inline void dem_separation(const dem_system *s, const double *xi, const double *xj,
                                  double d[3])
{
    for (int k = 0; k < 3; k++)
        d[k] = xi[k] - xj[k];
    if (s->any_periodic)
        for (int k = 0; k < 3; k++)
            if (s->periodic[k]) {
                double L = s->hi[k] - s->lo[k];
                d[k] -= L * __builtin_nearbyint(d[k] / L);
            }
}

#endif
