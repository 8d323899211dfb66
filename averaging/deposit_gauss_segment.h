/* The Gaussian line integral of a segment on a Cartesian x-y-z grid (deposit_gauss.c,
 * which includes this three times: SEG_FN the function's name, SEG_LANES 1 for the build
 * for any processor, 4 for the one with AVX2 and 8 for the one with AVX-512, which
 * classify a row's cells and evaluate the cut cells that many at a time through the lane
 * helpers of deposit_gauss_lanes.h (row_classify4, put4, cut_push4, cut_flush4,
 * node_sums4 and the same with 8); the same operations cell by cell, so the same weights
 * to the bit). */
/* rows along x padded to a whole number of lanes, and of four cells (node_sums) */
#define SEG_PAD (SEG_LANES > 4 ? SEG_LANES : 4)
/* The uncut part: with d = r - a (the cell centre from a), node s of the rule and
 * k = 1/2w^2,
 *   e^{-|d - s b|^2 k} = e^{-|d|^2 k} e^{(2 s d_0.b - s^2 |b|^2) k} prod_x X_x(s)^{i_x},
 * d_0 the offset of the first cell of the box, i_x the cell's index in it and
 * X_x(s) = e^{2 s b_x h_x k}: per node one exponential and one per direction, the
 * powers by products.  The rows along x are summed over the nodes 4 cells at a time (SEG_PAD
 * in the vector builds). */
int SEG_FN(const mimas_deposit *dp, const double a[3], const double b[3], mimas_weights *ws)
{
    const mimas_weight *wt = dp->wt;
    const mimas_grid *g = dp->grid;
    double bv[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double l2 = bv[0] * bv[0] + bv[1] * bv[1] + bv[2] * bv[2], len = sqrt(l2);
    double R = mimas_weight_reach(wt), R2 = wt->reach2, kap = wt->inv2w2;
    if (!(len > 0) || wt->cutoff > 5.0)
        return -1;
    /* the cells within R of the segment's bounding box */
    int lo[3], hi[3], n[3];
    for (int d = 0; d < 3; d++) {
        double lo_d = a[d] < b[d] ? a[d] : b[d], hi_d = a[d] < b[d] ? b[d] : a[d];
        if (!dep_index_range(dp, d, lo_d - R, hi_d + R, &lo[d], &hi[d]))
            return MIMAS_OK;
        n[d] = hi[d] - lo[d] + 1;
    }
    const double *xs, *wsg;
    int pieces, per = line_rule(len / wt->w, wt->cutoff, &xs, &wsg, &pieces);
    int nq = per * pieces, nqp = (nq + 3) & ~3, n0p = (n[0] + SEG_PAD - 1) & ~(SEG_PAD - 1);
    if (nq > SEG_MAXNODE)
        return -1;
    double tau0 = 0.0; /* d_0.b */
    for (int d = 0; d < 3; d++)
        tau0 += (dep_centre(dp, d, lo[d]) - a[d]) * bv[d];
    /* the largest exponent of the factors: beyond the range of doubles, cell by cell */
    double big = fabs(2.0 * tau0 * kap) + l2 * kap;
    for (int d = 0; d < 3; d++) {
        double d0 = dep_centre(dp, d, lo[d]) - a[d];
        big += fabs(2.0 * bv[d] * dp->h[d] * kap) * n[d] + fabs(2.0 * bv[d] * d0 * kap);
    }
    if (big > 600.0)
        return -1;
    if (mimas_weights_reserve(ws, (size_t)n[0] * n[1] * n[2] + 8)) /* + 8: put8 */
        return MIMAS_EIO;
    /* per direction: offsets from a, squared offsets from a and b, the Gaussian factors
     * about a and b; the nodes' powers X^i: x node-major (rows padded to 4), y and z
     * node-minor; the row's sums; the row scalars of a plane (plane_rows_at) */
    size_t total = (size_t)n0p + n[1] + n[2]; /* x's rows padded (SEG_PAD) */
    int n1p = (n[1] + 3) & ~3;
    size_t nbuf = 5 * total + (size_t)nqp * ((size_t)n0p + n[1] + n[2]) + (size_t)n0p +
                  5 * (size_t)n1p;
#if SEG_LANES > 1
    /* the cut cells queued: a plane's at most, and room for a lane helper's stores */
    size_t qcap = (size_t)n0p * n[1] + 2 * SEG_LANES;
    nbuf += 6 * qcap;
#endif
    double *buf = mimas_weights_scratch(ws, nbuf);
    if (!buf)
        return MIMAS_EIO;
    double *dx[3], *qa[3], *qb[3], *ea[3], *eb[3];
    double sq[SEG_MAXNODE], wq[SEG_MAXNODE], eyz[SEG_MAXNODE];
    for (int p = 0, k = 0; p < pieces; p++)
        for (int m = 0; m < per; m++, k++) {
            gl_node(xs, wsg, per, m, (double)p / pieces, (double)(p + 1) / pieces, &sq[k], &wq[k]);
            wq[k] *= exp((2.0 * sq[k] * tau0 - sq[k] * sq[k] * l2) * kap);
        }
    for (int k = nq; k < nqp; k++)
        sq[k] = wq[k] = 0.0;
    double *ex0 = buf + 5 * total, *exy = ex0 + (size_t)nqp * n0p, *exz = exy + (size_t)nqp * n[1];
    double *restrict vrow = exz + (size_t)nqp * n[2];
    double *pbuf = vrow + n0p;
    plane_rows pr = {pbuf, pbuf + n1p, pbuf + 2 * n1p, pbuf + 3 * n1p, pbuf + 4 * n1p};
#if SEG_LANES > 1
    double *qbuf = pbuf + 5 * n1p;
    cut_queue cq = {(size_t *)(void *)(qbuf + 5 * qcap), qbuf, qbuf + qcap, qbuf + 2 * qcap,
                    qbuf + 3 * qcap, qbuf + 4 * qcap, 0};
#endif
    for (int d = 0, o = 0; d < 3; d++) {
        dx[d] = buf + o;
        qa[d] = buf + total + o;
        qb[d] = buf + 2 * total + o;
        ea[d] = buf + 3 * total + o;
        eb[d] = buf + 4 * total + o;
        for (int i = 0; i < n[d]; i++) {
            double c = dep_centre(dp, d, lo[d] + i), da = c - a[d], db = c - b[d];
            dx[d][i] = da;
            qa[d][i] = da * da;
            qb[d][i] = db * db;
        }
        for (int i = n[d]; d == 0 && i < n0p; i++) { /* never within R: see row_classify4 */
            dx[d][i] = ea[d][i] = eb[d][i] = 0.0;
            qa[d][i] = qb[d][i] = INFINITY;
        }
        gauss_row(dp, d, lo[d], n[d], a[d], ea[d]);
        /* X(s) for the node pairs s = c_p -+ x_m of each piece p: e^{c_p beta} e^{-+x_m beta},
         * one exponential per piece and per pair */
        double beta = 2.0 * bv[d] * dp->h[d] * kap, X[SEG_MAXNODE];
        int half = per / 2;
        for (int p = 0; p < pieces; p++) {
            double cp = exp((p + 0.5) / pieces * beta);
            for (int m = 0; m < half; m++) {
                double xm = exp(0.5 / pieces * xs[m] * beta);
                X[p * per + m] = cp / xm;        /* gl_node: the first half are the -x_m */
                X[p * per + half + m] = cp * xm;
            }
        }
        for (int k = nq; k < nqp; k++)
            X[k] = 0.0;
        node_powers(X, nqp, n[d], d == 0 ? n0p : 0, d == 0 ? ex0 : (d == 1 ? exy : exz));
        gauss_row(dp, d, lo[d], n[d], b[d], eb[d]);
        o += d == 0 ? n0p : n[d];
    }
    dep_cursor cur = dep_cursor_at(ws);
    double coef = wt->coef, sh = coef * wt->shift, pyz = bv[1] * bv[1] + bv[2] * bv[2];
    double inv_l2 = 1.0 / l2, inv_len = 1.0 / len, inv_pyz = pyz > 0 ? 1.0 / pyz : 0.0;
    shell_consts sc = {R2, 1.0 / (M_SQRT2 * wt->w), wt->tail,
                       coef * sqrt(M_PI / 2.0) * wt->w / len, coef * wt->shift / len};
#if SEG_LANES > 1
    row_reach rr = {bv[0], l2, inv_l2, R2, 0.0, 0.0, 0.0, 0.0, 0.0};
#endif
    for (int kz = 0; kz < n[2]; kz++) {
        size_t plane = (size_t)lo[0] + (size_t)g->n[0] * (size_t)g->n[1] * (size_t)(lo[2] + kz);
        plane_rows_at(dx[1], qa[1], qb[1], dx[2][kz], qa[2][kz], qb[2][kz], bv, inv_pyz, n1p, &pr);
        for (int j = 0; j < n[1]; j++) {
            /* the row (a line along x) is out of reach when the segment's projection
             * on the y-z plane stays R or more from the row's (y, z) */
            if (pr.rr[j] >= R2)
                continue;
            double qay = pr.qay[j], qby = pr.qby[j], tyz = pr.tyz[j];
            size_t row = plane + (size_t)g->n[0] * (size_t)(lo[1] + j);
#if SEG_LANES > 1
            /* The cells within R of the segment, and of those the ones with the whole
             * segment within R (the two balls' intersection), SEG_LANES at a time
             * (row_classify4, the same tests as a cell at a time): the latter by the
             * nodes, the others queued for the closed form, SEG_LANES at a time
             * (cut_flush4). */
            if (cq.n + n[0] > (int)qcap - SEG_LANES)
                SEG_V(cut_flush)(&cq, &sc, len, 0, &cur);
            row_reach_across(&rr, qay, qby, tyz);
            double ayz = 0.0, eayz = ea[1][j] * ea[2][kz], ebyz = eb[1][j] * eb[2][kz];
            int have_eyz = 0;
            for (int c = 0; c < n[0]; c += SEG_LANES) {
                int uncut,
                    in = SEG_V(row_classify)(&rr, dx[0] + c, qa[0] + c, qb[0] + c, &uncut);
                if (uncut) {
                    if (!have_eyz) {
                        const double *ey = exy + (size_t)j * nqp, *ez = exz + (size_t)kz * nqp;
                        for (int k = 0; k < nqp; k++)
                            eyz[k] = wq[k] * ey[k] * ez[k];
                        ayz = coef * ea[1][j] * ea[2][kz];
                        have_eyz = 1;
                    }
                    /* the uncut line integral of the lanes' cells over the nodes */
                    SEG_V(node_sums)(ex0, (size_t)n0p, eyz, nq, c, vrow);
                    SEG_V(put)(&cur, row + (size_t)c, uncut, ayz, ea[0] + c, vrow + c, sh);
                }
                if (in & ~uncut)
                    SEG_V(cut_push)(&cq, row + (size_t)c, in & ~uncut, qa[0] + c, qb[0] + c,
                                    dx[0] + c, ea[0] + c, eb[0] + c, qay, qby, bv[0], tyz,
                                    inv_len, eayz, ebyz);
            }
#else
            /* The cells within R of the segment form an interval of the row (the
             * distance to a segment is convex along a line), holding the point nearest
             * to the segment, x = a + ty b: walk out from the cells on either side of
             * it.  The cells with the whole segment within R (the two balls'
             * intersection) are an interval inside it. */
            row_geom rg = {qa[0], qb[0], dx[0], qay, qby, tyz, bv[0], l2, inv_l2, R2};
            int c0, c1;
            if (!reach_span(&rg, (pr.ty[j] * bv[0] - dx[0][0]) / dp->h[0], n[0], &c0, &c1))
                continue;
            double ra = R2 - qay, rb = R2 - qby;
            int i0 = c0, i1 = c1;
            while (i0 <= i1 && !(qa[0][i0] < ra && qb[0][i0] < rb))
                i0++;
            while (i1 >= i0 && !(qa[0][i1] < ra && qb[0][i1] < rb))
                i1--;
            if (i0 <= i1) {
                /* the uncut line integral, 4 cells at a time over the nodes */
                const double *ey = exy + (size_t)j * nqp, *ez = exz + (size_t)kz * nqp;
                for (int k = 0; k < nqp; k++)
                    eyz[k] = wq[k] * ey[k] * ez[k];
                node_sums(ex0, (size_t)n0p, eyz, nq, i0 & ~3, (i1 + 4) & ~3, vrow);
                double ayz = coef * ea[1][j] * ea[2][kz];
                for (int i = i0; i <= i1; i++)
                    dep_cursor_put(&cur, row + (size_t)i, ayz * ea[0][i] * vrow[i] - sh);
            } else {
                i0 = c1 + 1; /* no such cells: every cell of [c0, c1] is cut */
                i1 = c1;
            }
            /* the others, where the cut ball cuts the segment: [c0, i0) and (i1, c1] */
            double ebyz = eb[1][j] * eb[2][kz], eayz = ea[1][j] * ea[2][kz];
            for (int i = c0; i <= c1; i++) {
                if (i == i0) {
                    i = i1;
                    continue;
                }
                double qai = qa[0][i] + qay, qbi = qb[0][i] + qby;
                double t = dx[0][i] * bv[0] + tyz;
                double v = shell_cell(&sc, qai < R2, qbi < R2, t * inv_len, qai, len,
                                      ea[0][i] * eayz, eb[0][i] * ebyz);
                if (v != 0.0)
                    dep_cursor_put(&cur, row + (size_t)i, v);
            }
#endif
        }
    }
#if SEG_LANES > 1
    SEG_V(cut_flush)(&cq, &sc, len, 1, &cur);
#endif
    dep_cursor_done(ws, &cur);
    return MIMAS_OK;
}
#undef SEG_PAD
