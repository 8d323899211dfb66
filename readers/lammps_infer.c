#include <config.h>

#include "lammps_infer.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The keyword sets, without history (its width is what the count leaves). */
static const struct {
    const char *before, *after;   /* the keywords before and after history */
    int width;                    /* columns besides the history */
    int min_history;
} sets[] = {
    /* LIGGGHTS' default (no keywords): history is always part of it */
    {"pos,vel,id,force,torque", "contactArea", 22, 1},
    {"pos,vel,id,force,force_normal,force_tangential,torque,torque_normal,torque_tangential",
     "contactArea,delta,contactPoint", 38, 0},
};

int gran_infer_keywords(size_t ncols, char *buf, size_t len)
{
    int best = -1;
    long best_h = 0;
    for (int k = 0; k < (int)(sizeof sets / sizeof sets[0]); k++) {
        long h = (long)ncols - sets[k].width;
        if (h < sets[k].min_history || h > 64)
            continue;
        if (best < 0 || h < best_h)
            best = k, best_h = h;
    }
    if (best < 0)
        return -1;
    if (best_h > 0)
        snprintf(buf, len, "%s,history:%ld,%s", sets[best].before, best_h, sets[best].after);
    else
        snprintf(buf, len, "%s,%s", sets[best].before, sets[best].after);
    return 0;
}

static double norm3(const double v[3])
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static const mimas_extra *find_extra(const mimas_extra *x, size_t n, const char *name)
{
    for (size_t e = 0; e < n; e++)
        if (!strcmp(x[e].name, name) && x[e].ncomp == 1)
            return &x[e];
    return NULL;
}

/* The 6 significant digits of a length printed by LIGGGHTS, at the scale of
 * the coordinates involved (generous: several roundings add up). */
static double length_tol(const double *a, const double *b, double r)
{
    double s = r;
    for (int d = 0; d < 3; d++)
        s = fmax(s, fmax(fabs(a[d]), fabs(b[d])));
    return 5e-5 * s + 1e-12;
}

/* force = force_normal + force_tangential, force_normal along n (unit). */
static int split_fits(const double *f, const double *fn, const double *ft, const double n[3])
{
    double fmag = norm3(f), sum[3], along = fn[0] * n[0] + fn[1] * n[1] + fn[2] * n[2], perp[3];
    for (int d = 0; d < 3; d++) {
        sum[d] = fn[d] + ft[d] - f[d];
        perp[d] = fn[d] - along * n[d];
    }
    return norm3(sum) <= 1e-4 * fmag + 1e-300 && norm3(perp) <= 2e-3 * norm3(fn) + 1e-300;
}

static int check_pairs(const mimas_frame *f, char *why, size_t len)
{
    const mimas_contacts *c = &f->contacts;
    const mimas_particles *p = &f->particles;
    const mimas_extra *area = find_extra(c->extra, c->n_extra, "contact_area");
    for (size_t k = 0; k < c->n; k++) {
        size_t i = c->i[k], j = c->j[k];
        double ri = p->radius[i], rj = p->radius[j], d[3], xj[3];
        for (int m = 0; m < 3; m++)
            d[m] = p->pos[i][m] - p->pos[j][m];
        mimas_box_min_image(&f->box, d);
        for (int m = 0; m < 3; m++)
            xj[m] = p->pos[i][m] - d[m]; /* the touching image of j */
        double r = norm3(d), tol = length_tol(p->pos[i], xj, ri + rj);
        if (!(r > 0)) {
            snprintf(why, len, "contact %zu joins two particles at one place", k);
            return -1;
        }
        double n[3] = {-d[0] / r, -d[1] / r, -d[2] / r}; /* from i to j */
        if ((c->present & MIMAS_C_OVERLAP) && fabs(c->overlap[k] - (ri + rj - r)) > tol) {
            snprintf(why, len, "contact %zu has overlap %g, the radii and the distance give %g",
                     k, c->overlap[k], ri + rj - r);
            return -1;
        }
        if (c->present & MIMAS_C_POINT) {
            double a[3], b[3];
            for (int m = 0; m < 3; m++) {
                a[m] = c->point[k][m] - p->pos[i][m];
                b[m] = c->point[k][m] - xj[m];
            }
            if (norm3(a) + norm3(b) - r > 4 * tol) {
                snprintf(why, len, "the contact point of contact %zu is not between the "
                         "centres", k);
                return -1;
            }
        }
        if (area) {
            /* the circle where the two spheres intersect */
            double A = -M_PI / 4 * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj)) /
                       (r * r);
            if (fabs(area->data[k] - A) > 2 * M_PI * (ri + rj) * tol + 1e-4 * fabs(A)) {
                snprintf(why, len, "contact %zu has contact area %g, the radii and the distance "
                         "give %g", k, area->data[k], A);
                return -1;
            }
        }
        if ((c->present & MIMAS_C_FORCE_N) && (c->present & MIMAS_C_FORCE_T) &&
            !split_fits(c->force[k], c->force_n[k], c->force_t[k], n)) {
            snprintf(why, len, "the normal and tangential forces of contact %zu do not add up "
                     "to its force along the branch", k);
            return -1;
        }
    }
    return 0;
}

static int check_walls(const mimas_frame *f, char *why, size_t len)
{
    const mimas_wall_contacts *w = &f->walls;
    const mimas_particles *p = &f->particles;
    const mimas_extra *area = find_extra(w->extra, w->n_extra, "contact_area");
    if (!(w->present & MIMAS_W_POINT))
        return 0;
    for (size_t k = 0; k < w->n; k++) {
        size_t i = w->particle[k];
        double R = p->radius[i], d[3];
        for (int m = 0; m < 3; m++)
            d[m] = p->pos[i][m] - w->point[k][m];
        double r = norm3(d), delta = R - r, tol = length_tol(p->pos[i], w->point[k], R);
        if (!(r > 0) || delta < -tol) {
            snprintf(why, len, "wall contact %zu: the contact point is %g from the centre of a "
                     "particle of radius %g", k, r, R);
            return -1;
        }
        if ((w->present & MIMAS_W_OVERLAP) && fabs(w->overlap[k] - delta) > tol) {
            snprintf(why, len, "wall contact %zu has overlap %g, the radius and the contact "
                     "point give %g", k, w->overlap[k], delta);
            return -1;
        }
        if (area) {
            double A = M_PI * (R * R - r * r);
            if (fabs(area->data[k] - A) > 2 * M_PI * R * tol + 1e-4 * fabs(A)) {
                snprintf(why, len, "wall contact %zu has contact area %g, the radius and the "
                         "contact point give %g", k, area->data[k], A);
                return -1;
            }
        }
        double n[3] = {-d[0] / r, -d[1] / r, -d[2] / r};
        if ((w->present & MIMAS_W_FORCE_N) && (w->present & MIMAS_W_FORCE_T) &&
            !split_fits(w->force[k], w->force_n[k], w->force_t[k], n)) {
            snprintf(why, len, "the normal and tangential forces of wall contact %zu do not add "
                     "up to its force", k);
            return -1;
        }
    }
    return 0;
}

int gran_check_inferred(const mimas_frame *f, int walls, char *why, size_t len)
{
    if (!(f->particles.present & MIMAS_P_RADIUS)) {
        snprintf(why, len, "the per-atom dump has no radii to check them with");
        return -1;
    }
    return walls ? check_walls(f, why, len) : check_pairs(f, why, len);
}
