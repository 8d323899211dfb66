#include <config.h>

#include "cell_list.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void mimas_cell_list_init(mimas_cell_list *cl)
{
    memset(cl, 0, sizeof *cl);
}

void mimas_cell_list_free(mimas_cell_list *cl)
{
    free(cl->start);
    free(cl->index);
    free(cl->bin);
    mimas_cell_list_init(cl);
}

/* Fractional coordinates of x in the box: x = lo + s0 a + s1 b + s2 c. */
static void fractional(const mimas_box *b, const double x[3], double s[3])
{
    double d[3] = {x[0] - b->lo[0], x[1] - b->lo[1], x[2] - b->lo[2]};
    s[2] = d[2] / (b->hi[2] - b->lo[2]);
    s[1] = (d[1] - s[2] * b->yz) / (b->hi[1] - b->lo[1]);
    s[0] = (d[0] - s[1] * b->xy - s[2] * b->xz) / (b->hi[0] - b->lo[0]);
}

/* Bin index along axis d: wrapped for periodic axes, clamped otherwise
 * (clamping keeps points within reach in the same or adjacent bins). */
static int bin_index(const mimas_cell_list *cl, int d, double s)
{
    int nb = cl->nb[d];
    if (cl->box.periodic[d])
        s -= floor(s);
    int k = (int)floor(s * nb);
    return k < 0 ? 0 : (k >= nb ? nb - 1 : k);
}

static size_t bin_of(const mimas_cell_list *cl, const double x[3], int idx[3])
{
    double s[3];
    fractional(&cl->box, x, s);
    for (int d = 0; d < 3; d++)
        idx[d] = bin_index(cl, d, s[d]);
    return (size_t)idx[0] + (size_t)cl->nb[0] * ((size_t)idx[1] + (size_t)cl->nb[1] * (size_t)idx[2]);
}

static double norm(const double v[3])
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static void cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

int mimas_cell_list_build(mimas_cell_list *cl, const mimas_box *box, size_t n,
                          const double (*pos)[3], const unsigned char *use, double reach,
                          mimas_error *err)
{
    cl->box = *box;
    cl->reach = reach;
    /* the distance between opposite faces along each edge vector, V / |e1 x e2| */
    double e[3][3], c[3];
    mimas_box_edges(box, e);
    double V = mimas_box_volume(box);
    size_t total = 1;
    for (int d = 0; d < 3; d++) {
        cross(e[(d + 1) % 3], e[(d + 2) % 3], c);
        double width = V / norm(c);
        if (box->periodic[d] && !(reach < 0.5 * width))
            return mimas_error_set(err, MIMAS_EUSAGE, "the search radius %g is not below half "
                                   "the periodic box width %g", reach, width);
        double k = floor(width / reach);
        cl->nb[d] = k < 1 ? 1 : (k > 1024 ? 1024 : (int)k);
    }
    /* no more bins than about twice the particles (bigger bins stay correct) */
    for (;;) {
        total = (size_t)cl->nb[0] * (size_t)cl->nb[1] * (size_t)cl->nb[2];
        if (total <= 2 * n + 8)
            break;
        int big = cl->nb[0] >= cl->nb[1] ? (cl->nb[0] >= cl->nb[2] ? 0 : 2)
                                         : (cl->nb[1] >= cl->nb[2] ? 1 : 2);
        cl->nb[big] = (cl->nb[big] + 1) / 2;
    }
    if (total + 1 > cl->bins_cap) {
        size_t *s = realloc(cl->start, (total + 1) * sizeof *s);
        if (!s)
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the cell list");
        cl->start = s;
        cl->bins_cap = total + 1;
    }
    if (n > cl->n_cap) {
        size_t *ix = realloc(cl->index, n * sizeof *ix), *b = realloc(cl->bin, n * sizeof *b);
        if (ix)
            cl->index = ix;
        if (b)
            cl->bin = b;
        if (!ix || !b)
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the cell list");
        cl->n_cap = n;
    }
    /* counting sort by bin */
    memset(cl->start, 0, (total + 1) * sizeof *cl->start);
    int idx[3];
    for (size_t k = 0; k < n; k++)
        if (!use || use[k]) {
            cl->bin[k] = bin_of(cl, pos[k], idx);
            cl->start[cl->bin[k] + 1]++;
        }
    for (size_t b = 0; b < total; b++)
        cl->start[b + 1] += cl->start[b];
    for (size_t k = 0; k < n; k++)
        if (!use || use[k])
            cl->index[cl->start[cl->bin[k]]++] = k;
    /* the increments moved every start to the next bin's: shift back */
    for (size_t b = total; b > 0; b--)
        cl->start[b] = cl->start[b - 1];
    cl->start[0] = 0;
    return MIMAS_OK;
}

/* The distinct bins next to bin k along an axis (3, or all of them when there
 * are fewer than 3 periodic bins). */
static int adjacent(const mimas_cell_list *cl, int d, int k, int out[3])
{
    int nb = cl->nb[d], m = 0;
    if (cl->box.periodic[d] && nb < 3) {
        for (int b = 0; b < nb; b++)
            out[m++] = b;
        return m;
    }
    for (int b = k - 1; b <= k + 1; b++) {
        int w = cl->box.periodic[d] ? (b + nb) % nb : b;
        if (w >= 0 && w < nb)
            out[m++] = w;
    }
    return m;
}

void mimas_cell_list_query(const mimas_cell_list *cl, const double x[3], const double (*pos)[3],
                           mimas_neighbour_fn fn, void *user)
{
    int idx[3], nbr[3][3], cnt[3];
    bin_of(cl, x, idx);
    for (int d = 0; d < 3; d++)
        cnt[d] = adjacent(cl, d, idx[d], nbr[d]);
    int periodic = cl->box.periodic[0] || cl->box.periodic[1] || cl->box.periodic[2];
    double r2 = cl->reach * cl->reach;
    for (int c = 0; c < cnt[2]; c++)
        for (int b = 0; b < cnt[1]; b++)
            for (int a = 0; a < cnt[0]; a++) {
                size_t bin = (size_t)nbr[0][a] +
                             (size_t)cl->nb[0] * ((size_t)nbr[1][b] + (size_t)cl->nb[1] * (size_t)nbr[2][c]);
                for (size_t m = cl->start[bin]; m < cl->start[bin + 1]; m++) {
                    size_t j = cl->index[m];
                    double d[3] = {x[0] - pos[j][0], x[1] - pos[j][1], x[2] - pos[j][2]};
                    if (periodic)
                        mimas_box_min_image(&cl->box, d);
                    double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                    if (d2 < r2)
                        fn(user, j, d, d2);
                }
            }
}
