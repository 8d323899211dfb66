/* The Gaussian's contacts on r-z grids (deposit_ring.c, which includes this twice: with
 * RING_LANES_FN and RING_SEG_FN the names of the lanes and of the deposit, and with
 * RING_AVX2 the build for processors with AVX2, whose lanes read M_{1/2}'s table four at a
 * time, ring_m_half4; the same operations lane by lane, so the same weights to the bit). */
/* Four branch points for one cell: 0 when none is within reach, else 1 with val their
 * averages (0 for the flagged ones) and *flag the bits of the lanes left to ring_value. */
static inline int RING_LANES_FN(const mimas_deposit *dp, const double *dr2, const double *dz,
                                const double *irr, double norm, double *val, int *flag)
{
    const mimas_weight *wt = dp->wt;
    ring_v4 D2, Z, IR, zero = {0, 0, 0, 0}, one = zero + 1.0;
    memcpy(&D2, dr2, sizeof D2);
    memcpy(&Z, dz, sizeof Z);
    ring_v4 e = wt->reach2 - (D2 + Z * Z), tiny = zero + 1e-20;
    ring_m4 in = e > zero;
#if RING_AVX2
    if (!_mm256_movemask_pd((__m256d)in))
#else
    if (!(in[0] | in[1] | in[2] | in[3]))
#endif
        return 0; /* no point within reach of the cell */
    memcpy(&IR, irr, sizeof IR);
    /* at least 1e-20 where positive: their powers stay normal numbers (a power
     * below 1e-220 changes nothing) */
    ring_v4 X = e * wt->inv2w2, Y = e * IR;
    X = RING_SEL(in, RING_SEL(X > tiny, X, tiny), zero);
    Y = RING_SEL(in, RING_SEL(Y > tiny, Y, tiny), zero);
    ring_v4 IA = IR / wt->inv2w2; /* 1/a, a = 4 r rho/2w^2 */
    ring_m4 fl = in & ((Y > RING_LANE_Y) | (IA > 1.0 / (4.0 * (RING_LANE_N + 2))) |
                       (X > (double)RING_XMAX));
    ring_v4 T0;
#if RING_AVX2
    T0 = (ring_v4)ring_m_half4((__m256d)X);
#else
    for (int l = 0; l < 4; l++)
        T0[l] = ring_m_half_at(X[l] < RING_XMAX ? X[l] : RING_XMAX); /* fmin, inline */
#endif
    ring_v4 U = wt->tail * T0, xn = zero + wt->tail, ian = one, s0 = zero, V;
    if (wt->shift != 0.0) { /* the shifted kernel: its shift times t_m's series too */
        ring_v4 yn = one, sa = zero;
        for (int n = 0; n <= RING_LANE_N; n++) {
            ring_v4 next = (n + 0.5) * U - xn;
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
            ring_v4 next = (n + 0.5) * U - xn;
            s0 += ring_binom[n] * ian * U;
            U = next;
            ian *= IA;
            xn *= X;
        }
        V = s0;
    }
    V = RING_SEL(in & ~fl, V, zero);
    /* the average: norm sqrt(y) V (sqrt is exact to rounding in vectors too) */
#if RING_AVX2
    ring_v4 sy = (ring_v4)_mm256_sqrt_pd((__m256d)Y);
#else
    ring_v4 sy;
    for (int l = 0; l < 4; l++)
        sy[l] = sqrt(Y[l]);
#endif
    V = norm * sy * V;
    memcpy(val, &V, sizeof V);
#if RING_AVX2
    *flag = _mm256_movemask_pd((__m256d)fl);
#else
    int bits = 0;
    for (int l = 0; l < 4; l++)
        bits |= (fl[l] != 0) << l;
    *flag = bits;
#endif
    return 1;
}

#if RING_AVX2
static
#endif
int RING_SEG_FN(const mimas_deposit *dp, const double aa[3], const double ab[3], const double am[3],
                double reach, double scale, mimas_weights *ws)
{
    const mimas_weight *wt = dp->wt;
    int lo[3], hi[3], ok;
    ws->has_grad = 0;
    if (cell_box(dp, am, reach, lo, hi, ws, &ok) || !ok)
        return ok ? MIMAS_EIO : MIMAS_OK;
    double b[3] = {ab[0] - aa[0], ab[1] - aa[1], ab[2] - aa[2]};
    const double *xs, *wsg;
    int n = dep_ring_rule(wt, sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]), &xs, &wsg);
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
            for (int q = 0; q < n; q += 4) {
                double val[4];
                int flag;
                const double *d2 = dr2 + i * n + q, *z = dz + j * n + q, *ir = irr + i * n + q;
                if (!RING_LANES_FN(dp, d2, z, ir, norm, val, &flag))
                    continue;
                if (!flag) { /* the lanes' values, in the same order */
                    sum += wq[q] * val[0];
                    sum += wq[q + 1] * val[1];
                    sum += wq[q + 2] * val[2];
                    sum += wq[q + 3] * val[3];
                    continue;
                }
                for (int l = 0; l < 4; l++) {
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
