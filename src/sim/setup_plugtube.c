/* The plugtube scenario: plug conveying in a tube (docs/simulate.md;
 * Strauß 2005, Ch. 5 and 6).  The tube runs along z with its axis through
 * x = y = 0, the inlet at z = 0 and the outlet at z = length; a horizontal
 * tube has gravity along -x instead of -z.  Below the inlet a packed feed
 * column (type 2, copies of one periodic block) moves up at the feed speed;
 * its grains are released at z = 0 and become type 1.  Grains beyond the
 * outlet (or fallen out below the inlet) are removed when the neighbour list
 * is rebuilt.  The gas is the gas-pressure model (gas.h; its grid covers the
 * tube and the part of the feed column just below the inlet), a fluid at
 * rest (drag.h) or none. */
#include <config.h>

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "drag.h"
#include "gas.h"
#include "setup.h"
#include "tube_feed.h"

struct sim_tube_run {
    double radius, length, particle_radius, density;
    /* feed: blocks k = 0, 1, ... of the column sit at z in [-(k+1) L_b, -k L_b) + shift */
    int feeding;
    double feed_speed, keep;     /* column kept at least `keep` below the inlet */
    sim_feed_block block;
    int64_t blocks;              /* added so far (checkpointed) */
    int motion;
    /* fluid */
    int model;
    long gas_every;
    double dt;
    sim_gas gas;
    sim_drag drag;
    uint8_t *drop;
    size_t drop_cap;
};

void sim_tube_free(sim_tube_run *t)
{
    if (!t)
        return;
    sim_feed_block_free(&t->block);
    if (t->model == SIM_GAS_PRESSURE)
        sim_gas_free(&t->gas);
    free(t->drop);
    free(t);
}

/* the next block of the column, glued to the feed motion */
static int add_block(sim_tube_run *t, dem_system *s, mimas_error *err)
{
    const sim_feed_block *b = &t->block;
    int rc = dem_reserve(s, s->n + b->n, err);
    if (rc)
        return rc;
    const dem_motion *mo = &s->motions[t->motion];
    double base = -(double)(t->blocks + 1) * b->length;
    for (size_t k = 0; k < b->n; k++) {
        double anchor[3] = {b->x[k][0], b->x[k][1], b->x[k][2] + base}, x[3];
        for (int q = 0; q < 3; q++)
            x[q] = anchor[q] + mo->shift[q];
        size_t p = dem_add_particle(s, 2, t->particle_radius, t->density, x);
        s->glued[p] = t->motion;
        memcpy(s->anchor[p], anchor, sizeof anchor);
        memcpy(s->x_ref[p], x, sizeof x);
        memcpy(s->v[p], mo->velocity, sizeof s->v[p]);
    }
    t->blocks++;
    return MIMAS_OK;
}

/* the column reaches `keep` below the inlet */
static int extend_column(sim_tube_run *t, dem_system *s, mimas_error *err)
{
    int rc = MIMAS_OK;
    while (!rc && t->feeding &&
           -(double)t->blocks * t->block.length + s->motions[t->motion].shift[2] > -t->keep)
        rc = add_block(t, s, err);
    return rc;
}

/* before a neighbour-list build: grains that left the tube go, the column grows */
static int tube_edit(void *ctx, dem_system *s, mimas_error *err)
{
    sim_tube_run *t = ctx;
    if (s->n > t->drop_cap) {
        uint8_t *d = realloc(t->drop, s->cap);
        if (!d)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        t->drop = d;
        t->drop_cap = s->cap;
    }
    size_t gone = 0;
    for (size_t k = 0; k < s->n; k++) {
        double z = s->x[k][2];
        t->drop[k] = s->glued[k] < 0 && (z >= t->length || z < -2 * t->particle_radius);
        gone += t->drop[k];
    }
    int rc = gone ? dem_remove(s, t->drop, err) : MIMAS_OK;
    return rc ? rc : extend_column(t, s, err);
}

static void tube_forces(void *ctx, dem_system *s)
{
    sim_tube_run *t = ctx;
    if (t->model == SIM_GAS_FLUID_AT_REST) {
        sim_drag_apply(&t->drag, s);
        return;
    }
    if (t->model != SIM_GAS_PRESSURE)
        return;
    /* every gas_every steps the gas advances to the time of the positions the
     * forces are for, and the drag on each grain is computed and held (dem_forces
     * adds it every step) until the next gas step (docs/simulate.md: why that is stable); the first
     * forces of a run take the drag of the field set up */
    if (s->force_step % t->gas_every == 0) {
        sim_gas_deposit(&t->gas, s);
        if (s->force_step > 0)
            sim_gas_step(&t->gas, (double)t->gas_every * t->dt, t->feeding ? t->feed_speed : 0);
        sim_gas_drag_held(&t->gas, s, s->held);
    }
}

/* fill_count grains on a jittered lattice from the outlet end down */
static int fill(sim_tube_run *t, dem_system *s, const sim_scenario *sc, mimas_error *err)
{
    if (sc->fill_count == 0)
        return MIMAS_OK;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!rng)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    gsl_rng_set(rng, (unsigned long)sc->seed);
    double r = t->particle_radius, a = 2 * r * 1.02, room = a / 2 - r;
    int m = (int)ceil(t->radius / a);
    long placed = 0;
    int rc = MIMAS_OK;
    for (int iz = 0; placed < sc->fill_count && !rc; iz++) {
        double z = t->length - a / 2 - iz * a;
        if (z < a / 2) {
            rc = mimas_error_set(err, MIMAS_EDATA, "[plugtube] fill_count = %ld grains do not "
                                 "fit into the tube", sc->fill_count);
            break;
        }
        for (int iy = -m; iy <= m && placed < sc->fill_count && !rc; iy++)
            for (int ix = -m; ix <= m && placed < sc->fill_count; ix++) {
                double c[3] = {ix * a, iy * a, z};
                if (hypot(c[0], c[1]) > t->radius - a / 2 * 1.01)
                    continue;
                double x[3];
                for (int q = 0; q < 3; q++)
                    x[q] = c[q] + room * (2 * gsl_rng_uniform(rng) - 1);
                if ((rc = dem_reserve(s, s->n + 1, err)))
                    break;
                dem_add_particle(s, 1, r, sc->density, x);
                placed++;
            }
    }
    gsl_rng_free(rng);
    return rc;
}

int sim_setup_plugtube(dem_system *s, const sim_scenario *sc, sim_plan *plan, mimas_error *err)
{
    sim_tube_run *t = calloc(1, sizeof *t);
    if (!t)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    plan->tube = t;
    t->radius = sc->tube_diameter / 2;
    t->length = sc->tube_length;
    t->particle_radius = sc->diameter * sc->coarse_grain / 2;
    t->density = sc->density;
    t->model = sc->gas_model;
    t->gas_every = sc->gas_every;
    t->dt = sc->dt;
    double A = M_PI * t->radius * t->radius;
    int rc = MIMAS_OK;
    t->feeding = sc->mass_flow > 0 || sc->feed_speed > 0;
    if (t->feeding) {
        rc = sim_feed_block_make(&t->block, sc, t->radius, sc->feed_porosity, err);
        if (rc)
            return rc;
        t->feed_speed = sc->mass_flow > 0
                            ? sc->mass_flow / (sc->density * (1 - t->block.porosity) * A)
                            : sc->feed_speed;
        t->keep = t->block.length + 4 * t->particle_radius;
        t->motion = s->nmotions;
        s->motions[s->nmotions++] = (dem_motion){.velocity = {0, 0, t->feed_speed},
                                                 .release = 1, .release_normal = {0, 0, 1},
                                                 .release_offset = 0, .release_type = 1};
        rc = extend_column(t, s, err);
    }
    if (!rc)
        rc = fill(t, s, sc, err);
    dem_wall wall = {.kind = DEM_WALL_CYLINDER, .id = 1, .radius = t->radius};
    if (!rc)
        rc = dem_add_wall(s, &wall, err);
    if (!rc && t->model == SIM_GAS_PRESSURE) {
        /* the cells of the tube, and below the inlet as many whole cells as the
         * feed column always fills (it reaches at least `keep` below the inlet):
         * the gas is fed below the column and flows through it, as in Strauß
         * (2005, Sec. 5.1), so that the grains entering the tube are lifted by
         * the pressure gradient across a packed bed */
        size_t axial = (size_t)lround(sc->tube_length / sc->gas_cell_length);
        axial = axial < 2 ? 2 : axial;
        double h = t->length / (double)axial;
        size_t below = t->feeding ? (size_t)floor(t->keep / h * (1 + 1e-12)) : 0;
        sim_gas_params gp = {t->radius, t->length, (size_t)sc->gas_cells_across,
                             axial + below, sc->gas_pressure,
                             sim_gas_effective_viscosity(sc->gas_viscosity, sc->gas_reynolds),
                             sc->gas_velocity, sc->diameter * sc->coarse_grain, sc->gas_theta,
                             -(double)below * h};
        rc = sim_gas_init(&t->gas, &gp, err);
        if (!rc)
            sim_gas_deposit(&t->gas, s);
    }
    if (!rc && t->model == SIM_GAS_FLUID_AT_REST)
        t->drag = (sim_drag){sc->drag_law, sc->wall_factor, sc->fluid_density, sc->gas_viscosity,
                             sc->tube_diameter, sc->buoyancy};
    if (rc)
        return rc;
    s->hooks = (dem_hooks){t, tube_edit, tube_forces};
    plan->total_steps = llround(sc->tube_time / sc->dt);
    double bottom = -(t->feeding ? t->keep + t->block.length : 0);
    plan->box = (mimas_box){.lo = {-t->radius, -t->radius, bottom},
                            .hi = {t->radius, t->radius, t->length}};
    return MIMAS_OK;
}

size_t sim_tube_state(sim_tube_run *t, sim_ck_chunk *chunks, size_t max)
{
    size_t n = 0;
    if (n < max)
        chunks[n++] = (sim_ck_chunk){&t->blocks, sizeof t->blocks};
    if (t->model != SIM_GAS_PRESSURE)
        return n;
    sim_gas *g = &t->gas;
    size_t nc = sim_gas_cells(g);
    if (n + 2 <= max) {
        chunks[n++] = (sim_ck_chunk){g->pressure, nc * sizeof *g->pressure};
        chunks[n++] = (sim_ck_chunk){g->porosity, nc * sizeof *g->porosity};
    }
    for (int d = 0; d < 3 && n + 2 <= max; d++) {
        size_t nf = g->f[d].m[0] * g->f[d].m[1] * g->f[d].m[2];
        chunks[n++] = (sim_ck_chunk){g->f[d].kappa, nf * sizeof *g->f[d].kappa};
        chunks[n++] = (sim_ck_chunk){g->f[d].grad, nf * sizeof *g->f[d].grad};
    }
    return n;
}

sim_gas *sim_tube_gas(sim_tube_run *t)
{
    return t->model == SIM_GAS_PRESSURE ? &t->gas : NULL;
}

int sim_tube_frame(const sim_tube_run *t, mimas_frame *f, mimas_error *err)
{
    f->tube = (mimas_tube){.present = 1, .origin = {0, 0, 0}, .direction = {0, 0, 1},
                           .radius = t->radius, .length = t->length};
    if (t->model != SIM_GAS_PRESSURE) {
        f->gas.present = 0;
        return MIMAS_OK;
    }
    const sim_gas *g = &t->gas;
    int rc = mimas_gas_resize(&f->gas, g->n[0], g->n[1], g->n[2], err);
    if (rc)
        return rc;
    size_t nc = sim_gas_cells(g);
    memcpy(f->gas.origin, g->lo, sizeof g->lo);
    memcpy(f->gas.spacing, g->h, sizeof g->h);
    memcpy(f->gas.pressure, g->pressure, nc * sizeof *g->pressure);
    memcpy(f->gas.porosity, g->porosity, nc * sizeof *g->porosity);
    sim_gas_velocity(g, f->gas.velocity);
    return MIMAS_OK;
}
