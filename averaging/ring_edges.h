/* A kernel's azimuthal average along a contact's branch on an r-z grid: where the
 * average is singular along the branch, and the quadrature nodes that split the branch
 * there (docs/fields.md, "Cylindrical grids without phi cells").
 *
 * The average at the ring (r, z) of the kernel around a point at distance rho from the
 * axis is cut where the ring leaves the kernel's support, (rho - r)^2 + dz^2 = R^2, and
 * where all of it enters, (rho + r)^2 + dz^2 = R^2; at both it goes as the square root of
 * the distance from the edge.  Along the branch a + s b the two edges are the real roots in
 * s of one quartic, (q + r^2 + dz^2 - R^2)^2 = 4 r^2 q with q = |a + s b|^2 across the axis;
 * where the branch nearly touches an edge the quartic has a pair of complex roots near it,
 * and rho = sqrt(q) has branch points off the branch by its nearest approach to the axis.
 * A rule along the whole branch is off by up to 6e-4 of the kernel's peak there (8e-3 at
 * cutoff 2); the split rule integrates each piece in a variable that makes the nearest of
 * these points smooth (u^2 from an edge, sinh(u) about a complex pair). */
#ifndef MIMAS_RING_EDGES_H
#define MIMAS_RING_EDGES_H

#include "weight.h"

/* A branch a -> a + b in the grid's axis frame. */
typedef struct mimas_ring_branch {
    double a[3], b[3];
    double len;  /* |b| */
    double q[3]; /* its squared distance from the axis, q[0] + q[1] s + q[2] s^2 */
    /* its nearest approach to the axis, where rho has its branch points star +- i beta
     * (beta infinite for a branch along the axis) */
    double star, beta;
    /* its middle: distance from the axis, z, and q about it, qm[0] + qm[1] t + q[2] t^2 with
     * t = s - 1/2 */
    double rho_mid, z_mid, qm[2];
    /* the radius of the disc about the middle, in branch lengths, where a singular point
     * asks for the split rule; the square of the reach plus half the length */
    double h, out2;
    double len8; /* the longest piece the rule of 8 points takes (dep_ring_longest) */
} mimas_ring_branch;

/* The branch a -> ab for the weight wt. */
void mimas_ring_branch_init(mimas_ring_branch *br, const mimas_weight *wt, const double a[3],
                            const double ab[3]);

/* The nodes of the split rule at one ring: room for 18 pieces of 16 nodes, padded to a
 * multiple of 8 with nodes out of reach (weight 0, dr2 infinite). */
#define MIMAS_RING_NODES_MAX 288
typedef struct mimas_ring_nodes {
    double w[MIMAS_RING_NODES_MAX];   /* the weight of each (its share of s in [0, 1]) */
    double rho[MIMAS_RING_NODES_MAX]; /* its distance from the axis */
    double dz[MIMAS_RING_NODES_MAX];  /* the ring's z minus the node's */
    double dr2[MIMAS_RING_NODES_MAX]; /* (r - rho)^2 */
    double irr[MIMAS_RING_NODES_MAX]; /* 1/(4 r rho), infinite on the axis */
} mimas_ring_nodes;

/* The split rule for the branch at the ring (r, z) of wt's average: -1 when no singular
 * point is near the branch (the rule along the whole branch, dep_ring_rule, is accurate
 * there), else the number of nodes (0 when all of the branch is outside the support: the
 * ring has no weight). */
int mimas_ring_edge_nodes(const mimas_ring_branch *br, const mimas_weight *wt, double r,
                          double z, mimas_ring_nodes *nd);

#endif
