/* The Gaussian's particles and contacts on r-z grids in lanes of RING_W (deposit_ring.c,
 * which includes this once for each build: with RING_TABLE_FN, RING_REACH_FN,
 * RING_LANES_FN, RING_CELLS_FN, RING_SEG_FN and RING_SPHERE_FN the names of the table's
 * lanes, the lanes' common set-up, the contacts' and the particles' series lanes and the
 * two deposits, RING_W the lanes' width
 * and the lane helpers, see there; with RING_NARROW, the deposit that takes the branches
 * whose rule has fewer than RING_W points). */
/* ring_m_half_at at RING_W points (X >= 0, taken as RING_XMAX beyond it), lane by lane
 * the same operations, the coefficients gathered. */
static inline void RING_TABLE_FN(const RING_VT *Xv, RING_VT *T)
{
    RING_VT zero = {0}, xmax = zero + RING_XMAX;
    RING_VT X = RING_SEL(*Xv < xmax, *Xv, xmax);
    RING_IT m = __builtin_convertvector(X * RING_STEP, RING_IT), top = {0};
    top += RING_STEP * RING_XMAX - 1;
    RING_IT below = m < top;
    m = (m & below) | (top & ~below);
    RING_VT t = X - (__builtin_convertvector(m, RING_VT) + 0.5) / RING_STEP, t2 = t * t;
    RING_IT row = m * (RING_DEG + 1);
    const double *base = &ring_m_half[0][0];
    RING_VT c[RING_DEG + 1];
    for (int k = 0; k <= RING_DEG; k++)
        RING_GATHER(base + k, &row, &c[k]);
    RING_VT lo = (c[0] + c[1] * t) + t2 * (c[2] + c[3] * t);
    RING_VT hi = (c[4] + c[5] * t) + t2 * (c[6] + c[7] * t);
    *T = lo + t2 * t2 * hi;
}

/* The lanes' series variables from e = R^2 - D0^2 and 1/(4 r rho) (irr): 0 when no lane
 * is within reach (e > 0), else 1 with *in those that are, X = e/2w^2 and y = e irr (at
 * least 1e-20 where positive: their powers stay normal numbers, and a power below 1e-220
 * changes nothing; 0 outside reach), 1/a = irr 2w^2, T_0 = M_{1/2}(X) from the table, and
 * *fl the lanes within reach left to ring_value (y > RING_LANE_Y, a < 4 (RING_LANE_N + 2),
 * X > RING_XMAX). */
static inline int RING_REACH_FN(const mimas_weight *wt, const RING_VT *e, const double *irr,
                                RING_MT *in, RING_MT *fl, RING_VT *X, RING_VT *Y, RING_VT *IA,
                                RING_VT *T0)
{
    RING_VT IR, zero = {0}, tiny = zero + 1e-20;
    *in = *e > zero;
    if (!RING_ANY(in))
        return 0;
    memcpy(&IR, irr, sizeof IR);
    *X = *e * wt->inv2w2;
    *Y = *e * IR;
    *X = RING_SEL(*in, RING_SEL(*X > tiny, *X, tiny), zero);
    *Y = RING_SEL(*in, RING_SEL(*Y > tiny, *Y, tiny), zero);
    *IA = IR / wt->inv2w2; /* 1/a, a = 4 r rho/2w^2 */
    *fl = *in & ((*Y > RING_LANE_Y) | (*IA > 1.0 / (4.0 * (RING_LANE_N + 2))) |
                 (*X > (double)RING_XMAX));
    RING_TABLE_FN(X, T0);
    return 1;
}

/* The second tier (deposit_ring.c) at RING_W lanes: *V = s0 - 2 shift sa as in
 * RING_LANES_FN. */
static inline void RING_TIER2_FN(const mimas_deposit *dp, const RING_VT *X, const RING_VT *Y,
                                 RING_VT *V)
{
    const mimas_weight *wt = dp->wt;
    RING_VT zero = {0}, term = zero + ring_inv_half[RING_TIER2_N + 1], T = term, s0 = zero;
    for (int j = RING_TIER2_N + 2; j <= RING_TIER2_N + 1 + dp->ring_terms; j++) {
        term *= *X * ring_inv_half[j];
        T += term;
    }
    T *= wt->tail;
    for (int n = RING_TIER2_N; n >= 0; n--) {
        RING_VT Tn = (wt->tail + *X * T) * ring_inv_half[n];
        s0 = s0 * *Y + ring_binom[n] * Tn;
        T = Tn;
    }
    *V = s0;
    if (wt->shift != 0.0) {
        RING_VT sa = zero;
        for (int n = RING_TIER2_N; n >= 0; n--)
            sa = sa * *Y + 0.5 * ring_binom[n] * ring_inv_half[n]; /* c_n/(2n + 1) */
        *V = s0 - 2.0 * wt->shift * sa;
    }
}

/* RING_W branch points for one cell: 0 when none is within reach, else 1 with val their
 * averages (0 for the flagged ones) and *flag the bits of the lanes left to ring_value
 * (those of the first tier's flagged with y above RING_TIER2_Y, or all where there is no
 * second tier). */
static inline int RING_LANES_FN(const mimas_deposit *dp, const double *dr2, const double *dz,
                                const double *irr, double norm, double *val, int *flag)
{
    const mimas_weight *wt = dp->wt;
    RING_VT D2, Z, zero = {0}, one = zero + 1.0, X, Y, IA, T0;
    RING_MT in, fl;
    memcpy(&D2, dr2, sizeof D2);
    memcpy(&Z, dz, sizeof Z);
    RING_VT e = wt->reach2 - (D2 + Z * Z);
    if (!RING_REACH_FN(wt, &e, irr, &in, &fl, &X, &Y, &IA, &T0))
        return 0; /* no point within reach of the cell */
    RING_VT U = wt->tail * T0, xn = zero + wt->tail, ian = one, s0 = zero, V;
    if (wt->shift != 0.0) { /* the shifted kernel: its shift times t_m's series too */
        RING_VT yn = one, sa = zero;
        for (int n = 0; n <= RING_LANE_N; n++) {
            RING_VT next = (n + 0.5) * U - xn;
            s0 += ring_binom[n] * ian * U;
            sa += 0.5 * ring_binom[n] * ring_inv_half[n] * yn; /* c_n/(2n + 1) */
            U = next;
            ian *= IA;
            xn *= X;
            yn *= Y;
        }
        V = s0 - 2.0 * wt->shift * sa;
    } else { /* s0 - 0 sa: s0 itself */
        for (int n = 0; n <= RING_LANE_N; n++) {
            RING_VT next = (n + 0.5) * U - xn;
            s0 += ring_binom[n] * ian * U;
            U = next;
            ian *= IA;
            xn *= X;
        }
        V = s0;
    }
    V = RING_SEL(in & ~fl, V, zero);
    if (dp->ring_terms) {
        RING_MT f2 = fl & (Y <= RING_TIER2_Y);
        if (RING_ANY(&f2)) {
            RING_VT V2;
            RING_TIER2_FN(dp, &X, &Y, &V2);
            V = RING_SEL(f2, V2, V);
            fl &= ~f2;
        }
    }
    /* the average: norm sqrt(y) V (sqrt is exact to rounding in vectors too) */
    RING_VT sy;
    RING_SQRT(&Y, &sy);
    V = norm * sy * V;
    memcpy(val, &V, sizeof V);
    *flag = RING_BITS(&fl);
    return 1;
}

/* The rule's sum at one cell over n nodes (a multiple of RING_W): their offsets' squares d2
 * and z offsets z, 1/(4 r rho) ir, distances from the axis rho and weights w. */
static inline double RING_SUM_FN(const mimas_deposit *dp, double r, const double *d2,
                                 const double *z, const double *ir, const double *rho,
                                 const double *w, int n, double norm)
{
    double sum = 0.0;
    for (int q = 0; q < n; q += RING_W) {
        double val[RING_W];
        int flag;
        if (!RING_LANES_FN(dp, d2 + q, z + q, ir + q, norm, val, &flag))
            continue;
        if (!flag) { /* the lanes' values, in the same order */
            for (int l = 0; l < RING_W; l++)
                sum += w[q + l] * val[l];
            continue;
        }
        for (int l = 0; l < RING_W; l++) {
            double v = flag >> l & 1
                           ? ring_value(dp->wt, r, rho[q + l], z[q + l], d2[q + l], NULL)
                           : val[l];
            sum += w[q + l] * v;
        }
    }
    return sum;
}

int RING_SEG_FN(const mimas_deposit *dp, const double aa[3], const double ab[3], const double am[3],
                double reach, double scale, mimas_weights *ws)
{
    const mimas_weight *wt = dp->wt;
    /* the branch: its rule along the whole of it and, where an edge of the average is near,
     * the rule split there (ring_edges.h) */
    mimas_ring_branch br;
    mimas_ring_branch_init(&br, wt, aa, ab);
    const double *b = br.b, *xs, *wsg;
    int n = dep_ring_rule(wt, br.len, &xs, &wsg);
#ifdef RING_NARROW
    if (n % RING_W)
        return RING_NARROW(dp, aa, ab, am, reach, scale, ws);
#endif
    int lo[3], hi[3], ok;
    ws->has_grad = 0;
    if (cell_box(dp, am, reach, lo, hi, ws, &ok) || !ok)
        return ok ? MIMAS_EIO : MIMAS_OK;
    int nr = hi[0] - lo[0] + 1, nz = hi[2] - lo[2] + 1;
    /* per branch point q: rho_q, z_q, its weight; per column and row: the centre; per
     * column and point: the offset's square and 1/(4 r rho) (0 on the axis: flagged); per
     * row and point: the offset */
    double *t = mimas_weights_scratch(ws, 3 * (size_t)n + nr + nz + (size_t)n * (2 * nr + nz));
    if (!t)
        return MIMAS_EIO;
    double *rho = t, *zq = t + n, *wq = t + 2 * n, *rc = t + 3 * n, *zc = rc + nr;
    double *dr2 = zc + nz, *irr = dr2 + (size_t)n * nr, *dz = irr + (size_t)n * nr;
    for (int q = 0; q < n; q++) {
        double s, p[3];
        gl_node(xs, wsg, n, q, 0.0, 1.0, &s, &wq[q]);
        for (int m = 0; m < 3; m++)
            p[m] = aa[m] + s * b[m];
        rho[q] = hypot(p[0], p[1]);
        zq[q] = p[2];
    }
    for (int i = 0; i < nr; i++) {
        rc[i] = dep_centre(dp, 0, lo[0] + i);
        for (int q = 0; q < n; q++) {
            double rr = 4.0 * rc[i] * rho[q];
            dr2[i * n + q] = (rc[i] - rho[q]) * (rc[i] - rho[q]);
            irr[i * n + q] = rr > 0 ? 1.0 / rr : INFINITY;
        }
    }
    for (int j = 0; j < nz; j++) {
        zc[j] = dep_centre(dp, 2, lo[2] + j);
        for (int q = 0; q < n; q++)
            dz[j * n + q] = zc[j] - zq[q];
    }
    mimas_ring_nodes nd;
    int idx[3] = {0, lo[1], 0};
    double norm = wt->coef / M_PI;
    for (int j = 0; j < nz; j++)
        for (int i = 0; i < nr; i++) {
            int ne = mimas_ring_edge_nodes(&br, wt, rc[i], zc[j], &nd);
            double sum = ne < 0 ? RING_SUM_FN(dp, rc[i], dr2 + i * n, dz + j * n, irr + i * n,
                                              rho, wq, n, norm)
                                : RING_SUM_FN(dp, rc[i], nd.dr2, nd.dz, nd.irr, nd.rho, nd.w,
                                              ne, norm);
            if (sum == 0.0)
                continue;
            idx[0] = lo[0] + i;
            idx[2] = lo[2] + j;
            dep_put(ws, mimas_grid_index(dp->grid, idx), sum * scale);
        }
    return MIMAS_OK;
}

/* RING_W cells of a row (centres rc, offsets' squares dr2 = (r - rho)^2, 1/(4 r rho) irr,
 * all at the row's z offset dz) for a particle at distance rho from the axis: 0 when none is
 * within reach, else 1 with val the averages and, with gradients, gr and gz their
 * derivatives in r and z (0 for the flagged lanes: those left to ring_value, whose bits are
 * *flag).  The series of mimas_gauss_ring_short with RING_LANE_N + 1 terms as in
 * RING_LANES_FN, with the gradient's I_1 beside I_0 and the arc end's term (arc_end_grad):
 * d/dr = k (2 (r - rho) I_0 + 4 rho I_1) - f(R) (r - rho cos t_m)/(pi r rho sin t_m),
 * d/ddz = k 2 dz I_0 - f(R) dz/(pi r rho sin t_m), k = -coef/(2 w^2 pi). */
static inline int RING_CELLS_FN(const mimas_weight *wt, const double *rc, const double *dr2,
                                const double *irr, double dz, double rho, int with_grad,
                                double *val, double *gr, double *gz, int *flag)
{
    RING_VT D2, R, zero = {0}, one = zero + 1.0, X, Y, IA, T0;
    RING_MT in, fl;
    memcpy(&D2, dr2, sizeof D2);
    RING_VT e = wt->reach2 - (D2 + dz * dz);
    if (!RING_REACH_FN(wt, &e, irr, &in, &fl, &X, &Y, &IA, &T0))
        return 0;
    RING_MT ok = in & ~fl;
    RING_VT U = wt->tail * T0, xn = zero + wt->tail, ian = one, yn = one;
    RING_VT s0 = zero, s1 = zero, sa = zero;
    int shifted = wt->shift > 0;
    for (int n = 0; n <= RING_LANE_N; n++) {
        RING_VT next = (n + 0.5) * U - xn;
        s0 += ring_binom[n] * ian * U;
        ian *= IA;
        s1 += ring_binom[n] * ian * next; /* only the gradient's */
        if (shifted) {
            sa += 0.5 * ring_binom[n] * ring_inv_half[n] * yn;
            yn *= Y;
        }
        U = next;
        xn *= X;
    }
    RING_VT sy;
    RING_SQRT(&Y, &sy);
    RING_VT I0 = sy * s0, V = wt->coef / M_PI * I0;
    if (shifted) /* minus (coef/pi) shift t_m, t_m = 2 asin(sqrt(y)) */
        V -= wt->coef / M_PI * wt->shift * 2.0 * (sy * sa);
    V = RING_SEL(ok, V, zero);
    memcpy(val, &V, sizeof V);
    if (with_grad) {
        memcpy(&R, rc, sizeof R);
        double k = -wt->coef * wt->inv2w2 / M_PI, fR = wt->coef * (wt->tail - wt->shift);
        RING_VT I1 = sy * s1, Q = Y * (one - Y), sq;
        RING_SQRT(&Q, &sq);
        RING_VT sin_tm = 2.0 * sq, cos_tm = one - 2.0 * Y;
        RING_VT G0 = k * (2.0 * (R - rho) * I0 + 4.0 * rho * I1), G1 = k * 2.0 * dz * I0;
        if (fR != 0.0) {
            RING_VT den = R * rho * RING_SEL(ok, sin_tm, one);
            G0 += fR * (-(R - rho * cos_tm) / den) / M_PI;
            G1 += fR * (-dz / den) / M_PI;
        }
        G0 = RING_SEL(ok, G0, zero);
        G1 = RING_SEL(ok, G1, zero);
        memcpy(gr, &G0, sizeof G0);
        memcpy(gz, &G1, sizeof G1);
    }
    *flag = RING_BITS(&fl);
    return 1;
}

int RING_SPHERE_FN(const mimas_deposit *dp, const double a[3], int with_grad, double scale,
                   mimas_weights *ws)
{
    const mimas_weight *wt = dp->wt;
    int lo[3], hi[3], ok;
    ws->has_grad = with_grad;
    if (cell_box(dp, a, mimas_weight_reach(wt), lo, hi, ws, &ok) || !ok)
        return ok ? MIMAS_EIO : MIMAS_OK;
    /* per column (padded to whole lanes with columns out of reach): the centre, the
     * offset's square and 1/(4 r rho) (infinite on the axis: flagged); per row: the offset */
    int nr = hi[0] - lo[0] + 1, nz = hi[2] - lo[2] + 1, np = (nr + RING_W - 1) / RING_W * RING_W;
    double *t = mimas_weights_scratch(ws, 3 * (size_t)np + (size_t)nz);
    if (!t)
        return MIMAS_EIO;
    double *rc = t, *dr2 = t + np, *irr = t + 2 * np, *dz = t + 3 * np;
    double rho = hypot(a[0], a[1]);
    for (int i = 0; i < np; i++) {
        rc[i] = i < nr ? dep_centre(dp, 0, lo[0] + i) : 0.0;
        dr2[i] = i < nr ? (rc[i] - rho) * (rc[i] - rho) : INFINITY;
        double rr = 4.0 * rc[i] * rho;
        irr[i] = rr > 0 ? 1.0 / rr : INFINITY;
    }
    for (int j = 0; j < nz; j++)
        dz[j] = dep_centre(dp, 2, lo[2] + j) - a[2];
    int idx[3] = {0, lo[1], 0};
    for (int j = 0; j < nz; j++)
        for (int i0 = 0; i0 < nr; i0 += RING_W) {
            double val[RING_W], gr[RING_W], gz[RING_W];
            int flag;
            if (!RING_CELLS_FN(wt, rc + i0, dr2 + i0, irr + i0, dz[j], rho, with_grad, val, gr,
                               gz, &flag))
                continue;
            for (int l = 0; l < RING_W && i0 + l < nr; l++) {
                int i = i0 + l;
                double v, g[2] = {0, 0};
                if (flag >> l & 1) {
                    v = ring_value(wt, rc[i], rho, dz[j], dr2[i], with_grad ? g : NULL);
                } else {
                    v = val[l];
                    if (with_grad)
                        g[0] = gr[l], g[1] = gz[l];
                }
                if (v == 0.0 && g[0] == 0.0 && g[1] == 0.0)
                    continue;
                idx[0] = lo[0] + i;
                idx[2] = lo[2] + j;
                size_t cell = mimas_grid_index(dp->grid, idx);
                if (with_grad)
                    dep_put_grad(ws, cell, v * scale, g[0] * scale, 0.0, g[1] * scale);
                else
                    dep_put(ws, cell, v * scale);
            }
        }
    return MIMAS_OK;
}

/* the parameters of this build, for the next */
#undef RING_W
#undef RING_VT
#undef RING_MT
#undef RING_IT
#undef RING_BITS
#undef RING_GATHER
#undef RING_SQRT
#undef RING_TABLE_FN
#undef RING_REACH_FN
#undef RING_LANES_FN
#undef RING_TIER2_FN
#undef RING_CELLS_FN
#undef RING_SUM_FN
#undef RING_SEG_FN
#undef RING_SPHERE_FN
#undef RING_NARROW
