/* The lane helpers of the Gaussian line integral on x-y-z grids (deposit_gauss_segment.h's
 * vector builds): a row's cells classified, the uncut ones summed over the nodes and put,
 * the cut ones queued and evaluated, SEG_LANES cells at a time in GCC's vectors.
 * deposit_gauss.c includes this once for each build, under its #pragma GCC target, with
 * SEG_LANES, the vector, mask and index types SEG_VT, SEG_MT and SEG_IT, SEG_BITS (a mask
 * as bits), SEG_GATHER (the table's coefficient at each lane's row), SEG_SQRT and SEG_SEL
 * (m ? a : b lane by lane) of lanes_x86.h, and SEG_PACK, SEG_PACK_CELLS and
 * SEG_PACK_RUN (the lanes of some bits of a vector, of cell indices read or of the
 * consecutive cells from one, moved to the front and all SEG_LANES stored: the weight
 * list and the queue have room for SEG_LANES more).  Lane by lane the same operations as
 * the portable build's cell (shell_cell, within_reach, the rows' node sums), so the same
 * weights to the bit in every build. */

/* vrow[c..] = sum_k f[k] ex[k n + c..] for the lanes' cells from c, the nodes in order */
static inline __attribute__((always_inline)) void SEG_V(node_sums_n)(const double *ex, size_t n,
                                                                     const double *f, int nq,
                                                                     int c, double *vrow)
{
    SEG_VT acc = {0}, x;
    for (int k = 0; k < nq; k++) {
        memcpy(&x, ex + (size_t)k * n + c, sizeof x);
        acc += x * f[k];
    }
    memcpy(vrow + c, &acc, sizeof acc);
}

/* The same with the usual node counts known to the compiler (its loop unrolled). */
static inline void SEG_V(node_sums)(const double *ex, size_t n, const double *f, int nq, int c,
                                    double *vrow)
{
    switch (nq) {
    case 8:
        SEG_V(node_sums_n)(ex, n, f, 8, c, vrow);
        break;
    case 10:
        SEG_V(node_sums_n)(ex, n, f, 10, c, vrow);
        break;
    case 12:
        SEG_V(node_sums_n)(ex, n, f, 12, c, vrow);
        break;
    default:
        SEG_V(node_sums_n)(ex, n, f, nq, c, vrow);
    }
}

/* tab_eval at each lane's x >= 0, from H's table in the lanes of h, else G's */
static inline SEG_VT SEG_V(tab_eval)(SEG_VT x, SEG_MT h)
{
    SEG_IT m = __builtin_convertvector(x * 64.0, SEG_IT), top = {0};
    top += GT_N - 1;
    SEG_IT below = m < top;
    m = (m & below) | (top & ~below);
    SEG_VT d = x - (__builtin_convertvector(m, SEG_VT) + 0.5) * GT_DU;
    SEG_IT row = (m + (__builtin_convertvector(h, SEG_IT) & GT_N)) * (GT_DEG + 1);
    const double *base = &ghtab[0][0][0];
    SEG_VT v, a;
    SEG_GATHER(base + GT_DEG, &row, &v);
    for (int k = GT_DEG - 1; k >= 0; k--) {
        SEG_GATHER(base + k, &row, &a);
        v = v * d + a;
    }
    return v;
}

/* Evaluates the queued cells SEG_LANES at a time, shell_cell's operations lane by lane,
 * and puts those with a weight; a last group of fewer only when all (else it stays,
 * moved to the front). */
static void SEG_V(cut_flush)(cut_queue *q, const shell_consts *sc, double len, int all,
                             dep_cursor *cur)
{
    int n = q->n, done = all ? n : n & ~(SEG_LANES - 1);
    for (int m = n; all && (m & (SEG_LANES - 1)); m++) /* lanes that give 0: h^2 = R^2 */
        cut_push(q, 0, sc->R2, sc->R2, 0.0, 0.0, 0.0);
    const SEG_VT zero = {0};
    for (int i = 0; i < done; i += SEG_LANES) {
        SEG_VT e, qb, t, ea, eb, c, c2;
        memcpy(&e, q->e + i, sizeof e);
        memcpy(&qb, q->qb + i, sizeof qb);
        memcpy(&t, q->t + i, sizeof t);
        memcpy(&ea, q->ea + i, sizeof ea);
        memcpy(&eb, q->eb + i, sizeof eb);
        SEG_VT h2 = e - t * t;
        h2 = SEG_SEL(h2 < zero, zero, h2);
        SEG_MT valid = h2 < sc->R2, a_in = e < sc->R2, end = a_in | (qb < sc->R2);
        SEG_MT keep = valid & (end | ((t > zero) & (t < len)));
        c2 = SEG_SEL(valid, sc->R2 - h2, zero);
        SEG_SQRT(&c2, &c);
        /* the foot from the end inside the ball (a's when both are), its factor */
        SEG_VT tp = SEG_SEL(a_in, t, len - t), e_end = SEG_SEL(a_in, ea, eb);
        SEG_MT neg = tp < zero;
        SEG_VT T1 = SEG_V(tab_eval)(SEG_SEL(keep, c * sc->k, zero), end & neg);
        SEG_VT T2 = SEG_V(tab_eval)(SEG_SEL(keep & end, SEG_SEL(neg, -tp, tp) * sc->k, zero),
                                    neg);
        SEG_VT sum = sc->tail * T1 + e_end * T2, tails = e_end * T2 - sc->tail * T1;
        SEG_VT v = SEG_SEL(end, SEG_SEL(neg, tails, sum), 2.0 * sc->tail * T1);
        SEG_VT chord = SEG_SEL(end, tp + c, 2.0 * c);
        SEG_VT w = SEG_SEL(keep, sc->scale * v - sc->shift_scale * chord, zero);
        /* the lanes with a weight (w != 0, as in C: NaN too), of the queue's n */
        SEG_MT nonzero = w != zero;
        int put = SEG_BITS(&nonzero);
        if (n - i < SEG_LANES)
            put &= (1 << (n - i)) - 1;
        SEG_PACK(cur->w, w, put);
        SEG_PACK_CELLS(cur->cell, q->cell + i, put);
        int k = __builtin_popcount((unsigned)put);
        cur->w += k;
        cur->cell += k;
    }
    q->n = 0; /* the rest to the front (done >= where each goes) */
    for (int m = done; m < n; m++)
        cut_push(q, q->cell[m], q->e[m], q->qb[m], q->t[m], q->ea[m], q->eb[m]);
}

/* Puts the cells of the bits of m (of the lanes' from cell `first`): ayz ea vrow - sh,
 * the weights of uncut cells. */
static inline void SEG_V(put)(dep_cursor *cur, size_t first, int m, double ayz, const double *ea,
                              const double *vrow, double sh)
{
    SEG_VT e, v;
    memcpy(&e, ea, sizeof e);
    memcpy(&v, vrow, sizeof v);
    SEG_PACK(cur->w, ayz * e * v - sh, m);
    SEG_PACK_RUN(cur->cell, first, m);
    int k = __builtin_popcount((unsigned)m);
    cur->w += k;
    cur->cell += k;
}

/* Queues the cells of the bits of m (of the lanes' from cell `first` of a row): what
 * shell_cell takes of each, |r - a|^2 = qa + qay, |r - b|^2 = qb + qby, the foot
 * (dx b_x + tyz) / len and the factors ea eayz, eb ebyz. */
static inline void SEG_V(cut_push)(cut_queue *q, size_t first, int m, const double *qa,
                                   const double *qb, const double *dx, const double *ea,
                                   const double *eb, double qay, double qby, double bx,
                                   double tyz, double inv_len, double eayz, double ebyz)
{
    SEG_VT A, B, X, EA, EB;
    memcpy(&A, qa, sizeof A);
    memcpy(&B, qb, sizeof B);
    memcpy(&X, dx, sizeof X);
    memcpy(&EA, ea, sizeof EA);
    memcpy(&EB, eb, sizeof EB);
    SEG_PACK(q->e + q->n, A + qay, m);
    SEG_PACK(q->qb + q->n, B + qby, m);
    SEG_PACK(q->t + q->n, (X * bx + tyz) * inv_len, m);
    SEG_PACK(q->ea + q->n, EA * eayz, m);
    SEG_PACK(q->eb + q->n, EB * ebyz, m);
    SEG_PACK_RUN(q->cell + q->n, first, m);
    q->n += __builtin_popcount((unsigned)m);
}

/* Whether the lanes' cells of a row (their offsets dx from a along x, squared offsets qa,
 * qb from a and b along x) are within R of the segment (the bits returned) and, of those,
 * which have the whole segment within R (*uncut), given the segment's (b_x, |b|^2,
 * 1/|b|^2) and the row's (across x: (r - a).b, |r - a|^2, |r - b|^2): with t = (r - a).b
 * the distance^2 is |r - a|^2 for t <= 0, |r - b|^2 for t >= |b|^2, else |r - a|^2 -
 * t^2/|b|^2; whole when (c - a_x)^2 < R^2 - |r - a|^2 across x and the same about b.  The
 * cells past the row's end have dx = 0 and qa = qb = infinity: never within R. */
static inline int SEG_V(row_classify)(const row_reach *rr, const double *dx, const double *qa,
                                      const double *qb, int *uncut)
{
    SEG_VT A, B, X, zero = {0};
    memcpy(&A, qa, sizeof A);
    memcpy(&B, qb, sizeof B);
    memcpy(&X, dx, sizeof X);
    SEG_VT t = X * rr->bx + rr->tyz, qai = A + rr->qay;
    SEG_VT d2 = qai - t * t * rr->inv_l2;
    d2 = SEG_SEL(t >= rr->l2, B + rr->qby, d2);
    d2 = SEG_SEL(t <= zero, qai, d2);
    SEG_MT within = d2 < rr->R2, whole = within & (A < rr->ra) & (B < rr->rb);
    *uncut = SEG_BITS(&whole);
    return SEG_BITS(&within);
}

