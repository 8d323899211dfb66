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
