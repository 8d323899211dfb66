/* Scenario files (INI, parsed with libinih): one table of keys drives
 * parsing, range checks, --print-defaults and the documentation. */
#include <config.h>

#include "scenario.h"

#include <errno.h>
#include <ini.h>
#include <stdarg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

enum { K_REAL, K_INT, K_BOOL, K_CHOICE };
/* which scenario types a key applies to */
enum { S_RING = 1 << SIM_RINGSHEAR, S_BOX = 1 << SIM_BOX, S_PULL = 1 << SIM_PULLOFF,
       S_TUBE = 1 << SIM_PLUGTUBE, S_ALL = S_RING | S_BOX | S_PULL | S_TUBE };
/* range flags */
enum { R_MIN_OPEN = 1, R_NO_MAX = 2 };

typedef struct key_desc {
    const char *section, *name;
    int kind;
    size_t offset;            /* in sim_scenario, or in sim_contact_params for [contact] */
    double min, max;
    int range;
    const char *choices;      /* K_CHOICE: "a|b|c", value = index */
    const char *unit, *meaning;
    int scenarios;
} key_desc;

#define SC(f) offsetof(sim_scenario, f)
#define CP(f) offsetof(sim_contact_params, f)
#define BIG 0, R_NO_MAX

static const key_desc keys[] = {
    {"scenario", "type", K_CHOICE, SC(type), 0, 0, 0, "ringshear|box|pulloff|plugtube", "",
     "the scenario: split-bottom ring shear cell, periodic box, liquid-bridge pull-off, "
     "plug conveying in a tube", S_ALL},
    {"scenario", "seed", K_INT, SC(seed), 0, 2147483647.0, 0, NULL, "",
     "seed of the random numbers (sizes, insertion, velocities)", S_ALL},
    {"run", "dt", K_REAL, SC(dt), 0, BIG, NULL, "s",
     "time step (0: t_c/50 of the stiffest linear pair)", S_ALL},
    {"run", "dt_guard", K_BOOL, SC(dt_guard), 0, 1, 0, NULL, "",
     "refuse dt > t_c/50 of the stiffest linear pair (docs/theory.md §3)", S_ALL},
    {"run", "skin", K_REAL, SC(skin), 0, BIG | R_MIN_OPEN, NULL, "m",
     "Verlet-list skin; lists are rebuilt when a particle moved more than skin/2", S_ALL},
    {"run", "gravity_x", K_REAL, SC(gravity[0]), -1e6, 1e6, 0, NULL, "m s-2", "gravity, x",
     S_RING | S_BOX | S_PULL},
    {"run", "gravity_y", K_REAL, SC(gravity[1]), -1e6, 1e6, 0, NULL, "m s-2", "gravity, y",
     S_RING | S_BOX | S_PULL},
    {"run", "gravity_z", K_REAL, SC(gravity[2]), -1e6, 1e6, 0, NULL, "m s-2", "gravity, z",
     S_RING | S_BOX | S_PULL},
    {"run", "output_every", K_INT, SC(output_every), 1, 1e15, 0, NULL, "steps",
     "write a frame (particles, contacts, wall contacts) every this many steps", S_ALL},
    {"run", "checkpoint_every", K_INT, SC(checkpoint_every), 0, 1e15, 0, NULL, "steps",
     "write the checkpoint for --resume every this many steps (0: first frame, then at most once a minute)", S_ALL},
    {"run", "output_settle", K_BOOL, SC(output_settle), 0, 1, 0, NULL, "",
     "also write frames while the packing settles (ringshear)", S_RING},
    {"particles", "diameter", K_REAL, SC(diameter), 0, BIG | R_MIN_OPEN, NULL, "m",
     "mean particle diameter d (before coarse graining)", S_ALL},
    {"particles", "diameter_spread", K_REAL, SC(diameter_spread), 0, 0.5, 0, NULL, "",
     "diameters uniform in d (1 +- spread)", S_RING | S_BOX},
    {"particles", "density", K_REAL, SC(density), 0, BIG | R_MIN_OPEN, NULL, "kg m-3",
     "particle material density", S_ALL},
    {"particles", "liquid_content", K_REAL, SC(liquid_content), 0, 0.5, 0, NULL, "",
     "liquid mass per particle mass D; > 0 switches liquid bridges on (docs/theory.md §2.4)", S_ALL},
    {"particles", "liquid_density", K_REAL, SC(liquid_density), 0, BIG | R_MIN_OPEN, NULL,
     "kg m-3", "density of the liquid", S_ALL},
    {"particles", "coarse_grain", K_REAL, SC(coarse_grain), 1, 1000, 0, NULL, "",
     "coarse-grain factor alpha: radii x alpha, parameters scaled (docs/theory.md §2.5)", S_ALL},
    {"particles", "rotation", K_BOOL, SC(rotation), 0, 1, 0, NULL, "",
     "integrate the rotation of the particles (no: angular velocities stay 0)", S_ALL},
    {"contact", "model", K_CHOICE, CP(model), 0, 0, 0, "linear|hertz", "",
     "normal and tangential law: linear spring-dashpot or Hertz-Mindlin (docs/theory.md §2.1, §2.2)", S_ALL},
    {"contact", "stiffness_normal", K_REAL, CP(k_n), 0, BIG, NULL, "N m-1", "k_n (linear)", S_ALL},
    {"contact", "stiffness_tangential", K_REAL, CP(k_t), 0, BIG, NULL, "N m-1",
     "k_t of the tangential history spring (linear)", S_ALL},
    {"contact", "damping_normal", K_REAL, CP(gamma_n), 0, BIG, NULL, "N s m-1",
     "gamma_n (linear; ignored when restitution > 0)", S_ALL},
    {"contact", "damping_tangential", K_REAL, CP(gamma_t), 0, BIG, NULL, "N s m-1",
     "gamma_t (linear)", S_ALL},
    {"contact", "restitution", K_REAL, CP(restitution), 0, 1, 0, NULL, "",
     "coefficient of restitution e; 0: use damping_normal (linear); Hertz needs e > 0", S_ALL},
    {"contact", "normal_clip", K_BOOL, CP(normal_clip), 0, 1, 0, NULL, "",
     "normal force never attractive: max(0, k delta - gamma v_n); restitution at the end of "
     "the repulsion (Strauß 2005, eq. 3.13-3.14; docs/theory.md §2.1)", S_ALL},
    {"contact", "youngs_modulus", K_REAL, CP(youngs_modulus), 0, BIG, NULL, "Pa",
     "E (Hertz, JKR)", S_ALL},
    {"contact", "poisson", K_REAL, CP(poisson), 0, 0.5, 0, NULL, "", "Poisson ratio nu", S_ALL},
    {"contact", "friction", K_REAL, CP(friction), 0, BIG, NULL, "", "Coulomb friction mu", S_ALL},
    {"contact", "rolling_friction", K_REAL, CP(rolling_friction), 0, BIG, NULL, "m",
     "rolling friction length mu_r (docs/theory.md §2.3)", S_ALL},
    {"contact", "cohesion_energy", K_REAL, CP(cohesion_energy), 0, BIG, NULL, "J m-2",
     "JKR-type cohesion: work of adhesion w = twice the surface energy (Bierwisch 2009, eq. 2.4; docs/theory.md §2.4); needs youngs_modulus", S_ALL},
    {"contact", "surface_tension", K_REAL, CP(surface_tension), 0, BIG, NULL, "N m-1",
     "surface tension of the liquid bridges", S_ALL},
    {"contact", "contact_angle", K_REAL, CP(contact_angle), 0, 90, 0, NULL, "deg",
     "contact angle theta of the liquid bridges", S_ALL},
    {"contact", "resting_overlap", K_REAL, CP(resting_overlap), 0, 0.5, 0, NULL, "",
     "> 0: stiffness_normal = m g/(resting_overlap d): a particle resting on a wall overlaps "
     "this fraction of d (linear; m, d of the particles)", S_ALL},
    {"ringshear", "r_in", K_REAL, SC(r_in), 0, BIG | R_MIN_OPEN, NULL, "m",
     "radius of the inner (static) cylinder", S_RING},
    {"ringshear", "r_split", K_REAL, SC(r_split), 0, BIG | R_MIN_OPEN, NULL, "m",
     "split radius: the bottom rotates outside it", S_RING},
    {"ringshear", "r_out", K_REAL, SC(r_out), 0, BIG | R_MIN_OPEN, NULL, "m",
     "radius of the outer cylinder (rotates with the outer bottom)", S_RING},
    {"ringshear", "fill_height", K_REAL, SC(fill_height), 0, BIG | R_MIN_OPEN, NULL, "m",
     "fill height H; the particle count follows from it at solid fraction 0.6", S_RING},
    {"ringshear", "count", K_INT, SC(count), 0, 1e9, 0, NULL, "",
     "number of particles (0: from fill_height)", S_RING},
    {"ringshear", "omega", K_REAL, SC(omega), -1e6, 1e6, 0, NULL, "rad s-1",
     "angular velocity Omega of the outer bottom and the outer cylinder", S_RING},
    {"ringshear", "rough_bottom", K_BOOL, SC(rough_bottom), 0, 1, 0, NULL, "",
     "glue a layer of particles (type 2) onto the bottom", S_RING},
    {"ringshear", "settle_time", K_REAL, SC(settle_time), 0, BIG, NULL, "s",
     "time the inserted particles settle before the bottom turns", S_RING},
    {"ringshear", "shear_time", K_REAL, SC(shear_time), 0, BIG, NULL, "s",
     "simulated time of shearing", S_RING},
    {"box", "size_x", K_REAL, SC(box_size[0]), 0, BIG | R_MIN_OPEN, NULL, "m", "box edge x", S_BOX},
    {"box", "size_y", K_REAL, SC(box_size[1]), 0, BIG | R_MIN_OPEN, NULL, "m", "box edge y", S_BOX},
    {"box", "size_z", K_REAL, SC(box_size[2]), 0, BIG | R_MIN_OPEN, NULL, "m", "box edge z", S_BOX},
    {"box", "periodic_x", K_BOOL, SC(box_periodic[0]), 0, 1, 0, NULL, "",
     "periodic in x (else plane walls)", S_BOX},
    {"box", "periodic_y", K_BOOL, SC(box_periodic[1]), 0, 1, 0, NULL, "",
     "periodic in y (else plane walls)", S_BOX},
    {"box", "periodic_z", K_BOOL, SC(box_periodic[2]), 0, 1, 0, NULL, "",
     "periodic in z (else plane walls)", S_BOX},
    {"box", "count", K_INT, SC(box_count), 1, 1e9, 0, NULL, "", "number of particles", S_BOX},
    {"box", "speed", K_REAL, SC(box_speed), 0, BIG, NULL, "m s-1",
     "initial speeds: random directions, magnitudes uniform in [0, speed]", S_BOX},
    {"box", "time", K_REAL, SC(box_time), 0, BIG, NULL, "s", "simulated time", S_BOX},
    {"pulloff", "speed", K_REAL, SC(pull_speed), 0, BIG | R_MIN_OPEN, NULL, "m s-1",
     "separation speed of the two particles", S_PULL},
    {"pulloff", "distance", K_REAL, SC(pull_distance), 0, BIG | R_MIN_OPEN, NULL, "",
     "final gap in units of the particle radius", S_PULL},
    {"plugtube", "orientation", K_CHOICE, SC(tube_orientation), 0, 0, 0, "vertical|horizontal",
     "", "the tube runs along z; vertical: gravity along -z (against the flow), horizontal: "
     "along -x", S_TUBE},
    {"plugtube", "gravity", K_REAL, SC(tube_gravity), 0, 1e6, 0, NULL, "m s-2",
     "magnitude of gravity", S_TUBE},
    {"plugtube", "diameter", K_REAL, SC(tube_diameter), 0, BIG | R_MIN_OPEN, NULL, "m",
     "inner diameter D_t of the tube", S_TUBE},
    {"plugtube", "length", K_REAL, SC(tube_length), 0, BIG | R_MIN_OPEN, NULL, "m",
     "length L_t of the tube (inlet z = 0, outlet z = L_t; grains are removed beyond it)",
     S_TUBE},
    {"plugtube", "mass_flow", K_REAL, SC(mass_flow), 0, BIG, NULL, "kg s-1",
     "grain mass flow of the feed: the packed feed column is pushed in at the speed that "
     "gives it (0: use feed_speed)", S_TUBE},
    {"plugtube", "feed_speed", K_REAL, SC(feed_speed), 0, BIG, NULL, "m s-1",
     "speed of the feed column (used when mass_flow = 0; both 0: no feed)", S_TUBE},
    {"plugtube", "feed_porosity", K_REAL, SC(feed_porosity), 0.26, 0.95, 0, NULL, "",
     "porosity of the packed feed column", S_TUBE},
    {"plugtube", "fill_count", K_INT, SC(fill_count), 0, 1e9, 0, NULL, "",
     "particles placed in the tube at the start, from the outlet end on (e.g. a settling "
     "sphere)", S_TUBE},
    {"plugtube", "time", K_REAL, SC(tube_time), 0, BIG, NULL, "s", "simulated time", S_TUBE},
    {"gas", "model", K_CHOICE, SC(gas_model), 0, 0, 0, "pressure|fluid-at-rest|none", "",
     "the gas: the gas-pressure model of plug conveying, a fluid at rest (drag laws, "
     "buoyancy), or none", S_TUBE},
    {"gas", "superficial_velocity", K_REAL, SC(gas_velocity), 0, BIG, NULL, "m s-1",
     "superficial gas velocity v_s fed at the inlet and taken out at the outlet (pressure)",
     S_TUBE},
    {"gas", "pressure", K_REAL, SC(gas_pressure), 0, BIG | R_MIN_OPEN, NULL, "Pa",
     "ambient pressure P0 (pressure)", S_TUBE},
    {"gas", "viscosity", K_REAL, SC(gas_viscosity), 0, BIG | R_MIN_OPEN, NULL, "Pa s",
     "dynamic viscosity eta0 of the gas or fluid", S_TUBE},
    {"gas", "reynolds", K_REAL, SC(gas_reynolds), 0, 1e6, 0, NULL, "",
     "particle Reynolds number of the effective viscosity eta = eta0 (1 + 0.1935 Re^0.6305) "
     "(pressure; 0: eta = eta0)", S_TUBE},
    {"gas", "cells_across", K_INT, SC(gas_cells_across), 1, 64, 0, NULL, "",
     "gas cells across the tube, in x and in y (pressure)", S_TUBE},
    {"gas", "cell_length", K_REAL, SC(gas_cell_length), 0, BIG | R_MIN_OPEN, NULL, "m",
     "length of the gas cells along the tube (rounded to fit the tube; pressure)", S_TUBE},
    {"gas", "theta", K_REAL, SC(gas_theta), 0.5, 1, 0, NULL, "",
     "time weighting of the diffusion steps: 0.5 Crank-Nicolson, 1 implicit Euler "
     "(pressure; docs/simulate.md)", S_TUBE},
    {"gas", "every", K_INT, SC(gas_every), 1, 1e6, 0, NULL, "steps",
     "advance the gas every this many steps (pressure; docs/simulate.md)", S_TUBE},
    {"gas", "fluid_density", K_REAL, SC(fluid_density), 0, BIG, NULL, "kg m-3",
     "density rho_f of the fluid at rest (fluid-at-rest)", S_TUBE},
    {"gas", "drag_law", K_CHOICE, SC(drag_law), 0, 0, 0,
     "stokes|schiller-naumann|haider-levenspiel", "", "drag coefficient (fluid-at-rest)",
     S_TUBE},
    {"gas", "wall_factor", K_CHOICE, SC(wall_factor), 0, 0, 0, "none|francis|ataide", "",
     "correction of the drag for the tube wall (fluid-at-rest)", S_TUBE},
    {"gas", "buoyancy", K_BOOL, SC(buoyancy), 0, 1, 0, NULL, "",
     "buoyancy -rho_f V g (fluid-at-rest)", S_TUBE},
};
#define NKEYS (sizeof keys / sizeof keys[0])

static const char *const type_names[] = {"ringshear", "box", "pulloff", "plugtube"};

int sim_scenario_type(const char *name)
{
    for (int k = 0; k < SIM_SCENARIO_TYPES; k++)
        if (strcmp(name, type_names[k]) == 0)
            return k;
    return -1;
}

static void contact_defaults(sim_contact_params *c)
{
    /* the ring shear cell of Uhlig (2012, Table 4.2; docs/theory.md §7.1) */
    *c = (sim_contact_params){.model = SIM_LINEAR, .k_n = 110, .k_t = 12, .gamma_n = 2e-3,
                              .gamma_t = 0.5e-3, .restitution = 0, .normal_clip = 1,
                              .youngs_modulus = 0,
                              .poisson = 0.3, .friction = 0.01, .rolling_friction = 0,
                              .cohesion_energy = 0, .surface_tension = 0.072,
                              .contact_angle = 0};
}

void sim_scenario_defaults(sim_scenario *s, int type)
{
    memset(s, 0, sizeof *s);
    s->type = type;
    s->seed = 1;
    s->dt = 5e-6;
    s->dt_guard = 1;
    s->skin = 2e-4;
    s->gravity[2] = type == SIM_RINGSHEAR ? -9.81 : 0;
    s->output_every = type == SIM_PULLOFF ? 20 : 20000;
    s->diameter = 0.002;
    s->diameter_spread = type == SIM_RINGSHEAR ? 0.1 : 0;
    s->density = 2000;
    s->liquid_density = 1000;
    s->liquid_content = type == SIM_PULLOFF ? 0.01 : 0;
    s->coarse_grain = 1;
    s->rotation = 1;
    contact_defaults(&s->contact_all);
    for (int a = 0; a < SIM_MAX_TYPES; a++)
        for (int b = 0; b < SIM_MAX_TYPES; b++)
            s->contact[a][b] = s->contact_all;
    /* the split-bottom cell of Uhlig (2012; docs/theory.md §7.1) */
    s->r_in = 0.0147;
    s->r_split = 0.085;
    s->r_out = 0.11;
    s->fill_height = 0.038;
    s->omega = 2 * M_PI * 0.01;
    s->rough_bottom = 1;
    s->settle_time = 0.5;
    s->shear_time = 10;
    for (int d = 0; d < 3; d++) {
        s->box_size[d] = 0.02;
        s->box_periodic[d] = 1;
    }
    s->box_count = 100;
    s->box_speed = 0.1;
    s->box_time = 0.1;
    s->pull_speed = 1e-3;
    s->pull_distance = 0.5;
    /* plug conveying: the standard set of Strauss (2005, App. A) */
    s->tube_orientation = SIM_TUBE_VERTICAL;
    s->tube_gravity = 9.81;
    s->tube_diameter = 0.007;
    s->tube_length = 0.525;
    s->tube_time = 20;
    s->mass_flow = 6.9167e-4;     /* 2.49 kg/h */
    s->feed_speed = 0;
    s->feed_porosity = 0.506;
    s->gas_model = SIM_GAS_PRESSURE;
    s->gas_velocity = 1;
    s->gas_pressure = 101325;
    s->gas_viscosity = 1.82e-5;   /* air; Re = 65 gives the effective 0.0672 cP */
    s->gas_reynolds = 65;
    s->gas_cells_across = 1;
    s->gas_cell_length = 0.0035;
    s->gas_every = 10;
    s->gas_theta = 1;
    s->fluid_density = 1.2;
    s->drag_law = 1;              /* schiller-naumann */
    s->wall_factor = 0;
    s->buoyancy = 1;
    if (type == SIM_PLUGTUBE) {
        s->dt = 0;                /* t_c/50 */
        s->diameter = 0.0014;
        s->density = 937;
        s->skin = 0.3 * 0.0014;
        s->output_every = 2000;
        sim_contact_params *c = &s->contact_all;
        c->friction = 0.5;
        c->restitution = 0.5;
        c->normal_clip = 1;
        c->resting_overlap = 0.001;
        /* Coulomb sliding regularised by viscous friction below the limit
         * (Strauss 2005, eq. 3.22): no tangential spring */
        c->k_t = 0;
        c->gamma_t = 1e-3;
        for (int a = 0; a < SIM_MAX_TYPES; a++)
            for (int b = 0; b < SIM_MAX_TYPES; b++)
                s->contact[a][b] = s->contact_all;
    }
}

/* ---- parsing ------------------------------------------------------------- */

typedef struct override {
    int a, b;
    const key_desc *key;
    double value;
} override;

typedef struct parse_ctx {
    sim_scenario *s;
    sim_contact_params all;     /* [contact] */
    override *ov;
    size_t nov;
    int only_type;              /* first pass: look for [scenario] type only */
    int found_type, has_type;
    char msg[MIMAS_ERROR_MSG_MAX - 64];
    int failed;
} parse_ctx;

/* Records the first error of the file (inih goes on and reports its line). */
static int fail(parse_ctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(parse_ctx *c, const char *fmt, ...)
{
    if (!c->failed) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(c->msg, sizeof c->msg, fmt, ap);
        va_end(ap);
    }
    c->failed = 1;
    return 0;
}

/* "contact", "contact 1-2", "contact wall-1": *a, *b types (-1: all) */
static int contact_section(const char *section, int *a, int *b)
{
    if (strcmp(section, "contact") == 0) {
        *a = *b = -1;
        return 1;
    }
    if (strncmp(section, "contact ", 8) != 0)
        return 0;
    char x[16], y[16], extra;
    if (sscanf(section + 8, "%15[^-]-%15s%c", x, y, &extra) != 2)
        return -1;
    const char *t[2] = {x, y};
    int v[2];
    for (int k = 0; k < 2; k++) {
        char *end;
        long n = strcmp(t[k], "wall") == 0 ? 0 : strtol(t[k], &end, 10);
        if (strcmp(t[k], "wall") != 0 && (*end || end == t[k] || n < 1 || n >= SIM_MAX_TYPES))
            return -1;
        v[k] = (int)n;
    }
    *a = v[0];
    *b = v[1];
    return 1;
}

static int parse_value(const key_desc *k, const char *text, double *out)
{
    char *end;
    if (k->kind == K_BOOL) {
        if (!strcasecmp(text, "yes") || !strcasecmp(text, "true") || !strcmp(text, "1"))
            *out = 1;
        else if (!strcasecmp(text, "no") || !strcasecmp(text, "false") || !strcmp(text, "0"))
            *out = 0;
        else
            return -1;
        return 0;
    }
    if (k->kind == K_CHOICE) {
        const char *p = k->choices;
        for (int idx = 0; p && *p; idx++) {
            size_t len = strcspn(p, "|");
            if (strlen(text) == len && strncmp(p, text, len) == 0) {
                *out = idx;
                return 0;
            }
            p += len + (p[len] == '|');
        }
        return -1;
    }
    double v = strtod(text, &end);
    if (end == text || *end || !isfinite(v))
        return -1;
    if (k->kind == K_INT && v != floor(v))
        return -1;
    *out = v;
    return 0;
}

static int in_range(const key_desc *k, double v)
{
    if (k->kind != K_REAL && k->kind != K_INT)
        return 1;
    if ((k->range & R_MIN_OPEN) ? v <= k->min : v < k->min)
        return 0;
    return (k->range & R_NO_MAX) || v <= k->max;
}

static void store(void *base, const key_desc *k, double v)
{
    char *p = (char *)base + k->offset;
    if (k->kind == K_REAL)
        *(double *)p = v;
    else if (k->kind == K_INT)
        *(long *)p = (long)v;
    else
        *(int *)p = (int)v;
}

static double load(const void *base, const key_desc *k)
{
    const char *p = (const char *)base + k->offset;
    if (k->kind == K_REAL)
        return *(const double *)p;
    if (k->kind == K_INT)
        return (double)*(const long *)p;
    return *(const int *)p;
}

static int handler(void *user, const char *section, const char *name, const char *value)
{
    parse_ctx *c = user;
    if (c->only_type) {
        if (strcmp(section, "scenario") == 0 && strcmp(name, "type") == 0) {
            int t = sim_scenario_type(value);
            if (t < 0)
                return fail(c, "[scenario] type must be ringshear, box, pulloff or plugtube, "
                               "not '%s'", value);
            c->found_type = t;
            c->has_type = 1;
        }
        return 1;
    }
    int a = -1, b = -1, cs = contact_section(section, &a, &b);
    if (cs < 0)
        return fail(c, "bad section [%s]: use [contact], [contact A-B] or [contact wall-B] "
                       "with types 1..3", section);
    const char *sec = cs ? "contact" : section;
    const key_desc *k = NULL;
    int section_known = 0;
    for (size_t m = 0; m < NKEYS; m++) {
        if (strcmp(keys[m].section, sec) != 0)
            continue;
        section_known = 1;
        if (strcmp(keys[m].name, name) == 0)
            k = &keys[m];
    }
    if (!section_known)
        return fail(c, "unknown section [%s]", section);
    if (!k)
        return fail(c, "unknown key '%s' in [%s]", name, section);
    if (!(k->scenarios & (1 << c->s->type)))
        return fail(c, "key '%s' of [%s] does not apply to scenario %s", name, section,
                    type_names[c->s->type]);
    double v;
    if (parse_value(k, value, &v)) {
        if (k->kind == K_CHOICE)
            return fail(c, "%s must be one of %s, not '%s'", name, k->choices, value);
        return fail(c, "%s: '%s' is not a %s", name, value,
                    k->kind == K_BOOL ? "yes/no value" : k->kind == K_INT ? "whole number"
                                                                          : "number");
    }
    if (!in_range(k, v)) {
        char range[128];
        if (k->range & R_NO_MAX)
            snprintf(range, sizeof range, "%s %g", (k->range & R_MIN_OPEN) ? ">" : ">=", k->min);
        else
            snprintf(range, sizeof range, "in [%g, %g]", k->min, k->max);
        return fail(c, "%s = %s is out of range (must be %s)", name, value, range);
    }
    if (!cs) {
        store(c->s, k, v);
    } else if (a < 0) {
        store(&c->all, k, v);
    } else {
        override *grown = realloc(c->ov, (c->nov + 1) * sizeof *grown);
        if (!grown)
            return fail(c, "out of memory for the [contact A-B] overrides");
        c->ov = grown;
        c->ov[c->nov++] = (override){a, b, k, v};
    }
    return 1;
}

typedef struct string_reader {
    const char *p;
} string_reader;

static char *read_line(char *buf, int size, void *stream)
{
    string_reader *r = stream;
    if (!*r->p)
        return NULL;
    int n = 0;
    while (n < size - 1 && r->p[0]) {
        char ch = *r->p++;
        buf[n++] = ch;
        if (ch == '\n')
            break;
    }
    buf[n] = 0;
    return buf;
}

static int run_parse(parse_ctx *c, const char *path, const char *text)
{
    if (text) {
        string_reader r = {text};
        return ini_parse_stream(read_line, &r, handler, c);
    }
    return ini_parse(path, handler, c);
}

static int load_any(sim_scenario *s, const char *path, const char *text, const char *name,
                    mimas_error *err)
{
    parse_ctx c = {.s = s, .only_type = 1, .found_type = SIM_RINGSHEAR};
    int line = run_parse(&c, path, text);
    if (line < 0)
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot read the scenario file", name);
    if (line == 0 && !c.has_type)
        return mimas_error_set(err, MIMAS_EDATA, "%s: no [scenario] type (ringshear, box or "
                               "pulloff): not a scenario file (see mimas simulate "
                               "--print-defaults)", name);
    if (line == 0) {
        /* second pass: the defaults of the scenario type, then the file */
        sim_scenario_defaults(s, c.found_type);
        c.only_type = 0;
        c.all = s->contact[1][1];
        line = run_parse(&c, path, text);
    }
    if (line > 0) {
        free(c.ov);
        if (!c.failed)
            snprintf(c.msg, sizeof c.msg, "syntax error (expected [section] or key = value)");
        return mimas_error_set(err, MIMAS_EDATA, "%s:%d: %s", name, line, c.msg);
    }
    s->contact_all = c.all;
    for (int a = 0; a < SIM_MAX_TYPES; a++)
        for (int b = 0; b < SIM_MAX_TYPES; b++)
            s->contact[a][b] = c.all;
    for (size_t m = 0; m < c.nov; m++) {
        store(&s->contact[c.ov[m].a][c.ov[m].b], c.ov[m].key, c.ov[m].value);
        store(&s->contact[c.ov[m].b][c.ov[m].a], c.ov[m].key, c.ov[m].value);
    }
    free(c.ov);
    return sim_scenario_check(s, name, err);
}

int sim_scenario_load(sim_scenario *s, const char *path, mimas_error *err)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return mimas_error_set(err, MIMAS_EDATA, "%s: cannot open the scenario file: %s", path,
                               strerror(errno));
    if (S_ISDIR(st.st_mode))
        return mimas_error_set(err, MIMAS_EDATA, "%s: is a directory, not a scenario file", path);
    return load_any(s, path, NULL, path, err);
}

int sim_scenario_load_string(sim_scenario *s, const char *text, const char *name,
                             mimas_error *err)
{
    return load_any(s, NULL, text, name, err);
}

/* The most steps a run may have (and still count them in int64 with room). */
#define MAX_STEPS 1e15

/* A simulated time in steps of dt: refuses a count that would overflow (a
 * time of 1e300 s) or that no machine runs. */
static int check_steps(const char *name, const char *section, const char *key, double time,
                       double dt, mimas_error *err)
{
    if (dt == 0)
        return MIMAS_OK; /* dt = 0: t_c/50, checked once it is known (sim_setup) */
    double steps = time / dt;
    if (!(steps <= MAX_STEPS))
        return mimas_error_set(err, MIMAS_EDATA, "%s: [%s] %s = %g s is %g steps of dt = %g s, "
                               "more than %g", name, section, key, time, steps, dt, MAX_STEPS);
    return MIMAS_OK;
}

int sim_scenario_check(const sim_scenario *s, const char *name, mimas_error *err)
{
    int rc = MIMAS_OK;
    if (s->type == SIM_RINGSHEAR)
        rc = check_steps(name, "ringshear", "settle_time + shear_time",
                         s->settle_time + s->shear_time, s->dt, err);
    else if (s->type == SIM_BOX)
        rc = check_steps(name, "box", "time", s->box_time, s->dt, err);
    else if (s->type == SIM_PLUGTUBE)
        rc = check_steps(name, "plugtube", "time", s->tube_time, s->dt, err);
    else
        rc = check_steps(name, "pulloff", "distance x radius / speed",
                         s->pull_distance * s->diameter * s->coarse_grain / 2 / s->pull_speed,
                         s->dt, err);
    if (rc)
        return rc;
    if (s->type == SIM_RINGSHEAR) {
        if (!(s->r_in < s->r_split && s->r_split < s->r_out))
            return mimas_error_set(err, MIMAS_EDATA, "%s: [ringshear] needs r_in < r_split < "
                                   "r_out", name);
        double dmax = s->diameter * s->coarse_grain * (1 + s->diameter_spread);
        if (s->r_out - s->r_in < 3 * dmax)
            return mimas_error_set(err, MIMAS_EDATA, "%s: [ringshear] the gap r_out - r_in is "
                                   "narrower than three particle diameters", name);
    }
    if (s->type == SIM_PLUGTUBE) {
        double d = s->diameter * s->coarse_grain;
        if (s->mass_flow > 0 && s->feed_speed > 0)
            return mimas_error_set(err, MIMAS_EDATA, "%s: [plugtube] set either mass_flow or "
                                   "feed_speed (the other 0)", name);
        if (s->tube_diameter < 2.5 * d)
            return mimas_error_set(err, MIMAS_EDATA, "%s: [plugtube] the tube diameter must be "
                                   "at least 2.5 particle diameters", name);
        if (s->tube_length < 10 * d)
            return mimas_error_set(err, MIMAS_EDATA, "%s: [plugtube] the tube must be at least "
                                   "10 particle diameters long", name);
    }
    for (int a = 0; a < SIM_MAX_TYPES; a++)
        for (int b = a; b < SIM_MAX_TYPES; b++) {
            const sim_contact_params *c = &s->contact[a][b];
            const char *what = NULL;
            if (c->model == SIM_HERTZ && !(c->youngs_modulus > 0))
                what = "model = hertz needs youngs_modulus > 0";
            else if (c->model == SIM_HERTZ && !(c->restitution > 0))
                what = "model = hertz needs restitution > 0";
            else if (c->model == SIM_LINEAR && !(c->k_n > 0) && !(c->resting_overlap > 0))
                what = "model = linear needs stiffness_normal > 0 (or resting_overlap > 0)";
            else if (c->model == SIM_LINEAR && c->restitution > 0 && c->normal_clip &&
                     c->restitution <= exp(-2))
                what = "with normal_clip = yes no damping gives a restitution below exp(-2) = "
                       "0.135 (set normal_clip = no)";
            else if (c->cohesion_energy > 0 && !(c->youngs_modulus > 0))
                what = "cohesion_energy > 0 needs youngs_modulus > 0";
            if (what)
                return mimas_error_set(err, MIMAS_EDATA, "%s: [contact] (types %d-%d): %s",
                                       name, a, b, what);
        }
    return MIMAS_OK;
}

/* ---- printing ------------------------------------------------------------ */

/* The word of a yes/no or choice key's value. */
static void word_of(const key_desc *k, double v, char *buf, size_t len)
{
    if (k->kind == K_BOOL) {
        snprintf(buf, len, "%s", v != 0 ? "yes" : "no");
        return;
    }
    const char *p = k->choices;
    for (int idx = 0; idx < (int)v; idx++)
        p += strcspn(p, "|") + 1;
    snprintf(buf, len, "%.*s", (int)strcspn(p, "|"), p);
}

static void print_value(FILE *out, const key_desc *k, double v)
{
    if (k->kind == K_BOOL || k->kind == K_CHOICE) {
        char word[64];
        word_of(k, v, word, sizeof word);
        fputs(word, out);
    } else if (k->kind == K_INT) {
        fprintf(out, "%.0f", v);
    } else {
        char buf[40];
        snprintf(buf, sizeof buf, "%.15g", v);
        if (strtod(buf, NULL) != v)
            snprintf(buf, sizeof buf, "%.17g", v);
        fputs(buf, out);
    }
}

/* text as "; " comment lines of at most width characters, broken at spaces */
static void print_comment(FILE *out, const char *text, size_t width)
{
    while (*text) {
        size_t n = strlen(text);
        if (n > width) {
            n = width;
            while (n > 0 && text[n] != ' ')
                n--;
            if (n == 0)
                n = strcspn(text, " ");
        }
        fprintf(out, "; %.*s\n", (int)n, text);
        text += n;
        text += strspn(text, " ");
    }
}

void sim_scenario_print(const sim_scenario *s, FILE *out)
{
    fprintf(out, "# mimas simulate scenario (%s); every key with its default.\n"
                 "# Per type pair: [contact A-B] or [contact wall-B] override [contact].\n",
            type_names[s->type]);
    const char *section = "";
    for (size_t m = 0; m < NKEYS; m++) {
        const key_desc *k = &keys[m];
        if (!(k->scenarios & (1 << s->type)))
            continue;
        if (strcmp(section, k->section) != 0) {
            section = k->section;
            fprintf(out, "\n[%s]\n", section);
        }
        const void *base = strcmp(section, "contact") == 0 ? (const void *)&s->contact[1][1]
                                                           : (const void *)s;
        char text[600];
        snprintf(text, sizeof text, "%s%s%s%s", k->meaning, *k->unit ? " (" : "", k->unit,
                 *k->unit ? ")" : "");
        /* INI readers limit the line (inih: 200 bytes): a long meaning goes
         * on comment lines of its own, before the key */
        int own_lines = strlen(k->name) + strlen(text) > 140;
        if (own_lines)
            print_comment(out, text, 90);
        fprintf(out, "%s = ", k->name);
        print_value(out, k, load(base, k));
        if (own_lines)
            fputc('\n', out);
        else
            fprintf(out, "    ; %s\n", text);
    }
}

void sim_scenario_print_doc(FILE *out)
{
    fputs("| section | key | unit | scenarios | meaning |\n|---|---|---|---|---|\n", out);
    for (size_t m = 0; m < NKEYS; m++) {
        const key_desc *k = &keys[m];
        fprintf(out, "| %s | %s | %s | ", k->section, k->name, k->unit);
        const char *sep = "";
        for (int t = 0; t < SIM_SCENARIO_TYPES; t++)
            if (k->scenarios & (1 << t)) {
                fprintf(out, "%s%s", sep, type_names[t]);
                sep = ", ";
            }
        fprintf(out, " | %s |\n", k->meaning);
    }
}

/* ---- run parameters ------------------------------------------------------ */

static int add_key(mimas_parameters *ps, const char *section, const key_desc *k, double v,
                   mimas_error *err)
{
    char word[64] = "";
    mimas_parameter_kind kind = k->kind == K_REAL  ? MIMAS_PARAM_REAL
                                : k->kind == K_INT ? MIMAS_PARAM_INTEGER
                                                   : MIMAS_PARAM_TEXT;
    if (kind == MIMAS_PARAM_TEXT)
        word_of(k, v, word, sizeof word);
    return mimas_parameters_add(ps, section, k->name, kind, v, word, k->unit, err);
}

int sim_scenario_parameters(const sim_scenario *s, mimas_parameters *ps, mimas_error *err)
{
    mimas_parameters_clear(ps);
    int rc = MIMAS_OK;
    for (size_t m = 0; !rc && m < NKEYS; m++) {
        const key_desc *k = &keys[m];
        if (!(k->scenarios & (1 << s->type)))
            continue;
        int contact = strcmp(k->section, "contact") == 0;
        rc = add_key(ps, k->section, k, load(contact ? (const void *)&s->contact_all
                                                     : (const void *)s, k), err);
    }
    /* the keys a [contact A-B] section sets to another value */
    for (int a = 0; !rc && a < SIM_MAX_TYPES; a++)
        for (int b = a > 0 ? a : 1; !rc && b < SIM_MAX_TYPES; b++) {
            char section[32];
            if (a == 0)
                snprintf(section, sizeof section, "contact wall-%d", b);
            else
                snprintf(section, sizeof section, "contact %d-%d", a, b);
            for (size_t m = 0; !rc && m < NKEYS; m++) {
                const key_desc *k = &keys[m];
                if (strcmp(k->section, "contact") != 0)
                    continue;
                double v = load(&s->contact[a][b], k);
                if (v != load(&s->contact_all, k))
                    rc = add_key(ps, section, k, v, err);
            }
        }
    return rc;
}
