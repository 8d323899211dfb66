/* The Gaussian's contacts on r-z grids (deposit_ring.c, which includes this once for each
 * build: with RING_TABLE_FN, RING_LANES_FN and RING_SEG_FN the names of the table's lanes,
 * the series' lanes and the deposit, RING_W the lanes' width and the lane helpers, see
 * there; with RING_NARROW, the deposit that takes the branches whose rule has fewer than
 * RING_W points). */
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

/* RING_W branch points for one cell: 0 when none is within reach, else 1 with val their
 * averages (0 for the flagged ones) and *flag the bits of the lanes left to ring_value. */
static inline int RING_LANES_FN(const mimas_deposit *dp, const double *dr2, const double *dz,
                                const double *irr, double norm, double *val, int *flag)
{
    const mimas_weight *wt = dp->wt;
    RING_VT D2, Z, IR, zero = {0}, one = zero + 1.0;
    memcpy(&D2, dr2, sizeof D2);
    memcpy(&Z, dz, sizeof Z);
    RING_VT e = wt->reach2 - (D2 + Z * Z), tiny = zero + 1e-20;
    RING_MT in = e > zero;
    if (!RING_ANY(&in))
        return 0; /* no point within reach of the cell */
    memcpy(&IR, irr, sizeof IR);
    /* at least 1e-20 where positive: their powers stay normal numbers (a power
     * below 1e-220 changes nothing) */
    RING_VT X = e * wt->inv2w2, Y = e * IR;
    X = RING_SEL(in, RING_SEL(X > tiny, X, tiny), zero);
    Y = RING_SEL(in, RING_SEL(Y > tiny, Y, tiny), zero);
    RING_VT IA = IR / wt->inv2w2; /* 1/a, a = 4 r rho/2w^2 */
    RING_MT fl = in & ((Y > RING_LANE_Y) | (IA > 1.0 / (4.0 * (RING_LANE_N + 2))) |
                       (X > (double)RING_XMAX));
    RING_VT T0;
    RING_TABLE_FN(&X, &T0);
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
    /* the average: norm sqrt(y) V (sqrt is exact to rounding in vectors too) */
    RING_VT sy;
    RING_SQRT(&Y, &sy);
    V = norm * sy * V;
    memcpy(val, &V, sizeof V);
    *flag = RING_BITS(&fl);
    return 1;
}

int RING_SEG_FN(const mimas_deposit *dp, const double aa[3], const double ab[3], const double am[3],
                double reach, double scale, mimas_weights *ws)
{
    const mimas_weight *wt = dp->wt;
    double b[3] = {ab[0] - aa[0], ab[1] - aa[1], ab[2] - aa[2]};
    const double *xs, *wsg;
    int n = dep_ring_rule(wt, sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]), &xs, &wsg);
#ifdef RING_NARROW
    if (n % RING_W)
        return RING_NARROW(dp, aa, ab, am, reach, scale, ws);
#endif
    int lo[3], hi[3], ok;
    ws->has_grad = 0;
    if (cell_box(dp, am, reach, lo, hi, ws, &ok) || !ok)
        return ok ? MIMAS_EIO : MIMAS_OK;
    int nr = hi[0] - lo[0] + 1, nz = hi[2] - lo[2] + 1;
    /* per branch point q: rho_q, z_q, its weight; per column and point: the offset's
     * square and 1/(4 r rho) (0 on the axis: flagged); per row and point: the offset */
    double *t = mimas_weights_scratch(ws, 3 * (size_t)n + nr + (size_t)n * (2 * nr + nz));
    if (!t)
        return MIMAS_EIO;
    double *rho = t, *zq = t + n, *wq = t + 2 * n, *rc = t + 3 * n, *dr2 = rc + nr;
    double *irr = dr2 + (size_t)n * nr, *dz = irr + (size_t)n * nr;
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
        double zc = dep_centre(dp, 2, lo[2] + j);
        for (int q = 0; q < n; q++)
            dz[j * n + q] = zc - zq[q];
    }
    int idx[3] = {0, lo[1], 0};
    double norm = wt->coef / M_PI;
    for (int j = 0; j < nz; j++)
        for (int i = 0; i < nr; i++) {
            double sum = 0.0;
            for (int q = 0; q < n; q += RING_W) {
                double val[RING_W];
                int flag;
                const double *d2 = dr2 + i * n + q, *z = dz + j * n + q, *ir = irr + i * n + q;
                if (!RING_LANES_FN(dp, d2, z, ir, norm, val, &flag))
                    continue;
                if (!flag) { /* the lanes' values, in the same order */
                    for (int l = 0; l < RING_W; l++)
                        sum += wq[q + l] * val[l];
                    continue;
                }
                for (int l = 0; l < RING_W; l++) {
                    double v = flag >> l & 1
                                   ? ring_value(wt, rc[i], rho[q + l], z[l], d2[l], NULL)
                                   : val[l];
                    sum += wq[q + l] * v;
                }
            }
            if (sum == 0.0)
                continue;
            idx[0] = lo[0] + i;
            idx[2] = lo[2] + j;
            dep_put(ws, mimas_grid_index(dp->grid, idx), sum * scale);
        }
    return MIMAS_OK;
}

/* the parameters of this build, for the next */
#undef RING_W
#undef RING_VT
#undef RING_MT
#undef RING_IT
#undef RING_ANY
#undef RING_BITS
#undef RING_GATHER
#undef RING_SQRT
#undef RING_TABLE_FN
#undef RING_LANES_FN
#undef RING_SEG_FN
#undef RING_NARROW
