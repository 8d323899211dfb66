/* voro++ wrapper: cells of lattices have the analytic volumes (plain and
 * radical), cell volumes fill the box, walled boxes and annuli (with
 * voro++'s tangent-plane approximation of cylinders, exact for particles on a
 * regular ring), surface flags, the extent cut, and agreement with a bare
 * voro++ loop. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "assert_close.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "voro_cells.h"
#include "voro_walls.h"

/* Lattice points of a cubic cell of edge a with basis b[nb], repeated m^3
 * times, offset so no point lies on a block boundary. */
static size_t lattice(double (*pos)[3], int m, double a, const double (*basis)[3], int nb)
{
    size_t n = 0;
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++)
            for (int k = 0; k < m; k++)
                for (int b = 0; b < nb; b++) {
                    pos[n][0] = (i + basis[b][0] + 0.25) * a;
                    pos[n][1] = (j + basis[b][1] + 0.25) * a;
                    pos[n][2] = (k + basis[b][2] + 0.25) * a;
                    n++;
                }
    return n;
}

static void check_lattice_at(const double (*basis)[3], int nb, int expected_faces, double a)
{
    const int m = 5;
    double (*pos)[3] = malloc(sizeof *pos * (size_t)(m * m * m * nb));
    double *vol = malloc(sizeof *vol * (size_t)(m * m * m * nb));
    int *faces = malloc(sizeof *faces * (size_t)(m * m * m * nb));
    size_t n = lattice(pos, m, a, basis, nb);
    mimas_box box = {{0, 0, 0}, {m * a, m * a, m * a}, 0, 0, 0, {1, 1, 1}};
    mimas_error err;
    assert_int_equal(mimas_voro_cells(&box, n, (const double (*)[3])pos, NULL, vol, faces, NULL, &err),
                     MIMAS_OK);
    for (size_t k = 0; k < n; k++) {
        assert_close(vol[k], a * a * a / nb, 1e-12 * a * a * a);
        assert_int_equal(faces[k], expected_faces);
    }
    free(pos);
    free(vol);
    free(faces);
}

/* Lattice constants of order 1, and in units where it is 370 (voro++'s
 * absolute tolerances fail there unless the wrapper rescales) or 3.7e-4. */
static void check_lattice(const double (*basis)[3], int nb, int expected_faces)
{
    check_lattice_at(basis, nb, expected_faces, 0.37);
    check_lattice_at(basis, nb, expected_faces, 370.0);
    check_lattice_at(basis, nb, expected_faces, 3.7e-4);
}

static void test_simple_cubic(void **state)
{
    (void)state;
    const double sc[1][3] = {{0, 0, 0}};
    check_lattice(sc, 1, 6);
}

static void test_bcc(void **state)
{
    (void)state;
    const double bcc[2][3] = {{0, 0, 0}, {0.5, 0.5, 0.5}};
    check_lattice(bcc, 2, 14); /* truncated octahedra */
}

static void test_fcc(void **state)
{
    (void)state;
    const double fcc[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    check_lattice(fcc, 4, 12); /* rhombic dodecahedra */
}

/* Rock salt: a simple cubic lattice of spacing a with alternating radii
 * R1 > R2.  The radical plane between neighbours at distance a lies at
 * x2 = (a^2 + R2^2 - R1^2)/(2a) from the small sphere, so the small cells are
 * cubes of edge 2 x2 (the farther neighbours' planes do not reach them) and
 * the big cells hold the rest, 2 a^3 - (2 x2)^3 per pair. */
static void test_radical_rock_salt(void **state)
{
    (void)state;
    const int m = 4;
    const double a = 0.8, R1 = 0.36, R2 = 0.24;
    size_t n = (size_t)(m * m * m);
    double (*pos)[3] = malloc(sizeof *pos * n), *rad = malloc(sizeof *rad * n);
    double *vol = malloc(sizeof *vol * n);
    int *faces = malloc(sizeof *faces * n);
    size_t k = 0;
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++)
            for (int l = 0; l < m; l++, k++) {
                pos[k][0] = (i + 0.25) * a;
                pos[k][1] = (j + 0.25) * a;
                pos[k][2] = (l + 0.25) * a;
                rad[k] = (i + j + l) % 2 ? R2 : R1;
            }
    mimas_box box = {{0, 0, 0}, {m * a, m * a, m * a}, 0, 0, 0, {1, 1, 1}};
    mimas_voro_options o = {rad, NULL, 0, 0, 0, NULL};
    mimas_error err;
    assert_int_equal(mimas_voro_cells(&box, n, (const double (*)[3])pos, &o, vol, faces, NULL,
                                      &err), MIMAS_OK);
    double x2 = (a * a + R2 * R2 - R1 * R1) / (2 * a), small = pow(2 * x2, 3);
    for (k = 0; k < n; k++) {
        if (rad[k] == R2) {
            assert_close(vol[k], small, 1e-12 * small);
            assert_int_equal(faces[k], 6);
        } else {
            assert_close(vol[k], 2 * a * a * a - small, 1e-12 * small);
        }
    }
    free(pos);
    free(rad);
    free(vol);
    free(faces);
}

/* Random points (uniform in fractional coordinates of the box, or between
 * z0 and z1 when z0 < z1). */
static void random_points(gsl_rng *rng, const mimas_box *box, size_t n, double (*pos)[3],
                          double z0, double z1)
{
    double L[3] = {box->hi[0] - box->lo[0], box->hi[1] - box->lo[1], box->hi[2] - box->lo[2]};
    for (size_t k = 0; k < n; k++) {
        double s[3] = {gsl_rng_uniform(rng), gsl_rng_uniform(rng), gsl_rng_uniform(rng)};
        pos[k][0] = box->lo[0] + s[0] * L[0] + s[1] * box->xy + s[2] * box->xz;
        pos[k][1] = box->lo[1] + s[1] * L[1] + s[2] * box->yz;
        pos[k][2] = z0 < z1 ? z0 + s[2] * (z1 - z0) : box->lo[2] + s[2] * L[2];
    }
}

static double sum_of(const double *v, size_t n)
{
    double s = 0;
    for (size_t k = 0; k < n; k++)
        s += v[k];
    return s;
}

/* Plane walls inside the box: a floor and a lid at z = 0.1 and 0.8 in a box
 * periodic along x (closed along y): the cells fill Lx Ly 0.7. */
static void test_plane_walls(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const size_t n = 1500;
    double (*pos)[3] = malloc(sizeof *pos * n), *vol = malloc(sizeof *vol * n);
    unsigned char *surf = malloc(n);
    mimas_box box = {{-0.2, 0.1, 0}, {0.6, 0.5, 0.9}, 0, 0, 0, {1, 0, 0}};
    random_points(rng, &box, n, pos, 0.1, 0.8);
    mimas_voro_wall w[2];
    mimas_error err;
    size_t nw;
    assert_int_equal(mimas_voro_walls_parse("plane:z:0.1,plane:-z:0.8", w, 2, &nw, &err), 0);
    assert_int_equal(nw, 2);
    mimas_voro_options o = {NULL, w, nw, 0, 0, NULL};
    if (mimas_voro_cells(&box, n, (const double (*)[3])pos, &o, vol, NULL, surf, &err))
        fail_msg("%s", err.msg);
    double V = 0.8 * 0.4 * 0.7;
    assert_close(sum_of(vol, n), V, 1e-10 * V);
    /* the lowest and highest particles' cells reach the walls; no cell is cut */
    size_t lo = 0, hi = 0, flagged = 0;
    for (size_t k = 0; k < n; k++) {
        lo = pos[k][2] < pos[lo][2] ? k : lo;
        hi = pos[k][2] > pos[hi][2] ? k : hi;
        flagged += surf[k] != 0;
        assert_true((surf[k] & MIMAS_VORO_CUT) == 0);
    }
    assert_int_equal(surf[lo], MIMAS_VORO_TOUCHES_WALL);
    assert_int_equal(surf[hi], MIMAS_VORO_TOUCHES_WALL);
    assert_true(flagged > 50 && flagged < n / 2);
    free(pos);
    free(vol);
    free(surf);
    gsl_rng_free(rng);
}

/* Surface flags in a closed box holding a simple cubic lattice: exactly the
 * outer layer touches the box faces. */
static void test_surface_flags_of_box_faces(void **state)
{
    (void)state;
    const int m = 5;
    const double a = 1.0, sc[1][3] = {{0, 0, 0}};
    size_t n = (size_t)(m * m * m);
    double (*pos)[3] = malloc(sizeof *pos * n), *vol = malloc(sizeof *vol * n);
    unsigned char *surf = malloc(n);
    lattice(pos, m, a, sc, 1);
    for (size_t k = 0; k < n; k++)
        for (int d = 0; d < 3; d++)
            pos[k][d] += 0.25 * a; /* centres at (i + 1/2) a */
    mimas_box box = {{0, 0, 0}, {m * a, m * a, m * a}, 0, 0, 0, {0, 0, 0}};
    mimas_error err;
    assert_int_equal(mimas_voro_cells(&box, n, (const double (*)[3])pos, NULL, vol, NULL, surf,
                                      &err), MIMAS_OK);
    for (size_t k = 0; k < n; k++) {
        int outer = 0;
        for (int d = 0; d < 3; d++)
            outer |= pos[k][d] < a || pos[k][d] > (m - 1) * a;
        assert_int_equal(surf[k], outer ? MIMAS_VORO_TOUCHES_WALL : 0);
        assert_close(vol[k], a * a * a, 1e-12);
    }
    free(pos);
    free(vol);
    free(surf);
}

/* n particles on a circle of radius rho in each of `layers` layers of a box
 * periodic along z.  Their cells are the wedges between the bisecting
 * half-planes, cut by the plane tangent to each cylinder at the particle's
 * angle (voro++'s approximation), so the walls become regular n-gons: the
 * outer wall R alone leaves n R^2 tan(pi/n) per unit height, an annulus
 * n (R^2 - R_in^2) tan(pi/n). */
static void check_ring(const char *spec, double R_in, double R, double rho)
{
    const int n_ring = 12, layers = 3;
    const double h = 0.3, x0 = 0.4, y0 = -0.3;
    size_t n = (size_t)(n_ring * layers);
    double (*pos)[3] = malloc(sizeof *pos * n), *vol = malloc(sizeof *vol * n);
    int *faces = malloc(sizeof *faces * n);
    unsigned char *surf = malloc(n);
    for (int l = 0; l < layers; l++)
        for (int k = 0; k < n_ring; k++) {
            double t = 2 * M_PI * (k + 0.3) / n_ring;
            double *p = pos[l * n_ring + k];
            p[0] = x0 + rho * cos(t);
            p[1] = y0 + rho * sin(t);
            p[2] = (l + 0.5) * h;
        }
    mimas_box box = {{x0 - 1.3 * R, y0 - 1.3 * R, 0}, {x0 + 1.3 * R, y0 + 1.3 * R, layers * h},
                     0, 0, 0, {0, 0, 1}};
    mimas_voro_wall w[2];
    size_t nw;
    mimas_error err;
    assert_int_equal(mimas_voro_walls_parse(spec, w, 2, &nw, &err), 0);
    mimas_voro_options o = {NULL, w, nw, 0, 0, NULL};
    if (mimas_voro_cells(&box, n, (const double (*)[3])pos, &o, vol, faces, surf, &err))
        fail_msg("%s", err.msg);
    double V = layers * h * n_ring * (R * R - R_in * R_in) * tan(M_PI / n_ring);
    assert_close(sum_of(vol, n), V, 1e-10 * V);
    for (size_t k = 0; k < n; k++) {
        assert_int_equal(surf[k], MIMAS_VORO_TOUCHES_WALL);
        /* two wedge sides, top, bottom, the walls */
        assert_int_equal(faces[k], 4 + (int)nw);
    }
    free(pos);
    free(vol);
    free(faces);
    free(surf);
}

static void test_cylinder_walls_on_a_ring(void **state)
{
    (void)state;
    check_ring("cylinder:2:0.4:-0.3", 0.0, 2.0, 1.3);
    check_ring("cylinder:2:outer:0.4:-0.3,cylinder:1:inner:0.4:-0.3", 1.0, 2.0, 1.3);
}

/* Random points in an annulus: a wall with the particles inside never loses
 * volume (each point of the disk is kept by the tangent plane of the
 * particle whose cell holds it: x . u <= |x| <= R), and one with the
 * particles outside never adds any (points inside the inner cylinder are cut
 * off); the slivers the tangent planes add or miss are O(dtheta^2) of the
 * wall layer (dtheta ~ 0.1 here): within 1 %. */
static void test_random_annulus(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const size_t n = 4000;
    const double R_in = 0.5, R = 1.0, H = 0.5;
    double (*pos)[3] = malloc(sizeof *pos * n), *vol = malloc(sizeof *vol * n);
    for (size_t k = 0; k < n;) {
        double x = 2 * gsl_rng_uniform(rng) - 1, y = 2 * gsl_rng_uniform(rng) - 1;
        double r = hypot(x, y);
        if (r > R_in && r < R) {
            pos[k][0] = x;
            pos[k][1] = y;
            pos[k][2] = H * gsl_rng_uniform(rng);
            k++;
        }
    }
    mimas_box box = {{-1.2, -1.2, 0}, {1.2, 1.2, H}, 0, 0, 0, {0, 0, 1}};
    mimas_voro_wall w[2];
    size_t nw;
    mimas_error err;
    assert_int_equal(mimas_voro_walls_parse("cylinder:1", w, 2, &nw, &err), 0);
    mimas_voro_options o = {NULL, w, nw, 0, 0, NULL};
    assert_int_equal(mimas_voro_cells(&box, n, (const double (*)[3])pos, &o, vol, NULL, NULL,
                                      &err), MIMAS_OK);
    double disk = M_PI * R * R * H, s = sum_of(vol, n);
    assert_true(s >= disk * (1 - 1e-12) && s < 1.01 * disk);
    assert_int_equal(mimas_voro_walls_parse("cylinder:0.5:inner", w, 2, &nw, &err), 0);
    o.nwalls = nw;
    assert_int_equal(mimas_voro_cells(&box, n, (const double (*)[3])pos, &o, vol, NULL, NULL,
                                      &err), MIMAS_OK);
    double outside = (2.4 * 2.4 - M_PI * R_in * R_in) * H;
    s = sum_of(vol, n);
    assert_true(s <= outside * (1 + 1e-12) && s > 0.99 * outside);
    assert_int_equal(mimas_voro_walls_parse("cylinder:0.5:inner,cylinder:1", w, 2, &nw, &err), 0);
    o.nwalls = nw;
    assert_int_equal(mimas_voro_cells(&box, n, (const double (*)[3])pos, &o, vol, NULL, NULL,
                                      &err), MIMAS_OK);
    double annulus = M_PI * (R * R - R_in * R_in) * H;
    s = sum_of(vol, n);
    assert_true(fabs(s - annulus) < 0.01 * annulus);
    free(pos);
    free(vol);
    gsl_rng_free(rng);
}

/* --max-extent: a lone particle's cell is the cube of half-edge L cut by the
 * octahedron |x| + |y| + |z| <= sqrt(3) L: the octahedron's volume
 * (4/3) c^3, c = sqrt(3) L, less its six tips beyond the cube, each a
 * pyramid of height c - L over a square of diagonal 2 (c - L), 14 faces.  In
 * a dense lattice the cut changes nothing. */
static void test_max_extent(void **state)
{
    (void)state;
    const double L = 0.2, c = sqrt(3.0) * L;
    double pos[1][3] = {{0.3, 0.6, 0.5}}, vol[1];
    int faces[1];
    unsigned char surf[1];
    mimas_box box = {{0, 0, 0}, {1, 2, 1}, 0, 0, 0, {0, 0, 0}};
    mimas_voro_options o = {NULL, NULL, 0, L, 0, NULL};
    mimas_error err;
    assert_int_equal(mimas_voro_cells(&box, 1, (const double (*)[3])pos, &o, vol, faces, surf,
                                      &err), MIMAS_OK);
    double V = 4.0 / 3.0 * c * c * c - 6.0 * (2.0 / 3.0) * pow(c - L, 3);
    assert_close(vol[0], V, 1e-12 * V);
    assert_int_equal(faces[0], 14);
    assert_int_equal(surf[0], MIMAS_VORO_CUT);
    /* the cell of a particle next to a box face: cut and touching */
    pos[0][0] = 0.1;
    assert_int_equal(mimas_voro_cells(&box, 1, (const double (*)[3])pos, &o, vol, faces, surf,
                                      &err), MIMAS_OK);
    assert_int_equal(surf[0], MIMAS_VORO_CUT | MIMAS_VORO_TOUCHES_WALL);

    const int m = 4;
    const double a = 0.5, sc[1][3] = {{0, 0, 0}};
    double (*lat)[3] = malloc(sizeof *lat * (size_t)(m * m * m));
    double *lv = malloc(sizeof *lv * (size_t)(m * m * m));
    unsigned char *ls = malloc((size_t)(m * m * m));
    size_t n = lattice(lat, m, a, sc, 1);
    mimas_box per = {{0, 0, 0}, {m * a, m * a, m * a}, 0, 0, 0, {1, 1, 1}};
    o.max_extent = a; /* the cube's corners at x + y + z = 1.5 a < sqrt(3) a */
    assert_int_equal(mimas_voro_cells(&per, n, (const double (*)[3])lat, &o, lv, NULL, ls, &err),
                     MIMAS_OK);
    for (size_t k = 0; k < n; k++) {
        assert_close(lv[k], a * a * a, 1e-12);
        assert_int_equal(ls[k], 0); /* no face on the cut planes beyond the cube */
    }
    free(lat);
    free(lv);
    free(ls);
}

/* The wrapper gives the bare voro++ loop's volumes and faces on points of
 * order-1 spacing (its rescaling only rounds), and threads change nothing. */
static void test_matches_bare_voropp(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const size_t n = 6000;
    double (*pos)[3] = malloc(sizeof *pos * n), *rad = malloc(sizeof *rad * n);
    double *v0 = malloc(sizeof *v0 * n), *v1 = malloc(sizeof *v1 * n), *v2 = malloc(sizeof *v2 * n);
    int *f0 = malloc(sizeof *f0 * n), *f1 = malloc(sizeof *f1 * n), *f2 = malloc(sizeof *f2 * n);
    mimas_box box = {{0, 0, 0}, {20, 15, 20}, 0, 0, 0, {1, 0, 1}};
    random_points(rng, &box, n, pos, 0, 0);
    for (size_t k = 0; k < n; k++)
        rad[k] = 0.2 + 0.3 * gsl_rng_uniform(rng);
    mimas_error err;
    for (int radical = 0; radical < 2; radical++) {
        const double *r = radical ? rad : NULL;
        assert_int_equal(mimas_voro_reference(&box, n, (const double (*)[3])pos, r, v0, f0, &err),
                         MIMAS_OK);
        mimas_voro_options o = {r, NULL, 0, 0, 1, NULL};
        assert_int_equal(mimas_voro_cells(&box, n, (const double (*)[3])pos, &o, v1, f1, NULL,
                                          &err), MIMAS_OK);
        o.threads = 2;
        assert_int_equal(mimas_voro_cells(&box, n, (const double (*)[3])pos, &o, v2, f2, NULL,
                                          &err), MIMAS_OK);
        for (size_t k = 0; k < n; k++) {
            assert_close(v1[k], v0[k], 1e-12 * v0[k]);
            assert_int_equal(f1[k], f0[k]);
            assert_true(v2[k] == v1[k]);
            assert_int_equal(f2[k], f1[k]);
        }
    }
    free(pos);
    free(rad);
    free(v0), free(v1), free(v2);
    free(f0), free(f1), free(f2);
    gsl_rng_free(rng);
}

static void test_wall_errors(void **state)
{
    (void)state;
    mimas_voro_wall w[4];
    size_t nw;
    mimas_error err;
    const char *bad[] = {"plane:q:0", "plane:z", "plane:z:1:2", "cylinder:-1", "cylinder:1:up",
                         "cylinder:1:inner:3", "cone:1", "plane:z:abc"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        assert_int_equal(mimas_voro_walls_parse(bad[k], w, 4, &nw, &err), MIMAS_EUSAGE);
    assert_int_equal(mimas_voro_walls_parse("plane:z:0,plane:-z:1,plane:x:0,plane:y:0,plane:-y:1",
                                            w, 4, &nw, &err), MIMAS_EUSAGE);
    /* a particle below the floor */
    assert_int_equal(mimas_voro_walls_parse("plane:z:0.2", w, 4, &nw, &err), 0);
    mimas_box box = {{0, 0, 0}, {1, 1, 1}, 0, 0, 0, {0, 0, 0}};
    double pos[2][3] = {{0.5, 0.5, 0.5}, {0.5, 0.5, 0.1}}, vol[2];
    int64_t id[2] = {7, 8};
    mimas_voro_options o = {NULL, w, nw, 0, 0, id};
    assert_int_equal(mimas_voro_cells(&box, 2, (const double (*)[3])pos, &o, vol, NULL, NULL,
                                      &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "particle 8 at"));
    /* inside an inner cylinder */
    assert_int_equal(mimas_voro_walls_parse("cylinder:0.2:inner:0.5:0.5", w, 4, &nw, &err), 0);
    o.nwalls = nw;
    assert_int_equal(mimas_voro_cells(&box, 2, (const double (*)[3])pos, &o, vol, NULL, NULL,
                                      &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "particle 7 at"));
    /* walls in a tilted box */
    mimas_box tilted = {{0, 0, 0}, {1, 1, 1}, 0.1, 0, 0, {1, 1, 1}};
    assert_int_equal(mimas_voro_walls_parse("plane:z:0", w, 4, &nw, &err), 0);
    o.nwalls = nw;
    assert_int_equal(mimas_voro_cells(&tilted, 2, (const double (*)[3])pos, &o, vol, NULL, NULL,
                                      &err), MIMAS_EDATA);
}

static void sum_equals_volume(mimas_box box, int radical)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const size_t n = 2000;
    double (*pos)[3] = malloc(sizeof *pos * n);
    double *rad = malloc(sizeof *rad * n);
    double *vol = malloc(sizeof *vol * n);
    for (size_t k = 0; k < n; k++) {
        double s[3] = {gsl_rng_uniform(rng), gsl_rng_uniform(rng), gsl_rng_uniform(rng)};
        double L[3] = {box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]};
        pos[k][0] = box.lo[0] + s[0] * L[0] + s[1] * box.xy + s[2] * box.xz;
        pos[k][1] = box.lo[1] + s[1] * L[1] + s[2] * box.yz;
        pos[k][2] = box.lo[2] + s[2] * L[2];
        rad[k] = 0.01 + 0.02 * gsl_rng_uniform(rng);
    }
    mimas_error err;
    mimas_voro_options o = {radical ? rad : NULL, NULL, 0, 0, 0, NULL};
    int rc = mimas_voro_cells(&box, n, (const double (*)[3])pos, &o, vol, NULL, NULL, &err);
    if (rc)
        fail_msg("%s", err.msg);
    double sum = 0;
    for (size_t k = 0; k < n; k++)
        sum += vol[k];
    double V = mimas_box_volume(&box);
    assert_close(sum, V, 1e-10 * V);
    free(pos);
    free(rad);
    free(vol);
    gsl_rng_free(rng);
}

static void test_volumes_sum_to_box(void **state)
{
    (void)state;
    mimas_box walls = {{-0.2, 0.1, 0}, {0.6, 0.5, 0.9}, 0, 0, 0, {0, 0, 0}};
    mimas_box mixed = {{-0.2, 0.1, 0}, {0.6, 0.5, 0.9}, 0, 0, 0, {1, 0, 1}};
    mimas_box tilted = {{-0.2, 0.1, 0}, {0.6, 0.5, 0.9}, 0.13, -0.07, 0.21, {1, 1, 1}};
    for (int radical = 0; radical < 2; radical++) {
        sum_equals_volume(walls, radical);
        sum_equals_volume(mixed, radical);
        sum_equals_volume(tilted, radical);
    }
}

static void test_outside_point_is_an_error(void **state)
{
    (void)state;
    mimas_box box = {{0, 0, 0}, {1, 1, 1}, 0, 0, 0, {0, 0, 0}};
    double pos[2][3] = {{0.5, 0.5, 0.5}, {1.5, 0.5, 0.5}};
    double vol[2];
    mimas_error err;
    assert_int_equal(mimas_voro_cells(&box, 2, (const double (*)[3])pos, NULL, vol, NULL, NULL, &err),
                     MIMAS_EDATA);
    mimas_box tilted_open = {{0, 0, 0}, {1, 1, 1}, 0.1, 0, 0, {1, 1, 0}};
    assert_int_equal(mimas_voro_cells(&tilted_open, 1, (const double (*)[3])pos, NULL, vol, NULL,
                                      NULL, &err), MIMAS_EDATA);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_simple_cubic),
        cmocka_unit_test(test_bcc),
        cmocka_unit_test(test_fcc),
        cmocka_unit_test(test_volumes_sum_to_box),
        cmocka_unit_test(test_outside_point_is_an_error),
        cmocka_unit_test(test_radical_rock_salt),
        cmocka_unit_test(test_plane_walls),
        cmocka_unit_test(test_surface_flags_of_box_faces),
        cmocka_unit_test(test_cylinder_walls_on_a_ring),
        cmocka_unit_test(test_random_annulus),
        cmocka_unit_test(test_max_extent),
        cmocka_unit_test(test_matches_bare_voropp),
        cmocka_unit_test(test_wall_errors),
    };
    return cmocka_run_group_tests_name("voro", tests, NULL, NULL);
}
