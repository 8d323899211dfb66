/* The simulation state as a mimas frame (particles, contacts, wall contacts;
 * the tube and gas fields of a plugtube run). */
#include <config.h>

#include <math.h>
#include <string.h>

#include "setup.h"

static int fill_particles(const dem_system *s, mimas_particles *p, mimas_error *err)
{
    unsigned bits = MIMAS_P_ID | MIMAS_P_TYPE | MIMAS_P_RADIUS | MIMAS_P_MASS | MIMAS_P_POS |
                    MIMAS_P_VEL | MIMAS_P_OMEGA | MIMAS_P_FORCE | MIMAS_P_CG |
                    (s->periodic[0] || s->periodic[1] || s->periodic[2] ? MIMAS_P_IMAGE : 0) |
                    (s->bridges_on ? MIMAS_P_LIQUID : 0);
    int rc = mimas_table_set_present(p, &mimas_particles_desc, bits, err);
    if (!rc)
        rc = mimas_table_resize(p, &mimas_particles_desc, s->n, err);
    if (rc)
        return rc;
    size_t n = s->n;
    memcpy(p->id, s->id, n * sizeof *p->id);
    memcpy(p->type, s->type, n * sizeof *p->type);
    memcpy(p->radius, s->radius, n * sizeof *p->radius);
    memcpy(p->mass, s->mass, n * sizeof *p->mass);
    memcpy(p->pos, s->x, n * sizeof *p->pos);
    memcpy(p->vel, s->v, n * sizeof *p->vel);
    memcpy(p->omega, s->w, n * sizeof *p->omega);
    memcpy(p->force, s->f, n * sizeof *p->force);
    for (size_t k = 0; k < n; k++)
        p->cg[k] = s->coarse_grain;
    if (p->image)
        memcpy(p->image, s->image, n * sizeof *p->image);
    if (p->liquid)
        memcpy(p->liquid, s->liquid, n * sizeof *p->liquid);
    return MIMAS_OK;
}

/* normal and tangential parts of f along n */
static void split(const double f[3], const double n[3], double fn[3], double ft[3])
{
    double a = f[0] * n[0] + f[1] * n[1] + f[2] * n[2];
    for (int q = 0; q < 3; q++) {
        fn[q] = a * n[q];
        ft[q] = f[q] - fn[q];
    }
}

static const unsigned contact_bits = MIMAS_C_POINT | MIMAS_C_FORCE | MIMAS_C_FORCE_N |
                                     MIMAS_C_FORCE_T | MIMAS_C_OVERLAP;

static int fill_contacts(const dem_system *s, mimas_contacts *c, mimas_error *err)
{
    const dem_nlist *nl = &s->nl;
    size_t count = 0, vb_col = 0;
    for (size_t k = 0; k < nl->ne; k++)
        count += nl->e[k].flags != 0;
    int rc = mimas_table_set_present(c, &mimas_contacts_desc, contact_bits, err);
    if (!rc && s->bridges_on)
        rc = mimas_table_add_extra(c, &mimas_contacts_desc, "bridge_volume", 1, &vb_col, err);
    if (!rc)
        rc = mimas_table_resize(c, &mimas_contacts_desc, count, err);
    if (rc)
        return rc;
    size_t row = 0;
    for (size_t i = 0; i < s->n; i++)
        for (size_t k = nl->start[i]; k < nl->start[i + 1]; k++) {
            const dem_entry *e = &nl->e[k];
            if (!e->flags)
                continue;
            size_t j = (size_t)e->j;
            double d[3], n[3];
            dem_separation(s, s->x[i], s->x[j], d);
            double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            double delta = s->radius[i] + s->radius[j] - dist;
            for (int q = 0; q < 3; q++) {
                n[q] = d[q] / dist;
                /* docs/theory.md §2: c = r_i - (R_i - delta/2) n */
                c->point[row][q] = s->x[i][q] - (s->radius[i] - delta / 2) * n[q];
                c->force[row][q] = -nl->eft[nl->tpos[k]].f[q];
            }
            split(c->force[row], n, c->force_n[row], c->force_t[row]);
            c->i[row] = i;
            c->j[row] = j;
            c->overlap[row] = delta;
            if (s->bridges_on)
                c->extra[vb_col].data[row] = nl->bv[k];
            row++;
        }
    return MIMAS_OK;
}

static int fill_walls(const dem_system *s, mimas_wall_contacts *w, mimas_error *err)
{
    size_t count = 0;
    for (size_t k = 0; k < s->n * DEM_MAX_WALLS; k++)
        count += s->wall_delta[k] > 0;
    int rc = mimas_table_set_present(w, &mimas_walls_desc,
                                     MIMAS_W_POINT | MIMAS_W_FORCE | MIMAS_W_FORCE_N |
                                         MIMAS_W_FORCE_T | MIMAS_W_OVERLAP, err);
    if (!rc)
        rc = mimas_table_resize(w, &mimas_walls_desc, count, err);
    if (rc)
        return rc;
    size_t row = 0;
    for (size_t i = 0; i < s->n; i++)
        for (int m = 0; m < s->nwalls; m++) {
            size_t slot = i * DEM_MAX_WALLS + (size_t)m;
            if (!(s->wall_delta[slot] > 0))
                continue;
            double n[3];
            dem_wall_geometry(&s->walls[m], s->x[i], s->radius[i], n, w->point[row]);
            memcpy(w->force[row], s->wall_f[slot], sizeof w->force[row]);
            split(w->force[row], n, w->force_n[row], w->force_t[row]);
            w->particle[row] = i;
            w->wall[row] = s->walls[m].id;
            w->overlap[row] = s->wall_delta[slot];
            row++;
        }
    return MIMAS_OK;
}

int sim_frame_fill(const dem_system *s, const sim_plan *plan, mimas_frame *f, mimas_error *err)
{
    f->step = s->step;
    f->time = (double)s->step * s->dt;
    f->box = plan->box;
    f->has_contacts = 1;
    f->has_walls = 1;
    int rc = fill_particles(s, &f->particles, err);
    if (!rc)
        rc = fill_contacts(s, &f->contacts, err);
    if (!rc)
        rc = fill_walls(s, &f->walls, err);
    f->tube.present = 0;
    f->gas.present = 0;
    if (!rc && plan->tube)
        rc = sim_tube_frame(plan->tube, f, err);
    return rc;
}
