// The voro++ wrapper: the only C++ in mimas (see voro_cells.h).
#include <config.h>

#include "voro_cells.h"

#include <cmath>
#include <cstdio>
#include <new>
#include <vector>
#include <voro++.hh>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace {

// A vertex lies on a bounding plane when within this distance of it, in
// units of the mean spacing (voro++ itself keeps vertices within 1e-11).
const double ON_PLANE = 1e-9;

// The plane v . u <= h bounding a cell, v relative to its particle, u a
// unit vector, with the flag a vertex on it sets.
struct bound {
    double u[3], h;
    unsigned char flag;
};

// Blocks of about five particles each, as voro++'s documentation advises.
void block_grid(const double L[3], size_t n, int g[3])
{
    double per_block = L[0] * L[1] * L[2] * 5.0 / (n ? double(n) : 1.0);
    double edge = std::cbrt(per_block);
    for (int d = 0; d < 3; d++) {
        double k = std::ceil(L[d] / edge);
        g[d] = k < 1.0 ? 1 : (k > 4096.0 ? 4096 : int(k));
    }
}

// A mimas_voro_wall in the scaled coordinates handed to voro++ (origin at
// the box's lo corner, unit length s).
class cut_wall : public voro::wall {
  public:
    cut_wall(const mimas_voro_wall &w, double s, const double lo[3]) : w_(w)
    {
        if (w.kind == MIMAS_VORO_PLANE) {
            w_.offset = (w.offset - (w.normal[0] * lo[0] + w.normal[1] * lo[1] +
                                     w.normal[2] * lo[2])) / s;
        } else {
            w_.axis[0] = (w.axis[0] - lo[0]) / s;
            w_.axis[1] = (w.axis[1] - lo[1]) / s;
            w_.radius = w.radius / s;
        }
    }
    // The plane bounding the cell of a particle at (x, y, z); false if none
    // (a particle on a cylinder's axis has no tangent plane).
    bool plane_at(double x, double y, double z, bound &b) const
    {
        if (w_.kind == MIMAS_VORO_PLANE) {
            for (int d = 0; d < 3; d++)
                b.u[d] = -w_.normal[d];
            b.h = w_.normal[0] * x + w_.normal[1] * y + w_.normal[2] * z - w_.offset;
        } else {
            double dx = x - w_.axis[0], dy = y - w_.axis[1], rho = std::hypot(dx, dy);
            if (!(rho > 1e-12))
                return false;
            double sign = w_.inner ? -1.0 : 1.0;
            b.u[0] = sign * dx / rho;
            b.u[1] = sign * dy / rho;
            b.u[2] = 0.0;
            b.h = sign * (w_.radius - rho);
        }
        b.flag = MIMAS_VORO_TOUCHES_WALL;
        return true;
    }
    bool point_inside(double x, double y, double z) override
    {
        if (w_.kind == MIMAS_VORO_PLANE)
            return w_.normal[0] * x + w_.normal[1] * y + w_.normal[2] * z >= w_.offset;
        double rho = std::hypot(x - w_.axis[0], y - w_.axis[1]);
        return w_.inner ? rho >= w_.radius : rho <= w_.radius;
    }
    bool cut_cell(voro::voronoicell &c, double x, double y, double z) override
    {
        return cut(c, x, y, z);
    }
    bool cut_cell(voro::voronoicell_neighbor &c, double x, double y, double z) override
    {
        return cut(c, x, y, z);
    }

  private:
    template <class Cell> bool cut(Cell &c, double x, double y, double z)
    {
        bound b;
        if (!plane_at(x, y, z, b))
            return true;
        // voro++'s nplane keeps v . n <= rsq/2
        return c.nplane(b.u[0], b.u[1], b.u[2], 2.0 * b.h, -1);
    }
    mimas_voro_wall w_;
};

// One tessellation: the scaled problem and where the results go.
struct job {
    size_t n;
    const double (*pos)[3];
    const double *radius;
    bool triclinic, periodic[3];
    double s, lo[3], L[3], tilt[3];   // scaled box; tilt = xy, xz, yz
    int g[3];
    std::vector<mimas_voro_wall> walls;
    double extent;                    // scaled max_extent (0: none)
    double *volume;
    int *faces;
    unsigned char *surface;
};

// The 14 directions of the max_extent cut: cube faces and octahedron faces.
void extent_directions(double u[14][3])
{
    const double a = 1.0 / std::sqrt(3.0);
    int k = 0;
    for (int d = 0; d < 3; d++)
        for (int sgn = -1; sgn <= 1; sgn += 2, k++) {
            u[k][0] = u[k][1] = u[k][2] = 0.0;
            u[k][d] = sgn;
        }
    for (int sx = -1; sx <= 1; sx += 2)
        for (int sy = -1; sy <= 1; sy += 2)
            for (int sz = -1; sz <= 1; sz += 2, k++) {
                u[k][0] = sx * a;
                u[k][1] = sy * a;
                u[k][2] = sz * a;
            }
}

// A particle's scaled coordinate along a non-periodic axis, inside [0, L)
// (voro++ drops a particle exactly on the upper face).
double inside(double x, double L)
{
    if (x < 0.0)
        return 0.0;
    return x < L ? x : std::nextafter(L, 0.0);
}

// After voro++ computed the cell of particle id at (x, y, z): the extent
// cut, the volume, faces and surface flags.
void finish_cell(voro::voronoicell &c, const job &J, const std::vector<cut_wall> &walls,
                 const double (*ext)[3], int id, double x, double y, double z,
                 std::vector<bound> &bounds)
{
    bounds.clear();
    if (J.extent > 0.0)
        for (int m = 0; m < 14; m++) {
            if (!c.nplane(ext[m][0], ext[m][1], ext[m][2], 2.0 * J.extent, -1))
                return; // cannot happen: the particle stays inside its cut cell
            bound b = {{ext[m][0], ext[m][1], ext[m][2]}, J.extent, MIMAS_VORO_CUT};
            bounds.push_back(b);
        }
    double s3 = J.s * J.s * J.s;
    J.volume[id] = c.volume() * s3;
    if (J.faces)
        J.faces[id] = c.number_of_faces();
    if (!J.surface)
        return;
    double p[3] = {x, y, z};
    for (int d = 0; d < 3 && !J.triclinic; d++) {
        if (J.periodic[d])
            continue;
        bound lo = {{0, 0, 0}, p[d], MIMAS_VORO_TOUCHES_WALL};
        bound hi = {{0, 0, 0}, J.L[d] - p[d], MIMAS_VORO_TOUCHES_WALL};
        lo.u[d] = -1.0;
        hi.u[d] = 1.0;
        bounds.push_back(lo);
        bounds.push_back(hi);
    }
    for (const cut_wall &w : walls) {
        bound b;
        if (w.plane_at(x, y, z, b))
            bounds.push_back(b);
    }
    // only planes within the cell's reach can hold a vertex (pts holds
    // twice the vertex positions relative to the particle)
    double reach = 0.5 * std::sqrt(c.max_radius_squared()) + ON_PLANE;
    unsigned char flags = 0;
    for (const bound &b : bounds) {
        if (b.h > reach || (flags & b.flag))
            continue;
        for (int v = 0; v < c.p; v++) {
            const double *q = c.pts + 3 * v;
            double dist = 0.5 * (q[0] * b.u[0] + q[1] * b.u[1] + q[2] * b.u[2]) - b.h;
            if (std::fabs(dist) <= ON_PLANE) {
                flags |= b.flag;
                break;
            }
        }
    }
    J.surface[id] = flags;
}

// Cells first .. last-1 of the container's loop order.
template <class Con, class Loop>
void compute_share(Con &con, const job &J, const std::vector<cut_wall> &walls, size_t first,
                   size_t last)
{
    double ext[14][3];
    extent_directions(ext);
    std::vector<bound> bounds;
    voro::voronoicell c;
    Loop loop(con);
    size_t at = 0;
    if (!loop.start())
        return;
    do {
        if (at >= first && con.compute_cell(c, loop)) {
            double x, y, z;
            loop.pos(x, y, z);
            finish_cell(c, J, walls, ext, loop.pid(), x, y, z, bounds);
        }
        at++;
    } while (at < last && loop.inc());
}

// Builds this thread's container, puts every particle and computes the
// thread's share of the cells.
void run_share(const job &J, size_t first, size_t last)
{
    double inv = 1.0 / J.s;
    std::vector<cut_wall> walls;
    for (const mimas_voro_wall &w : J.walls)
        walls.emplace_back(w, J.s, J.lo);
    auto scaled = [&](size_t k, int d) {
        double x = (J.pos[k][d] - J.lo[d]) * inv;
        return J.periodic[d] ? x : inside(x, J.L[d]);
    };
    if (J.triclinic) {
        // voro++'s periodic container has its origin at 0 and the LAMMPS tilt convention
        if (J.radius) {
            voro::container_periodic_poly con(J.L[0], J.tilt[0], J.L[1], J.tilt[1], J.tilt[2],
                                              J.L[2], J.g[0], J.g[1], J.g[2], 8);
            for (size_t k = 0; k < J.n; k++)
                con.put(int(k), scaled(k, 0), scaled(k, 1), scaled(k, 2), J.radius[k] * inv);
            compute_share<voro::container_periodic_poly, voro::c_loop_all_periodic>(
                con, J, walls, first, last);
        } else {
            voro::container_periodic con(J.L[0], J.tilt[0], J.L[1], J.tilt[1], J.tilt[2], J.L[2],
                                         J.g[0], J.g[1], J.g[2], 8);
            for (size_t k = 0; k < J.n; k++)
                con.put(int(k), scaled(k, 0), scaled(k, 1), scaled(k, 2));
            compute_share<voro::container_periodic, voro::c_loop_all_periodic>(con, J, walls,
                                                                                first, last);
        }
    } else if (J.radius) {
        voro::container_poly con(0, J.L[0], 0, J.L[1], 0, J.L[2], J.g[0], J.g[1], J.g[2],
                                 J.periodic[0], J.periodic[1], J.periodic[2], 8);
        for (cut_wall &w : walls)
            con.add_wall(w);
        for (size_t k = 0; k < J.n; k++)
            con.put(int(k), scaled(k, 0), scaled(k, 1), scaled(k, 2), J.radius[k] * inv);
        compute_share<voro::container_poly, voro::c_loop_all>(con, J, walls, first, last);
    } else {
        voro::container con(0, J.L[0], 0, J.L[1], 0, J.L[2], J.g[0], J.g[1], J.g[2],
                            J.periodic[0], J.periodic[1], J.periodic[2], 8);
        for (cut_wall &w : walls)
            con.add_wall(w);
        for (size_t k = 0; k < J.n; k++)
            con.put(int(k), scaled(k, 0), scaled(k, 1), scaled(k, 2));
        compute_share<voro::container, voro::c_loop_all>(con, J, walls, first, last);
    }
}

// A particle's id for messages (its index when there are no ids).
long long label(const mimas_voro_options *o, size_t k)
{
    return o && o->id ? (long long)o->id[k] : (long long)k;
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

// The first particle on the wrong side of a wall: its index and the wall's.
bool outside_wall(const mimas_voro_options *o, size_t n, const double (*pos)[3], size_t &k,
                  size_t &w)
{
    const double zero[3] = {0, 0, 0};
    for (w = 0; w < o->nwalls; w++) {
        cut_wall cw(o->walls[w], 1.0, zero);
        for (k = 0; k < n; k++)
            if (!cw.point_inside(pos[k][0], pos[k][1], pos[k][2]))
                return true;
    }
    return false;
}

int wall_error(const mimas_voro_options *o, const double (*pos)[3], size_t k, size_t w,
               mimas_error *err)
{
    const mimas_voro_wall &v = o->walls[w];
    char what[160];
    if (v.kind == MIMAS_VORO_PLANE)
        std::snprintf(what, sizeof what, "the plane wall (%g, %g, %g) . x >= %g", v.normal[0],
                      v.normal[1], v.normal[2], v.offset);
    else
        std::snprintf(what, sizeof what, "the cylinder wall r %s %g about (%g, %g)",
                      v.inner ? ">=" : "<=", v.radius, v.axis[0], v.axis[1]);
    return mimas_error_set(err, MIMAS_EDATA, "particle %lld at (%g, %g, %g) lies outside %s",
                           label(o, k), pos[k][0], pos[k][1], pos[k][2], what);
}

}  // namespace

extern "C" int mimas_voro_cells(const mimas_box *b, size_t n, const double (*pos)[3],
                                const mimas_voro_options *o, double *volume, int *faces,
                                unsigned char *surface, mimas_error *err)
{
    static const mimas_voro_options none = {};
    if (!o)
        o = &none;
    if (n > size_t(INT32_MAX))
        return mimas_error_set(err, MIMAS_EUSAGE, "too many particles for voro++ (%zu)", n);
    for (size_t k = 0; k < n; k++) {
        volume[k] = 0.0;
        if (faces)
            faces[k] = 0;
        if (surface)
            surface[k] = 0;
    }
    long out = first_outside(b, n, pos);
    if (out >= 0)
        return mimas_error_set(err, MIMAS_EDATA, "particle %lld at (%g, %g, %g) lies outside the box",
                               label(o, size_t(out)), pos[out][0], pos[out][1], pos[out][2]);
    job J;
    J.triclinic = mimas_box_is_triclinic(b);
    if (J.triclinic && !(b->periodic[0] && b->periodic[1] && b->periodic[2]))
        return mimas_error_set(err, MIMAS_EDATA, "a triclinic box must be periodic along x, y "
                               "and z for Voronoi cells");
    if (J.triclinic && o->nwalls)
        return mimas_error_set(err, MIMAS_EDATA, "walls need an orthogonal box");
    size_t kw, ww;
    if (o->nwalls && outside_wall(o, n, pos, kw, ww))
        return wall_error(o, pos, kw, ww, err);
    if (n == 0)
        return MIMAS_OK;
    double V = mimas_box_volume(b);
    J.s = V > 0 ? std::cbrt(V / double(n)) : 1.0;
    J.n = n;
    J.pos = pos;
    J.radius = o->radius;
    for (int d = 0; d < 3; d++) {
        J.periodic[d] = b->periodic[d] != 0;
        J.lo[d] = b->lo[d];
        J.L[d] = (b->hi[d] - b->lo[d]) / J.s;
    }
    J.tilt[0] = b->xy / J.s;
    J.tilt[1] = b->xz / J.s;
    J.tilt[2] = b->yz / J.s;
    block_grid(J.L, n, J.g);
    J.walls.assign(o->walls, o->walls + o->nwalls);
    J.extent = o->max_extent > 0 ? o->max_extent / J.s : 0.0;
    J.volume = volume;
    J.faces = faces;
    J.surface = surface;
    int threads = 1;
#ifdef _OPENMP
    threads = o->threads > 0 ? o->threads : omp_get_max_threads();
#endif
    // a share of fewer than a few thousand cells is not worth a container
    if (size_t(threads) > n / 2000 + 1)
        threads = int(n / 2000 + 1);
    int failed = 0;
#ifdef _OPENMP
#pragma omp parallel for num_threads(threads) schedule(static, 1) reduction(| : failed)
#endif
    for (int t = 0; t < threads; t++) {
        try {
            run_share(J, n * size_t(t) / size_t(threads), n * size_t(t + 1) / size_t(threads));
        } catch (const std::bad_alloc &) {
            failed = 1;
        }
    }
    if (failed)
        return mimas_error_set(err, MIMAS_EIO, "out of memory in voro++");
    return MIMAS_OK;
}

extern "C" int mimas_voro_reference(const mimas_box *b, size_t n, const double (*pos)[3],
                                    const double *radius, double *volume, int *faces,
                                    mimas_error *err)
{
    if (mimas_box_is_triclinic(b))
        return mimas_error_set(err, MIMAS_EUSAGE, "the reference loop takes orthogonal boxes");
    double L[3] = {b->hi[0] - b->lo[0], b->hi[1] - b->lo[1], b->hi[2] - b->lo[2]};
    int g[3];
    block_grid(L, n, g);
    for (size_t k = 0; k < n; k++) {
        volume[k] = 0.0;
        faces[k] = 0;
    }
    try {
        voro::voronoicell c;
        if (radius) {
            voro::container_poly con(b->lo[0], b->hi[0], b->lo[1], b->hi[1], b->lo[2], b->hi[2],
                                     g[0], g[1], g[2], b->periodic[0], b->periodic[1],
                                     b->periodic[2], 8);
            for (size_t k = 0; k < n; k++)
                con.put(int(k), pos[k][0], pos[k][1], pos[k][2], radius[k]);
            voro::c_loop_all loop(con);
            if (loop.start()) do
                    if (con.compute_cell(c, loop)) {
                        volume[loop.pid()] = c.volume();
                        faces[loop.pid()] = c.number_of_faces();
                    }
                while (loop.inc());
        } else {
            voro::container con(b->lo[0], b->hi[0], b->lo[1], b->hi[1], b->lo[2], b->hi[2], g[0],
                                g[1], g[2], b->periodic[0], b->periodic[1], b->periodic[2], 8);
            for (size_t k = 0; k < n; k++)
                con.put(int(k), pos[k][0], pos[k][1], pos[k][2]);
            voro::c_loop_all loop(con);
            if (loop.start()) do
                    if (con.compute_cell(c, loop)) {
                        volume[loop.pid()] = c.volume();
                        faces[loop.pid()] = c.number_of_faces();
                    }
                while (loop.inc());
        }
    } catch (const std::bad_alloc &) {
        return mimas_error_set(err, MIMAS_EIO, "out of memory in voro++");
    }
    return MIMAS_OK;
}
