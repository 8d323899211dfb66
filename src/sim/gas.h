/* The gas-pressure model of plug conveying (docs/theory.md §4; Strauß 2005,
 * Sec. 3.2-3.3, after McNamara and Flekkøy): the linearised pressure
 * equation
 *   dP/dt = (P0/(eta phi)) div(kappa grad P) - (P0/phi) div u
 * for the gas pressure P above the ambient P0 in the pores (porosity phi) of
 * the grains moving with the velocity field u, with the Carman-Kozeny
 * permeability kappa(phi) = d^2 phi^3/(180 (1 - phi)^2), on a regular grid
 * of cells that covers a tube along z (axis x = y = 0, inlet at z = 0,
 * outlet at z = length) and, below the inlet, the part z >= start of the
 * feed column pushed into it: the gas is fed at the lower end of the grid
 * and flows through the packed column into the tube.
 *
 * Discretisation (finite volumes): P and phi at the cell centres, u and kappa
 * on the faces (staggered).  The circular cross-section enters through the
 * fraction of each cell and each face that lies inside the tube.  A step of
 * length dt is split into the explicit source step (grain flux, the inlet
 * source and the outlet sink of the superficial velocity v_s) and
 * Crank-Nicolson diffusion along x, then y, then z, each one tridiagonal
 * system (GSL) with the tube wall and the tube ends closed (no flux).
 * Particles and grid exchange through tent (cloud-in-cell) weights:
 * 1 - phi_j = sum_i (V_i/V_cell) F(x_i - x_j); the drag on particle i is
 * -V_i grad P / (1 - phi) with grad P and phi interpolated with the same
 * weights. */
#ifndef MIMAS_SIM_GAS_H
#define MIMAS_SIM_GAS_H

#include <stddef.h>

#include "dem.h"
#include "error.h"

typedef struct sim_gas_params {
    double radius, length;   /* the tube, m */
    size_t across, axial;    /* cells across the tube (in x and in y) and along it */
    double P0;               /* ambient pressure, Pa */
    double eta;              /* (effective) gas viscosity, Pa s */
    double v_s;              /* superficial gas velocity fed at the inlet, m/s */
    double d;                /* grain diameter of the permeability law, m */
    double theta;            /* time weighting of the diffusion: 0.5 Crank-Nicolson, 1 implicit */
    double start;            /* lower end of the grid along z, <= 0 (0: the inlet) */
} sim_gas_params;

/* Values on the faces normal to one direction: the face grid has one node
 * more than the cells along that direction. */
typedef struct sim_gas_faces {
    size_t m[3];             /* nodes per direction */
    double *fraction;        /* fraction of the face inside the tube */
    double *cv_fraction;     /* fraction of the face's control volume inside the tube */
    double *phi, *u;         /* porosity and grain velocity (this component) deposited there */
    double *kappa;           /* permeability, m^2 (0 on the closed boundary faces) */
    double *grad;            /* pressure gradient along the direction, Pa/m (0 on the boundary) */
} sim_gas_faces;

typedef struct sim_gas {
    sim_gas_params p;
    size_t n[3];             /* cells nx, ny, nz */
    double lo[3], h[3];      /* lower corner of cell (0,0,0) and spacing */
    double *fraction;        /* fraction of each cell inside the tube (cross-section) */
    double *pressure;        /* P - P0, Pa; cell index i + nx (j + ny k) */
    double *porosity;        /* deposited porosity (1 where no grains) */
    sim_gas_faces f[3];
    double layer_volume;     /* tube volume of one layer of cells (the source volume V_s) */
    double *scratch;         /* 5 x cells: the tridiagonal systems */
    double *solid;           /* cells: deposited solid volume */
    /* per direction d: the cells in the order of the lines along d, and per
     * cell its face nodes below and above along d (fixed at init) */
    size_t *line_order[3], *face_below[3], *face_above[3];
    /* the 1-d tent weights of each particle at the last deposit, for
     * sim_gas_drag_held at the same positions */
    struct sim_gas_tents *tents;
    size_t tents_cap, tents_n;
} sim_gas;

int sim_gas_init(sim_gas *g, const sim_gas_params *p, mimas_error *err);
void sim_gas_free(sim_gas *g);

/* Permeability of the grains at porosity phi: Carman-Kozeny in series with
 * the Poiseuille permeability D^2/32 of the empty tube (so that an empty
 * tube has a finite, small resistance); phi is taken in [0.2, 1]. */
double sim_gas_permeability(const sim_gas *g, double phi);
/* Effective viscosity of a gas of viscosity eta0 at particle Reynolds
 * number Re: eta0 (1 + 0.1935 Re^0.6305) (Strauß 2005, eq. 3.67, after
 * Clift; meant for 20 < Re < 260); Re = 0 gives eta0. */
double sim_gas_effective_viscosity(double eta0, double re);

/* Particle -> grid: the porosity of the cells and the porosity and grain
 * velocity on the faces, from the particles on the grid (start <= z <
 * length), the feed column's included. */
void sim_gas_deposit(sim_gas *g, const dem_system *s);
/* Permeabilities from the face porosities (after a deposit, or after the
 * face porosities were set directly). */
void sim_gas_update_permeability(sim_gas *g);
/* One gas step of length dt: the source step (grain flux with the grains
 * entering the grid's lower end with velocity inlet_u, the inlet source and outlet
 * sink of v_s), then Crank-Nicolson diffusion along x, y and z.  Finally the
 * pressure is shifted so that the outlet layer is at 0 (the equation does
 * not change under a constant shift; the outlet is open to the ambient). */
void sim_gas_step(sim_gas *g, double dt, double inlet_u);
/* The diffusion part alone (no sources, no shift): for tests. */
void sim_gas_diffuse(sim_gas *g, double dt);
/* Grid -> particles: adds the drag -V grad P/(1 - phi) to the free particles
 * on the grid. */
void sim_gas_drag(const sim_gas *g, dem_system *s);
/* The same drag, written into held[k] (0 for the particles it does not act
 * on), with the weights kept by the last sim_gas_deposit: call it with the
 * positions of that deposit.  The numbers are those of sim_gas_drag. */
void sim_gas_drag_held(const sim_gas *g, const dem_system *s, double (*held)[3]);
/* Superficial (Darcy) gas velocity -kappa grad P/eta at the cell centres:
 * the mean of the fluxes through the two faces along each axis. */
void sim_gas_velocity(const sim_gas *g, double (*v)[3]);
size_t sim_gas_cells(const sim_gas *g);
/* Index of cell (i, j, k). */
static inline size_t sim_gas_index(const sim_gas *g, size_t i, size_t j, size_t k)
{
    return i + g->n[0] * (j + g->n[1] * k);
}

/* Area of the disk x^2 + y^2 <= r^2 inside the rectangle [x0,x1] x [y0,y1]
 * (closed form). */
double sim_disk_rect_area(double r, double x0, double x1, double y0, double y1);

#endif
