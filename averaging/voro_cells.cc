// The voro++ wrapper: the only C++ in mimas (see voro_cells.h).
#include <config.h>

#include "voro_cells.h"

#include <cmath>
#include <new>
#include <voro++.hh>

namespace {

// Blocks of about five particles each, as voro++'s documentation advises.
void block_grid(const mimas_box *b, size_t n, int g[3])
{
    double L[3] = {b->hi[0] - b->lo[0], b->hi[1] - b->lo[1], b->hi[2] - b->lo[2]};
    double per_block = L[0] * L[1] * L[2] * 5.0 / (n ? double(n) : 1.0);
    double edge = std::cbrt(per_block);
    for (int d = 0; d < 3; d++) {
        double k = std::ceil(L[d] / edge);
        g[d] = k < 1.0 ? 1 : (k > 4096.0 ? 4096 : int(k));
    }
}

// A particle whose cell voro++ does not compute has an empty cell: with radii
// (radical tessellation) a small sphere overlapping a big one can lose all
// of its power cell.  Positions were checked to lie in the container first.
template <class Container, class Loop>
void collect(Container &con, Loop &loop, size_t n, double *volume, int *faces)
{
    for (size_t k = 0; k < n; k++) {
        volume[k] = 0.0;
        if (faces)
            faces[k] = 0;
    }
    voro::voronoicell c;
    if (loop.start()) do {
            if (con.compute_cell(c, loop)) {
                int id = loop.pid();
                volume[id] = c.volume();
                if (faces)
                    faces[id] = c.number_of_faces();
            }
        } while (loop.inc());
}

// Index of the first particle outside the non-periodic extent of the box, or -1.
long first_outside(const mimas_box *b, size_t n, const double (*pos)[3])
{
    for (size_t k = 0; k < n; k++)
        for (int d = 0; d < 3; d++)
            if (!b->periodic[d] && !(pos[k][d] >= b->lo[d] && pos[k][d] <= b->hi[d]))
                return long(k);
    return -1;
}

}  // namespace

extern "C" int mimas_voro_cells(const mimas_box *b, size_t n, const double (*pos)[3],
                                const double *radius, double *volume, int *faces,
                                mimas_error *err)
{
    if (n > size_t(INT32_MAX))
        return mimas_error_set(err, MIMAS_EUSAGE, "too many particles for voro++ (%zu)", n);
    int g[3];
    block_grid(b, n, g);
    long out = first_outside(b, n, pos);
    if (out >= 0)
        return mimas_error_set(err, MIMAS_EDATA, "particle %ld at (%g, %g, %g) lies outside the box",
                               out, pos[out][0], pos[out][1], pos[out][2]);
    try {
        if (mimas_box_is_triclinic(b)) {
            if (!(b->periodic[0] && b->periodic[1] && b->periodic[2]))
                return mimas_error_set(err, MIMAS_EDATA,
                                       "a triclinic box must be periodic along x, y and z "
                                       "for Voronoi cells");
            double bx = b->hi[0] - b->lo[0], by = b->hi[1] - b->lo[1], bz = b->hi[2] - b->lo[2];
            // voro++'s periodic container has its origin at 0 and the LAMMPS tilt convention
            if (radius) {
                voro::container_periodic_poly con(bx, b->xy, by, b->xz, b->yz, bz, g[0], g[1],
                                                  g[2], 8);
                for (size_t k = 0; k < n; k++)
                    con.put(int(k), pos[k][0] - b->lo[0], pos[k][1] - b->lo[1],
                            pos[k][2] - b->lo[2], radius[k]);
                voro::c_loop_all_periodic loop(con);
                collect(con, loop, n, volume, faces);
            } else {
                voro::container_periodic con(bx, b->xy, by, b->xz, b->yz, bz, g[0], g[1], g[2], 8);
                for (size_t k = 0; k < n; k++)
                    con.put(int(k), pos[k][0] - b->lo[0], pos[k][1] - b->lo[1],
                            pos[k][2] - b->lo[2]);
                voro::c_loop_all_periodic loop(con);
                collect(con, loop, n, volume, faces);
            }
        } else if (radius) {
            voro::container_poly con(b->lo[0], b->hi[0], b->lo[1], b->hi[1], b->lo[2], b->hi[2],
                                     g[0], g[1], g[2], b->periodic[0], b->periodic[1],
                                     b->periodic[2], 8);
            for (size_t k = 0; k < n; k++)
                con.put(int(k), pos[k][0], pos[k][1], pos[k][2], radius[k]);
            voro::c_loop_all loop(con);
            collect(con, loop, n, volume, faces);
        } else {
            voro::container con(b->lo[0], b->hi[0], b->lo[1], b->hi[1], b->lo[2], b->hi[2], g[0],
                                g[1], g[2], b->periodic[0], b->periodic[1], b->periodic[2], 8);
            for (size_t k = 0; k < n; k++)
                con.put(int(k), pos[k][0], pos[k][1], pos[k][2]);
            voro::c_loop_all loop(con);
            collect(con, loop, n, volume, faces);
        }
    } catch (const std::bad_alloc &) {
        return mimas_error_set(err, MIMAS_EIO, "out of memory in voro++");
    }
    return MIMAS_OK;
}
