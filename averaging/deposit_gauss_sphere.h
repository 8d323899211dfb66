/* The Gaussian's particle on a Cartesian x-y-z grid (deposit_gauss.c; docs/fields.md, "The
 * Gaussian on x-y-z grids"): inside the cut ball, the product of the three rows of factors
 * of sphere_setup at the cell centres, and with with_grad its gradient.  deposit_gauss.c
 * includes this once for each build, as SPH_FN with SEG_LANES lanes (1: any processor;
 * 4, 8: under the #pragma GCC target of the vector builds, with lanes_x86.h's SEG_VT,
 * SEG_MT, SEG_BITS and deposit_gauss.c's SEG_PACK and SEG_PACK_RUN).
 *
 * A row's cells along x are taken SEG_LANES at a time: those inside the ball moved to the
 * front of the vector (SEG_PACK, SEG_PACK_RUN) and the whole vector stored at the end of
 * the list, which has room for SEG_LANES more; the list grows by the number inside.  The
 * portable build, a cell at a time, stores every cell and lets the list grow by one where
 * it is inside.  No branch depends on where a row's cells enter or leave the ball: with
 * the ends of each row's interval tested cell by cell, mispredicted branches made a
 * particle at a random place cost 1.5 times as long.  Lane by lane the products of the
 * portable build: every build gives the same cells in the same order, with the same
 * weights and gradients to the bit. */

int SPH_FN(const mimas_deposit *dp, const double x[3], int with_grad, mimas_weights *ws)
{
    sphere_box sb;
    int rc = sphere_setup(dp, x, SEG_LANES, ws, &sb);
    if (rc)
        return rc > 0 ? MIMAS_OK : rc;
    const mimas_weight *wt = dp->wt;
    const mimas_grid *g = dp->grid;
    double coef = wt->coef, sh = coef * wt->shift, R2 = wt->reach2;
    const double *e0 = sb.e[0], *q0 = sb.q[0], *gf0 = sb.gf[0];
    int n0 = sb.len[0];
    size_t n = ws->n, *cell = ws->cell;
    double *wl = ws->w, *gx = mimas_weights_grad(ws, 0), *gy = mimas_weights_grad(ws, 1),
           *gz = mimas_weights_grad(ws, 2);
    for (int k = 0; k < sb.len[2]; k++)
        for (int j = 0; j < sb.len[1]; j++) {
            double qyz = sb.q[1][j] + sb.q[2][k];
            if (qyz >= R2)
                continue;
            double eyz = coef * sb.e[1][j] * sb.e[2][k], fy = sb.gf[1][j], fz = sb.gf[2][k];
            size_t row = (size_t)sb.lo[0] +
                         (size_t)g->n[0] * ((size_t)(sb.lo[1] + j) +
                                            (size_t)g->n[1] * (size_t)(sb.lo[2] + k));
            for (int i = 0; i < n0; i += SEG_LANES) {
#if SEG_LANES == 1
                double v = e0[i] * eyz;
                cell[n] = row + (size_t)i;
                wl[n] = v - sh;
                if (with_grad) {
                    gx[n] = v * gf0[i];
                    gy[n] = v * fy;
                    gz[n] = v * fz;
                }
                n += q0[i] + qyz < R2;
#else
                SEG_VT qv, ev, fv;
                memcpy(&qv, q0 + i, sizeof qv);
                SEG_MT in = qv + qyz < R2;
                int bits = SEG_BITS(&in);
                if (!bits)
                    continue;
                memcpy(&ev, e0 + i, sizeof ev);
                SEG_VT v = ev * eyz;
                SEG_PACK_RUN(cell + n, row + (size_t)i, bits);
                SEG_PACK(wl + n, v - sh, bits);
                if (with_grad) {
                    memcpy(&fv, gf0 + i, sizeof fv);
                    SEG_PACK(gx + n, v * fv, bits);
                    SEG_PACK(gy + n, v * fy, bits);
                    SEG_PACK(gz + n, v * fz, bits);
                }
                n += (size_t)__builtin_popcount((unsigned)bits);
#endif
            }
        }
    ws->n = n;
    ws->has_grad = with_grad;
    return MIMAS_OK;
}
