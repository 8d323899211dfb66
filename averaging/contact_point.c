#include <config.h>

#include "contact_point.h"

#include <math.h>
#include <string.h>

void mimas_contact_point(const mimas_frame *f, size_t k, size_t i, double c[3])
{
    if (f->contacts.present & MIMAS_C_POINT) {
        memcpy(c, f->contacts.point[k], 3 * sizeof *c);
        return;
    }
    const mimas_particles *p = &f->particles;
    size_t j = f->contacts.i[k] == i ? f->contacts.j[k] : f->contacts.i[k];
    double d[3] = {p->pos[i][0] - p->pos[j][0], p->pos[i][1] - p->pos[j][1],
                   p->pos[i][2] - p->pos[j][2]};
    mimas_box_min_image(&f->box, d);
    double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double delta = p->radius[i] + p->radius[j] - r;
    double s = r > 0 ? (p->radius[i] - 0.5 * delta) / r : 0.0;
    for (int m = 0; m < 3; m++)
        c[m] = p->pos[i][m] - s * d[m];
}

void mimas_branch(const mimas_box *box, const double r[3], const double c[3], double b[3])
{
    for (int m = 0; m < 3; m++)
        b[m] = r[m] - c[m];
    mimas_box_min_image(box, b);
}

int mimas_frame_require_dynamics(const mimas_frame *f, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    int rc = mimas_table_require(p, &mimas_particles_desc,
                                 MIMAS_P_RADIUS | MIMAS_P_MASS | MIMAS_P_VEL, err);
    if (rc) {
        if (!(p->present & MIMAS_P_MASS))
            mimas_error_prefix(err, "%s", "give the particle density with --density");
        return rc;
    }
    if (f->has_contacts)
        rc = mimas_table_require(&f->contacts, &mimas_contacts_desc, MIMAS_C_FORCE, err);
    if (!rc && f->has_walls)
        rc = mimas_table_require(&f->walls, &mimas_walls_desc, MIMAS_W_FORCE | MIMAS_W_POINT,
                                 err);
    return rc;
}

void mimas_contacts_visit(const mimas_frame *f, const unsigned char *keep, size_t t, size_t nt,
                          mimas_pair_visit pair, mimas_wall_visit wall, void *user)
{
    const mimas_particles *p = &f->particles;
    const mimas_contacts *c = &f->contacts;
    for (size_t k = t; f->has_contacts && k < c->n; k += nt) {
        size_t i = c->i[k], j = c->j[k];
        if (!keep[i] && !keep[j])
            continue;
        if (keep[i] && keep[j]) {
            /* f_ij (x) (r_i - r_j), the branch by the minimum image (docs/theory.md §1) */
            double b[3] = {p->pos[i][0] - p->pos[j][0], p->pos[i][1] - p->pos[j][1],
                           p->pos[i][2] - p->pos[j][2]};
            mimas_box_min_image(&f->box, b);
            pair(user, k, b, (c->present & MIMAS_C_POINT) ? c->point[k] : p->pos[i]);
            continue;
        }
        /* one side left out (a wall particle): a wall contact of the other */
        size_t in = keep[i] ? i : j;
        double cp[3], fin[3];
        mimas_contact_point(f, k, in, cp);
        for (int m = 0; m < 3; m++)
            fin[m] = in == i ? c->force[k][m] : -c->force[k][m];
        wall(user, in, cp, fin);
    }
    const mimas_wall_contacts *w = &f->walls;
    for (size_t k = t; f->has_walls && k < w->n; k += nt)
        if (keep[w->particle[k]])
            wall(user, w->particle[k], w->point[k], w->force[k]);
}
