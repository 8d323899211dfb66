#include <config.h>

#include "average.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "contact_point.h"
#include "deposit.h"
#include "fields.h"
#include "simd.h"
#include "big_alloc.h"
#include "parallel.h"
#include "voronoi.h"

struct mimas_average {
    mimas_average_options opt;
    mimas_grid grid;        /* fitted to the first frame */
    size_t cells, frames;
    double *sum;            /* cells x NSUMS, summed over frames */
    size_t used;            /* the leading sums this average uses (sums_used) */
    size_t stride;          /* a cell's row in a frame's sums: used, rounded up to a whole
                             * number of cache lines (SUM_LINE) */
    double *frame_sum;      /* cells x stride, this frame */
    double *thread_sum;     /* threads x cells x stride (more than one thread) */
    int threads;
    /* per-frame field statistics (Welford), cells x nfields each */
    double *f_mean, *f_m2, *f_count;
    double *scratch;        /* nfields */
    /* per frame: particle selection and contact counts */
    unsigned char *keep;
    int *ncontacts;
    size_t cap;
    mimas_voronoi_values vor;   /* --weight voronoi: this frame's per-particle values */
    mimas_weights *ws;          /* per thread: the weights of the object being deposited */
    double kappa;               /* gradient correction of the kernel on this grid */
};

static mimas_fields_mode fields_mode(const mimas_weight *wt)
{
    return wt->voronoi ? MIMAS_FIELDS_VORONOI
                       : (wt->kind == MIMAS_WEIGHT_SHEPARD ? MIMAS_FIELDS_SHEPARD
                                                           : MIMAS_FIELDS_DENSITY);
}

/* Whether the weight's particles deposit the gradients of their weights (S_G) */
static int with_gradients(const mimas_weight *wt)
{
    return wt->kind == MIMAS_WEIGHT_GAUSS || wt->kind == MIMAS_WEIGHT_LUCY;
}

/* How many of the leading sums (fields.h) an average with this weight adds to: a
 * frame's sums hold only these, so that zeroing them, filling them and adding them
 * up moves no more memory than it must (bins: 35 of the 61). */
static size_t sums_used(const mimas_weight *wt)
{
    if (wt->voronoi)
        return NSUMS;
    if (wt->kind == MIMAS_WEIGHT_SHEPARD)
        return S_U + 3;
    return with_gradients(wt) ? S_G + 12 : S_G;
}

/* The doubles of a 64-byte cache line: a frame's sums give each cell a whole number of
 * lines, starting at a line's start (mimas_big_calloc), so that a particle's 16 sums
 * (S_N..S_K) and a contact's 16 (S_C..S_F) take two lines each, not three. */
#define SUM_LINE 8

int mimas_average_create(mimas_average **out, const mimas_average_options *o, mimas_error *err)
{
    *out = NULL;
    mimas_average *a = calloc(1, sizeof *a);
    if (!a)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the averaging");
    a->opt = *o;
    a->grid = o->grid;
    a->cells = o->grid_none ? 1 : mimas_grid_cells(&o->grid);
    size_t nf = mimas_fields_count();
    a->sum = mimas_big_calloc(a->cells * NSUMS, sizeof *a->sum);
    a->used = sums_used(&o->weight);
    a->threads = 1;
#ifdef _OPENMP
    a->threads = o->threads > 0 ? o->threads : omp_get_max_threads();
#endif
    /* one frame's sums: where one thread deposits, and what the spread is taken of;
     * more threads without the spread add their copies straight into the sum */
    int frame_sums = a->threads == 1 || o->spread;
    a->stride = (a->used + SUM_LINE - 1) / SUM_LINE * SUM_LINE;
    if (frame_sums)
        a->frame_sum = mimas_big_calloc(a->cells * a->stride, sizeof(double));
    a->scratch = calloc(nf, sizeof *a->scratch);
    if (a->threads > 1)
        a->thread_sum = mimas_big_calloc((size_t)a->threads * a->cells * a->stride, sizeof(double));
    a->ws = calloc((size_t)a->threads, sizeof *a->ws);
    /* the plain cut Gaussian's jump at its cutoff carries the part kappa of a linear
     * field's gradient where the 3-D kernel is sampled at cell centres; its marginals
     * and azimuthal averages are continuous */
    const mimas_grid *g = &o->grid;
    int sampled = !o->grid_none && g->gridded[2] &&
                  (g->kind == MIMAS_GRID_CARTESIAN ? g->gridded[0] && g->gridded[1]
                                                   : g->gridded[1]);
    a->kappa = sampled && o->weight.kind == MIMAS_WEIGHT_GAUSS ? o->weight.kappa : 0.0;
    int ok = a->sum && (a->frame_sum || !frame_sums) && a->scratch && a->ws &&
             (a->threads == 1 || a->thread_sum);
    if (ok && o->spread) {
        a->f_mean = mimas_big_calloc(a->cells * nf, sizeof *a->f_mean);
        a->f_m2 = mimas_big_calloc(a->cells * nf, sizeof *a->f_m2);
        a->f_count = mimas_big_calloc(a->cells * nf, sizeof *a->f_count);
        ok = a->f_mean && a->f_m2 && a->f_count;
    }
    if (!ok) {
        mimas_average_free(a);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for %zu cells", a->cells);
    }
    *out = a;
    return MIMAS_OK;
}

void mimas_average_reset(mimas_average *a)
{
    size_t nf = mimas_fields_count();
    memset(a->sum, 0, a->cells * NSUMS * sizeof *a->sum);
    if (a->opt.spread) {
        memset(a->f_mean, 0, a->cells * nf * sizeof *a->f_mean);
        memset(a->f_m2, 0, a->cells * nf * sizeof *a->f_m2);
        memset(a->f_count, 0, a->cells * nf * sizeof *a->f_count);
    }
    a->frames = 0;
}

void mimas_average_free(mimas_average *a)
{
    if (!a)
        return;
    mimas_big_free(a->sum);
    mimas_big_free(a->frame_sum);
    mimas_big_free(a->thread_sum);
    mimas_big_free(a->f_mean);
    mimas_big_free(a->f_m2);
    mimas_big_free(a->f_count);
    free(a->scratch);
    free(a->keep);
    free(a->ncontacts);
    for (int t = 0; a->ws && t < a->threads; t++)
        mimas_weights_free(&a->ws[t]);
    free(a->ws);
    free(a);
}

size_t mimas_average_frames(const mimas_average *a)
{
    return a->frames;
}

const mimas_grid *mimas_average_grid(const mimas_average *a)
{
    return &a->grid;
}

int mimas_average_grid_none(const mimas_average *a)
{
    return a->opt.grid_none;
}

int mimas_average_threads(const mimas_average *a)
{
    return a->threads;
}

const mimas_weight *mimas_average_weight(const mimas_average *a)
{
    return &a->opt.weight;
}

/* ---- the local basis: Cartesian, or (e_r, e_phi, e_z) at a point ---- */

typedef struct basis {
    int cyl;
    double e[3][3]; /* rows: the local unit vectors in global coordinates */
} basis;

static void basis_at(const mimas_grid *g, const double x[3], basis *B)
{
    B->cyl = g->kind == MIMAS_GRID_CYLINDRICAL;
    if (!B->cyl)
        return;
    double a[3];
    mimas_grid_to_axis(g, x, a);
    double r = hypot(a[0], a[1]);
    double c = r > 0 ? a[0] / r : 1.0, s = r > 0 ? a[1] / r : 0.0;
    for (int d = 0; d < 3; d++) {
        B->e[0][d] = c * g->ex[d] + s * g->ey[d];
        B->e[1][d] = -s * g->ex[d] + c * g->ey[d];
        B->e[2][d] = g->ez[d];
    }
}

static void to_local(const basis *B, const double v[3], double out[3])
{
    if (!B->cyl) {
        memcpy(out, v, 3 * sizeof *out);
        return;
    }
    for (int k = 0; k < 3; k++)
        out[k] = B->e[k][0] * v[0] + B->e[k][1] * v[1] + B->e[k][2] * v[2];
}

/* A tensor T[3a+b] in the local basis: E T E^T. */
static void tensor_to_local(const basis *B, const double *T, double *out)
{
    if (!B->cyl) {
        memcpy(out, T, 9 * sizeof *out);
        return;
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double s = 0;
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++)
                    s += B->e[i][a] * T[3 * a + b] * B->e[j][b];
            out[3 * i + j] = s;
        }
}

/* ---- accumulation of one object's weights ---- */

typedef struct particle_vals {
    double q[S_PARTICLE_END];   /* what the particle adds per unit weight: S_N..S_K */
    double qg[4];               /* m, m v: times the gradient (S_G) */
    double v[3];                /* for Shepard's S_U */
    double vcell;               /* Voronoi cell volume (0: not a Voronoi average) */
    int has_stress;
    double stress[9];           /* V_cell sigma in the local basis */
} particle_vals;

/* The usual case in one tight loop: the particle block and the gradients, four
 * sums at a time (the same products and sums as element by element). */
MIMAS_SIMD
static void add_particle_grad(double *restrict S0, size_t stride, const mimas_weights *ws,
                              const particle_vals *p)
{
    double q[S_PARTICLE_END], qg[4];
    memcpy(q, p->q, sizeof q);
    memcpy(qg, p->qg, sizeof qg);
    const size_t *cell = ws->cell;
    const double *wv = ws->w, *gx = mimas_weights_grad(ws, 0), *gy = mimas_weights_grad(ws, 1),
                 *gz = mimas_weights_grad(ws, 2);
#if defined(MIMAS_HAVE_V4D)
    _Static_assert(S_PARTICLE_END % 4 == 0, "a particle's sums are whole vectors of 4");
    enum { NV = S_PARTICLE_END / 4 };
    v4d qv[NV], gv = *(const v4d *)qg;
    for (int m = 0; m < NV; m++)
        qv[m] = *(const v4d *)(q + 4 * m);
#endif
    for (size_t k = 0; k < ws->n; k++) {
        double *restrict S = S0 + cell[k] * stride, w = wv[k];
        double g0 = gx[k], g1 = gy[k], g2 = gz[k];
#if defined(MIMAS_HAVE_V4D)
        for (int m = 0; m < NV; m++)
            *(v4d *)(S + 4 * m) += qv[m] * w;
        *(v4d *)(S + S_G) += gv * g0;
        *(v4d *)(S + S_G + 4) += gv * g1;
        *(v4d *)(S + S_G + 8) += gv * g2;
#else
        for (int m = 0; m < S_PARTICLE_END; m++)
            S[m] += q[m] * w;
        for (int m = 0; m < 4; m++)
            S[S_G + m] += qg[m] * g0;
        for (int m = 0; m < 4; m++)
            S[S_G + 4 + m] += qg[m] * g1;
        for (int m = 0; m < 4; m++)
            S[S_G + 8 + m] += qg[m] * g2;
#endif
    }
}

static void add_particle(double *S0, size_t stride, const mimas_weights *ws,
                         const particle_vals *p, int shepard, int voronoi)
{
    if (ws->has_grad && !shepard && !voronoi) {
        add_particle_grad(S0, stride, ws, p);
        return;
    }
    for (size_t k = 0; k < ws->n; k++) {
        double *S = S0 + ws->cell[k] * stride, w = ws->w[k];
        for (int m = 0; m < S_PARTICLE_END; m++)
            S[m] += p->q[m] * w;
        if (ws->has_grad) {
            /* gradients of mass and momentum densities, for the analytic
             * velocity gradient of the kernels */
            for (int b = 0; b < 3; b++) {
                double g = mimas_weights_grad(ws, b)[k];
                for (int m = 0; m < 4; m++)
                    S[S_G + 4 * b + m] += p->qg[m] * g;
            }
        }
        if (shepard)
            for (int m = 0; m < 3; m++)
                S[S_U + m] += p->v[m] * w;
        if (voronoi) {
            S[S_VC] += p->vcell * w;
            if (p->has_stress) {
                S[S_VSC] += p->vcell * w;
                for (int m = 0; m < 9; m++)
                    S[S_VS + m] += p->stress[m] * w;
            }
        }
    }
}

/* A contact's 16 sums, S_C..S_W (fields.h), four at a time. */
MIMAS_SIMD
static void add_contact(double *restrict S0, size_t stride, const mimas_weights *ws,
                        const double *qin)
{
    double q[16];
    memcpy(q, qin, sizeof q);
    const size_t *cell = ws->cell;
    const double *wv = ws->w;
#if defined(MIMAS_HAVE_V4D)
    v4d q0 = *(const v4d *)q, q1 = *(const v4d *)(q + 4), q2 = *(const v4d *)(q + 8),
        q3 = *(const v4d *)(q + 12);
#endif
    for (size_t k = 0; k < ws->n; k++) {
        double *restrict S = S0 + cell[k] * stride + S_C, w = wv[k];
#if defined(MIMAS_HAVE_V4D)
        *(v4d *)S += q0 * w;
        *(v4d *)(S + 4) += q1 * w;
        *(v4d *)(S + 8) += q2 * w;
        *(v4d *)(S + 12) += q3 * w;
#else
        for (int m = 0; m < 16; m++)
            S[m] += q[m] * w;
#endif
    }
}

/* One contact's stress and fabric: f acting on the particle at the end of
 * branch b, the segment from `from` to from + b. */
static int deposit_branch(const mimas_deposit *dp, const mimas_grid *g, double *S0,
                          size_t stride, mimas_weights *ws, const double from[3],
                          const double b[3], const double f[3], const double at[3])
{
    basis B;
    basis_at(g, at, &B);
    double fl[3], bl[3];
    to_local(&B, f, fl);
    to_local(&B, b, bl);
    double len = sqrt(bl[0] * bl[0] + bl[1] * bl[1] + bl[2] * bl[2]);
    /* f (x) b and n (x) n (xx yy zz xy xz yz) in the local basis, and S_F's 0: S_C, S_F */
    static const int fab[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
    double q[16];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            q[3 * i + j] = fl[i] * bl[j];
    for (int k = 0; k < 6; k++) {
        int i = fab[k][0], j = fab[k][1];
        q[9 + k] = len > 0 ? bl[i] * bl[j] / (len * len) : 0.0;
    }
    q[15] = 0.0;
    double to[3] = {from[0] + b[0], from[1] + b[1], from[2] + b[2]};
    ws->n = 0;
    if (mimas_deposit_segment(dp, from, to, ws))
        return MIMAS_EIO;
    add_contact(S0, stride, ws, q);
    return MIMAS_OK;
}

static int selected(const mimas_average_options *o, const mimas_particles *p, size_t k)
{
    return mimas_particle_selected(p, k, o->types, o->ntypes, o->exclude);
}

static int prepare(mimas_average *a, const mimas_frame *f, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    int rc = mimas_frame_require_dynamics(f, err);
    if (rc)
        return rc;
    if (a->opt.weight.voronoi) {
        mimas_voronoi_values_of(p, &a->vor);
        if (!a->vor.volume)
            return mimas_error_set(err, MIMAS_EMISSING, "particles have no %s: write the cells "
                                   "with mimas voronoi -o FILE.h5 and average that file",
                                   MIMAS_VORONOI_VOLUME);
    }
    if (p->n > a->cap) {
        unsigned char *k = realloc(a->keep, p->n);
        int *n = realloc(a->ncontacts, p->n * sizeof *n);
        if (k)
            a->keep = k;
        if (n)
            a->ncontacts = n;
        if (!k || !n)
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the averaging");
        a->cap = p->n;
    }
    for (size_t k = 0; k < p->n; k++) {
        /* Voronoi: only the particles mimas voronoi reported */
        int cell = !a->opt.weight.voronoi || !isnan(a->vor.volume[k]);
        a->keep[k] = (unsigned char)(selected(&a->opt, p, k) && cell);
        a->ncontacts[k] = 0;
    }
    const mimas_contacts *c = &f->contacts;
    for (size_t k = 0; f->has_contacts && k < c->n; k++)
        if (a->keep[c->i[k]] && a->keep[c->j[k]]) {
            a->ncontacts[c->i[k]]++;
            a->ncontacts[c->j[k]]++;
        }
    return MIMAS_OK;
}

/* A wall contact (or a contact with an excluded particle): f on the particle
 * at r, the segment from the contact point c to r (docs/theory.md §1, §6), and the
 * force as a wall force density at c. */
static int deposit_wall_contact(const mimas_deposit *dp, const mimas_grid *g, double *S,
                                size_t stride, mimas_weights *ws, const mimas_box *box,
                                const double r[3], const double c[3], const double f[3])
{
    double b[3];
    mimas_branch(box, r, c, b);
    double from[3] = {r[0] - b[0], r[1] - b[1], r[2] - b[2]};
    if (deposit_branch(dp, g, S, stride, ws, from, b, f, from))
        return MIMAS_EIO;
    double fl[3];
    basis B;
    basis_at(g, from, &B);
    to_local(&B, f, fl);
    ws->n = 0;
    if (mimas_deposit_sphere(dp, from, 0.0, 0, ws))
        return MIMAS_EIO;
    for (size_t k = 0; k < ws->n; k++)
        for (int m = 0; m < 3; m++)
            S[ws->cell[k] * stride + S_W + m] += fl[m] * ws->w[k];
    return MIMAS_OK;
}

/* Thread t's share of n objects (particles, contacts or wall contacts of a
 * frame): runs of SHARE_RUN consecutive objects dealt out in turn, thread t
 * taking runs t, t + nt, t + 2 nt, ...  Consecutive objects keep a thread's
 * reads of the frame (and, the objects of most files being ordered in space,
 * its writes to its sums) together: with every nt-th object instead, each
 * thread read every cache line of the frame, and the contacts of bins took 1.55x
 * less time on two threads than on one instead of 1.9x; the turns share out
 * costs that vary along the index (a grid over part of the box).  Loop
 * for (k = share_first(n, t); k < n; k = share_next(k, n, nt)). */
#define SHARE_RUN 4096

static inline size_t share_first(size_t n, int t)
{
    size_t k = (size_t)t * SHARE_RUN;
    return k < n ? k : n;
}

static inline size_t share_next(size_t k, size_t n, int nt)
{
    k++;
    if (k % SHARE_RUN == 0) /* the end of a run: past the other threads' runs */
        k += (size_t)(nt - 1) * SHARE_RUN;
    return k < n ? k : n;
}

/* Thread t of nt deposits its share of the particles, contacts and wall
 * contacts of the frame into the sums S, the weights of each object listed in ws;
 * MIMAS_EIO when out of memory. */
static int deposit_objects(const mimas_average *a, const mimas_frame *f, const mimas_grid *g,
                           const mimas_deposit *dp, double *S, int t, int nt, mimas_weights *ws)
{
    const mimas_particles *p = &f->particles;
    int shepard = a->opt.weight.kind == MIMAS_WEIGHT_SHEPARD, voronoi = a->opt.weight.voronoi;
    int with_grad = with_gradients(&a->opt.weight);
    size_t stride = a->stride;
    for (size_t k = share_first(p->n, t); k < p->n; k = share_next(k, p->n, nt)) {
        if (!a->keep[k])
            continue;
        particle_vals pv;
        memset(&pv, 0, sizeof pv);
        double m = p->mass[k], c = (double)a->ncontacts[k], v[3];
        basis B;
        basis_at(g, p->pos[k], &B);
        to_local(&B, p->vel[k], v);
        pv.q[S_N] = 1.0;
        pv.q[S_M] = m;
        pv.q[S_V] = 4.0 / 3.0 * M_PI * pow(p->radius[k], 3);
        pv.q[S_D] = 2.0 * p->radius[k];
        pv.q[S_Z] = c;
        pv.q[S_ZN] = c >= 2 ? c : 0.0;
        pv.q[S_NN] = c >= 2 ? 1.0 : 0.0;
        pv.qg[0] = m;
        for (int i = 0; i < 3; i++) {
            pv.v[i] = v[i];
            pv.q[S_P + i] = m * v[i];
            pv.qg[1 + i] = m * v[i];
            for (int j = i; j < 3; j++)
                pv.q[S_K + mimas_sym_index(i, j)] = m * v[i] * v[j];
        }
        if (voronoi) {
            /* V_cell sigma_k: an empty cell's stress is NaN and left out */
            pv.vcell = a->vor.volume[k];
            const double *st = a->vor.stress ? &a->vor.stress[9 * k] : NULL;
            pv.has_stress = st && !isnan(st[0]);
            if (pv.has_stress) {
                double T[9];
                for (int q = 0; q < 9; q++)
                    T[q] = pv.vcell * st[q];
                tensor_to_local(&B, T, pv.stress);
            }
        }
        ws->n = 0;
        if (mimas_deposit_sphere(dp, p->pos[k], p->radius[k], with_grad, ws))
            return MIMAS_EIO;
        add_particle(S, stride, ws, &pv, shepard, voronoi);
    }
    if (voronoi)
        return MIMAS_OK; /* the stress comes from the per-particle stresses */
    const mimas_contacts *c = &f->contacts;
    for (size_t k = share_first(c->n, t); f->has_contacts && k < c->n;
         k = share_next(k, c->n, nt)) {
        size_t i = c->i[k], j = c->j[k];
        if (!a->keep[i] && !a->keep[j])
            continue;
        if (a->keep[i] && a->keep[j]) {
            /* f_ij (x) (r_i - r_j), the branch by the minimum image (docs/theory.md §1) */
            double b[3] = {p->pos[i][0] - p->pos[j][0], p->pos[i][1] - p->pos[j][1],
                           p->pos[i][2] - p->pos[j][2]};
            mimas_box_min_image(&f->box, b);
            const double *at = (c->present & MIMAS_C_POINT) ? c->point[k] : p->pos[i];
            if (deposit_branch(dp, g, S, stride, ws, p->pos[j], b, c->force[k], at))
                return MIMAS_EIO;
            continue;
        }
        /* one side excluded (a wall particle): a wall contact of the other */
        size_t in = a->keep[i] ? i : j;
        double cp[3], fin[3];
        mimas_contact_point(f, k, in, cp);
        for (int m = 0; m < 3; m++)
            fin[m] = in == i ? c->force[k][m] : -c->force[k][m];
        if (deposit_wall_contact(dp, g, S, stride, ws, &f->box, p->pos[in], cp, fin))
            return MIMAS_EIO;
    }
    const mimas_wall_contacts *w = &f->walls;
    for (size_t k = share_first(w->n, t); f->has_walls && k < w->n;
         k = share_next(k, w->n, nt)) {
        size_t i = w->particle[k];
        if (!a->keep[i])
            continue;
        if (deposit_wall_contact(dp, g, S, stride, ws, &f->box, p->pos[i], w->point[k],
                                 w->force[k]))
            return MIMAS_EIO;
    }
    return MIMAS_OK;
}

/* deposit_objects with the thread's weight list in a copy of its own while it
 * works: the threads' lists lie side by side in a->ws, and the list's length,
 * written for every weight, would share a cache line with the neighbour's
 * (with two threads the particles of bins took longer than with one). */
static int deposit_frame(const mimas_average *a, const mimas_frame *f, const mimas_grid *g,
                         const mimas_deposit *dp, double *S, int t, int nt)
{
    mimas_weights ws = a->ws[t];
    int rc = deposit_objects(a, f, g, dp, S, t, nt, &ws);
    a->ws[t] = ws; /* kept, with what it has grown to, for the next frame */
    return rc;
}

/* frames this small are deposited by one thread: waking the others costs more
 * than they do */
#define SMALL_FRAME 2000

/* The frame's sums added to the sum over frames: one thread deposits into the
 * frame's own sums (a->frame_sum), more threads each into their own copy, added
 * up (into a->frame_sum too where it is kept, for the spread).  Every frame is
 * summed on its own before it is added, with or without the spread, so that the
 * spread (which -o always keeps) changes no digit of the fields.  MIMAS_EIO when
 * out of memory. */
static int deposit_frame_sums(mimas_average *a, const mimas_frame *f, const mimas_grid *g,
                              const mimas_deposit *dp)
{
    double *S = a->frame_sum;
    size_t used = a->used, stride = a->stride, nsum = a->cells * stride;
    if (a->threads > 1) {
        /* each thread deposits into its own sums, added up afterwards: the
         * result depends on the thread count only through summation order.
         * Zeroing the copies and adding them up (threads x cells x used doubles,
         * 60 MB for bins on a 46^3 grid) are shared out among the threads too, each over
         * its own range of cells, in the thread order of a serial sum (the same bits);
         * the frame's own sums are kept only for the spread. */
#ifdef _OPENMP
        int failed = 0;
#pragma omp parallel num_threads(a->threads) if (f->particles.n + f->contacts.n >= SMALL_FRAME)
        {
            int t = omp_get_thread_num(), nt = omp_get_num_threads();
            double *mine = a->thread_sum + (size_t)t * nsum;
            memset(mine, 0, nsum * sizeof *mine);
            if (deposit_frame(a, f, g, dp, mine, t, nt)) {
#pragma omp atomic write
                failed = 1;
            }
#pragma omp barrier
            int bad;
#pragma omp atomic read
            bad = failed;
            size_t c0 = bad ? 0 : a->cells * (size_t)t / (size_t)nt;
            size_t c1 = bad ? 0 : a->cells * (size_t)(t + 1) / (size_t)nt;
            for (size_t cell = c0; cell < c1; cell++)
                for (size_t m = 0; m < used; m++) {
                    size_t k = cell * stride + m;
                    double sum = 0.0;
                    for (int u = 0; u < nt; u++)
                        sum += a->thread_sum[(size_t)u * nsum + k];
                    if (S)
                        S[k] = sum;
                    a->sum[cell * NSUMS + m] += sum;
                }
        }
        return failed ? MIMAS_EIO : MIMAS_OK;
#endif
    }
    memset(S, 0, nsum * sizeof *S);
    if (deposit_frame(a, f, g, dp, S, 0, 1))
        return MIMAS_EIO;
    for (size_t cell = 0; cell < a->cells; cell++)
        for (size_t m = 0; m < used; m++)
            a->sum[cell * NSUMS + m] += S[cell * stride + m];
    return MIMAS_OK;
}

int mimas_average_add(mimas_average *a, const mimas_frame *f, mimas_error *err)
{
    int rc = prepare(a, f, err);
    if (rc)
        return rc;
    mimas_grid g = a->opt.grid;
    mimas_grid_fit_box(&g, &f->box);
    if (a->frames == 0)
        a->grid = g;
    mimas_deposit dp;
    if (mimas_deposit_init(&dp, &g, &a->opt.weight, &f->box, a->opt.grid_none, err))
        return MIMAS_EUSAGE;
    if (deposit_frame_sums(a, f, &g, &dp))
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    a->frames++;
    if (a->opt.spread) {
        size_t nf = mimas_fields_count();
        int cyl = g.kind == MIMAS_GRID_CYLINDRICAL && !a->opt.grid_none;
        for (size_t cell = 0; cell < a->cells; cell++) {
            double ctr[3] = {0, 0, 0};
            if (cyl)
                mimas_grid_cell_centre(&g, cell, ctr);
            double S[NSUMS] = {0}; /* the sums this average does not use are 0 */
            memcpy(S, &a->frame_sum[cell * a->stride], a->used * sizeof *S);
            mimas_fields_derive(S, cyl, ctr[0], fields_mode(&a->opt.weight), a->scratch);
            for (size_t q = 0; q < nf; q++) {
                double x = a->scratch[q];
                if (isnan(x))
                    continue;
                size_t at = cell * nf + q;
                double n = ++a->f_count[at];
                double delta = x - a->f_mean[at];
                a->f_mean[at] += delta / n;
                a->f_m2[at] += delta * (x - a->f_mean[at]);
            }
        }
    }
    return MIMAS_OK;
}

size_t mimas_average_sums_count(void)
{
    return NSUMS;
}

void mimas_average_sums(const mimas_average *a, size_t cell, double *sums)
{
    const double *s = &a->sum[cell * NSUMS];
    size_t n = a->frames;
    if (n && !(n & (n - 1))) {
        /* a power of two (one frame among them): its reciprocal is exact, and the product
         * is the quotient to the bit, without the divisions */
        double r = 1.0 / (double)n;
        for (int k = 0; k < NSUMS; k++)
            sums[k] = s[k] * r;
        return;
    }
    for (int k = 0; k < NSUMS; k++)
        sums[k] = n ? s[k] / (double)n : 0.0;
}

/* d V_a / d x_b of a cell: analytic for the Gaussian on Cartesian grids
 * (L = (grad j - V (x) grad rho)/rho), else central differences of the
 * time-averaged velocity over the neighbouring cells (one-sided at the grid's
 * edges and next to empty cells); zero along directions that are not
 * gridded.  Cylindrical grids: physical components, column 1 is (1/r) d/dphi. */
static int velocity_gradient(const mimas_average *a, const double *fields, size_t nf,
                             size_t cell, const double *S, double L[3][3])
{
    const mimas_grid *g = &a->grid;
    size_t iv = mimas_fields_velocity();
    const double *V = &fields[cell * nf + iv];
    if (isnan(V[0]))
        return 0;
    /* the kernels' analytic gradient (Shepard's ratio: differences, below) */
    if (a->opt.weight.kind == MIMAS_WEIGHT_GAUSS || a->opt.weight.kind == MIMAS_WEIGHT_LUCY) {
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                L[i][j] = (S[S_GP(i, j)] - V[i] * S[S_GM(j)]) / (S[S_M] * (1.0 - a->kappa));
        return 1;
    }
    int idx[3];
    mimas_grid_unindex(g, cell, idx);
    double ctr[3];
    mimas_grid_cell_centre(g, cell, ctr);
    for (int b = 0; b < 3; b++) {
        for (int i = 0; i < 3; i++)
            L[i][b] = 0.0;
        if (!g->gridded[b] || g->n[b] < 2)
            continue;
        int lo = idx[b] > 0 ? idx[b] - 1 : idx[b], hi = idx[b] + 1 < g->n[b] ? idx[b] + 1 : idx[b];
        int nb[3] = {idx[0], idx[1], idx[2]};
        nb[b] = lo;
        size_t cl = mimas_grid_index(g, nb);
        nb[b] = hi;
        size_t ch = mimas_grid_index(g, nb);
        if (isnan(fields[cl * nf + iv]))
            lo = idx[b], cl = cell;
        if (isnan(fields[ch * nf + iv]))
            hi = idx[b], ch = cell;
        if (lo == hi)
            return 0;
        double h = (g->hi[b] - g->lo[b]) / g->n[b] * (hi - lo);
        if (g->kind == MIMAS_GRID_CYLINDRICAL && b == 1)
            h *= ctr[0]; /* (1/r) d/dphi */
        for (int i = 0; i < 3; i++)
            L[i][b] = (fields[ch * nf + iv + (size_t)i] - fields[cl * nf + iv + (size_t)i]) / h;
    }
    return 1;
}

int mimas_average_fields(const mimas_average *a, double *fields, double *sd, double *count)
{
    size_t nf = mimas_fields_count(), iv = mimas_fields_velocity();
    int cyl = a->grid.kind == MIMAS_GRID_CYLINDRICAL && !a->opt.grid_none;
    for (size_t cell = 0; cell < a->cells; cell++) {
        double S[NSUMS];
        mimas_average_sums(a, cell, S);
        double ctr[3] = {0, 0, 0};
        if (cyl)
            mimas_grid_cell_centre(&a->grid, cell, ctr);
        mimas_fields_derive(S, cyl, ctr[0], fields_mode(&a->opt.weight),
                            &fields[cell * nf]);
        for (size_t q = 0; q < nf; q++) {
            size_t at = cell * nf + q;
            double n = a->opt.spread ? a->f_count[at] : 0;
            if (sd)
                sd[at] = n > 1 ? sqrt(a->f_m2[at] / (n - 1)) : NAN;
            if (count)
                count[at] = n;
        }
    }
    /* the strain rates need the velocities of the neighbours: a second pass, the cell's
     * sums formed again (no copy of all cells' sums: that was as large as the sums) */
    for (size_t cell = 0; cell < a->cells && !a->opt.grid_none; cell++) {
        if (isnan(fields[cell * nf + iv]))
            continue;
        double L[3][3], ctr[3] = {0, 0, 0}, S[NSUMS];
        mimas_average_sums(a, cell, S);
        if (cyl)
            mimas_grid_cell_centre(&a->grid, cell, ctr);
        if (velocity_gradient(a, fields, nf, cell, S, L))
            mimas_fields_strain(L, S, cyl, ctr[0], a->opt.diameter, &fields[cell * nf]);
    }
    return 0;
}

/* ---- the state for merging runs split over processes ---- */
int mimas_average_pack(const mimas_average *a, mimas_bytes *out, mimas_error *err)
{
    size_t nf = mimas_fields_count(), ns = a->cells * NSUMS, nq = a->cells * nf;
    size_t n = sizeof(uint64_t) + sizeof a->grid +
               (ns + (a->opt.spread ? 3 * nq : 0)) * sizeof(double);
    if (n > out->cap) {
        unsigned char *p = realloc(out->data, n);
        if (!p)
            return mimas_error_set(err, MIMAS_EIO, "out of memory for %zu cells", a->cells);
        out->data = p;
        out->cap = n;
    }
    uint64_t frames = a->frames;
    unsigned char *p = out->data;
    memcpy(p, &frames, sizeof frames);
    p += sizeof frames;
    memcpy(p, &a->grid, sizeof a->grid);
    p += sizeof a->grid;
    memcpy(p, a->sum, ns * sizeof(double));
    p += ns * sizeof(double);
    if (a->opt.spread) {
        memcpy(p, a->f_mean, nq * sizeof(double));
        memcpy(p + nq * sizeof(double), a->f_m2, nq * sizeof(double));
        memcpy(p + 2 * nq * sizeof(double), a->f_count, nq * sizeof(double));
    }
    out->n = n;
    return MIMAS_OK;
}

int mimas_average_merge(mimas_average *a, const unsigned char *data, size_t n,
                        mimas_error *err)
{
    size_t nf = mimas_fields_count(), ns = a->cells * NSUMS, nq = a->cells * nf;
    if (n != sizeof(uint64_t) + sizeof a->grid +
                 (ns + (a->opt.spread ? 3 * nq : 0)) * sizeof(double))
        return mimas_error_set(err, MIMAS_EDATA, "an average state of %zu bytes does not fit "
                               "%zu cells", n, a->cells);
    uint64_t frames;
    memcpy(&frames, data, sizeof frames);
    data += sizeof frames;
    /* an average without frames takes the grid of the state (as fitted to its
     * first frame); otherwise a keeps its own */
    if (a->frames == 0)
        memcpy(&a->grid, data, sizeof a->grid);
    data += sizeof a->grid;
    for (size_t k = 0; k < ns; k++) {
        double v;
        memcpy(&v, data + k * sizeof v, sizeof v);
        a->sum[k] += v;
    }
    data += ns * sizeof(double);
    for (size_t k = 0; a->opt.spread && k < nq; k++) {
        double mb, m2b, nb;
        memcpy(&mb, data + k * sizeof mb, sizeof mb);
        memcpy(&m2b, data + (nq + k) * sizeof m2b, sizeof m2b);
        memcpy(&nb, data + (2 * nq + k) * sizeof nb, sizeof nb);
        double na = a->f_count[k], nt = na + nb;
        if (nb == 0)
            continue;
        double delta = mb - a->f_mean[k];
        a->f_mean[k] += delta * nb / nt;
        a->f_m2[k] += m2b + delta * delta * na * nb / nt;
        a->f_count[k] = nt;
    }
    a->frames += (size_t)frames;
    return MIMAS_OK;
}

static int pack_any(const void *obj, mimas_bytes *out, mimas_error *err)
{
    return mimas_average_pack(obj, out, err);
}

static int merge_any(void *obj, const unsigned char *data, size_t n, mimas_error *err)
{
    return mimas_average_merge(obj, data, n, err);
}

int mimas_average_reduce(mimas_average *a, mimas_error *err)
{
    return mimas_par_reduce(a, pack_any, merge_any, err);
}
