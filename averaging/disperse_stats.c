#include <config.h>

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "disperse_impl.h"

#define G MIMAS_DISPERSE_GROUPS
#define REC 7

void disperse_comps_choose(disperse_comps *c, const mimas_axis *a)
{
    c->n = 6;
    c->axial = 5;
    c->trans[0] = 3;
    c->trans[1] = 4;
    for (int k = 0; k < 3; k++)
        if (fabs(a->ez[k]) == 1.0 && a->ez[(k + 1) % 3] == 0 && a->ez[(k + 2) % 3] == 0) {
            /* e_x and e_y are then the other two coordinate axes (axis.c) */
            c->n = 3;
            c->axial = k;
            c->trans[0] = (k + 1) % 3;
            c->trans[1] = (k + 2) % 3;
        }
}

void disperse_comps_project(const disperse_comps *c, const mimas_axis *a, const double v[3],
                            double *out)
{
    out[0] = v[0];
    out[1] = v[1];
    out[2] = v[2];
    if (c->n == 6)
        mimas_axis_vector_to_local(a, v, out + 3);
}

void disperse_comps_expand(const disperse_comps *c, const double *in, double out[6])
{
    out[MIMAS_DC_X] = in[0];
    out[MIMAS_DC_Y] = in[1];
    out[MIMAS_DC_Z] = in[2];
    out[MIMAS_DC_AXIAL] = in[c->axial];
    out[MIMAS_DC_TRANSVERSE] = in[c->trans[0]] + in[c->trans[1]];
    out[MIMAS_DC_TOTAL] = in[0] + in[1] + in[2];
}

size_t cohort_stats_bytes(size_t frames)
{
    return frames * G * REC * sizeof(double);
}

int cohort_stats_init(cohort_stats *s, size_t frames, mimas_error *err)
{
    memset(s, 0, sizeof *s);
    s->acc = calloc(frames * G * REC + 1, sizeof *s->acc);
    if (!s->acc)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    s->frames = frames;
    return MIMAS_OK;
}

void cohort_stats_add(cohort_stats *s, size_t member, size_t t, const double l[3])
{
    double *a = s->acc + (t * G + member % G) * REC;
    double n = a[0] + 1;
    a[0] = n;
    for (int c = 0; c < 3; c++) {
        double d = l[c] - a[1 + c];
        a[1 + c] += d / n;
        a[4 + c] += d * (l[c] - a[1 + c]);
    }
}

void cohort_stats_merged(const cohort_stats *s, size_t t, size_t skip, double *n,
                         double mean[3], double m2[3])
{
    *n = 0;
    for (int c = 0; c < 3; c++)
        mean[c] = m2[c] = 0;
    for (size_t g = 0; g < G; g++) {
        const double *a = s->acc + (t * G + g) * REC;
        if (g == skip || a[0] == 0)
            continue;
        double nb = a[0], na = *n, nn = na + nb;
        for (int c = 0; c < 3; c++) {
            double d = a[1 + c] - mean[c];
            mean[c] += d * nb / nn;
            m2[c] += a[4 + c] + d * d * na * nb / nn;
        }
        *n = nn;
    }
}

void cohort_stats_free(cohort_stats *s)
{
    free(s->acc);
    memset(s, 0, sizeof *s);
}
