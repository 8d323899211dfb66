/* MercuryDPM reader (readers/mercury.c): 3-D and 2-D .data files, .fstat
 * contacts and wall contacts with their sign conventions, time matching, and
 * every kind of bad input.  The hand-made files are in tests/data/mercury/
 * (README.md there derives the expected numbers); the bad inputs are written
 * to a temporary directory. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include <cmocka.h>

#include "assert_close.h"

#include "backend.h"
#include "frame.h"
#include "scratch.h"

#define TOL 1e-15 /* lengths of order 1e-3 m written with at most 6 digits */


/* A shipped data file: $TEST_SRCDIR/data/mercury/NAME (make check sets
 * TEST_SRCDIR; run by hand from the source tree otherwise). */
static const char *shipped(const char *name)
{
    static char buf[4][512];
    static int k;
    const char *top = getenv("TEST_SRCDIR");
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/data/mercury/%s", top ? top : "tests", name);
    return buf[k];
}

static const char *write_bytes(const char *name, const char *bytes, size_t n)
{
    const char *path = scratch_path(name);
    FILE *fp = fopen(path, "wb");
    assert_non_null(fp);
    assert_int_equal(fwrite(bytes, 1, n, fp), n);
    assert_int_equal(fclose(fp), 0);
    return path;
}

static const char *write_text(const char *name, const char *text)
{
    return write_bytes(name, text, strlen(text));
}

static int open_mercury(void **st, const char *const *data, size_t ndata,
                        const char *const *fstat, size_t nfstat, double density, int allow,
                        mimas_error *err)
{
    mimas_reader_options o;
    memset(&o, 0, sizeof o);
    o.contacts = fstat;
    o.ncontacts = nfstat;
    o.density = density;
    o.allow_missing_contacts = allow;
    return reader_mercury.open(st, data, ndata, &o, err);
}

/* Reads all frames of one .data file (with an .fstat file, or NULL); returns
 * the number of frames and the skipped count. */
static size_t count_frames(const char *data, const char *fstat, int allow, size_t *skipped)
{
    const char *d[1] = {data}, *c[1] = {fstat};
    void *st;
    mimas_error err;
    mimas_frame f;
    mimas_frame_init(&f);
    int rc = open_mercury(&st, d, 1, c, fstat ? 1 : 0, 0.0, allow, &err);
    if (rc)
        fail_msg("open: %s", err.msg);
    size_t n = 0;
    while ((rc = reader_mercury.next(st, &f, &err)) == MIMAS_OK)
        n++;
    if (rc != MIMAS_END)
        fail_msg("next: %s", err.msg);
    *skipped = reader_mercury.skipped(st);
    reader_mercury.close(st);
    mimas_frame_free(&f);
    return n;
}

/* Opening and reading must fail with MIMAS_EDATA and the one-line message
 * "PATH:LINE: ..." containing fragment. */
static void expect_error(const char *data, const char *fstat, int allow, const char *path,
                         long line, const char *fragment)
{
    const char *d[1] = {data}, *c[1] = {fstat};
    void *st = NULL;
    mimas_error err;
    memset(&err, 0, sizeof err);
    mimas_frame f;
    mimas_frame_init(&f);
    int rc = open_mercury(&st, d, 1, c, fstat ? 1 : 0, 0.0, allow, &err);
    while (rc == MIMAS_OK)
        rc = reader_mercury.next(st, &f, &err);
    if (st)
        reader_mercury.close(st);
    mimas_frame_free(&f);
    if (rc != MIMAS_EDATA)
        fail_msg("expected MIMAS_EDATA for '%s', got %d (%s)", fragment, rc, err.msg);
    char at[64];
    snprintf(at, sizeof at, ":%ld: ", line);
    size_t np = strlen(path);
    if (strncmp(err.msg, path, np) != 0 || strncmp(err.msg + np, at, strlen(at)) != 0 ||
        !strstr(err.msg, fragment) || strchr(err.msg, '\n'))
        fail_msg("message '%s' should be '%s%s...%s...'", err.msg, path, at, fragment);
}

static void assert_vec(const double *got, double x, double y, double z)
{
    assert_close(got[0], x, TOL);
    assert_close(got[1], y, TOL);
    assert_close(got[2], z, TOL);
}

/* ---- content detection ----------------------------------------------------- */

static int probe_text(const char *head)
{
    return reader_mercury.probe("x", head, strlen(head));
}

static void test_probe(void **state)
{
    (void)state;
    assert_true(probe_text("2 0.5 0 0 0 1 1 1 \n0.1 0.2 0.3 0 0 0 0.05 0 0 0 0 0 0 0\n"));
    assert_true(probe_text("1 0 0 0 1 1 \n0.5 0.5 0 0 0.1 0 0 1\n"));
    assert_true(probe_text("0 0 0 0 0 1 1 1 \n3 0.1 0 0 0 1 1 1 \n"));
    assert_true(probe_text("0 0 0 0 0 1 1 1 \n"));
    /* the row may be cut off only where the file ends */
    assert_true(probe_text("1 0 0 0 1 1\r\n0.5 0.5 0 0 0.1 0 0 1"));
    assert_false(probe_text("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\n"));
    static const char hdf5[] = "\x89HDF\r\n\x1a\n\0\0\0\0\0\x08\x08\0";
    assert_false(reader_mercury.probe("x.h5", hdf5, sizeof hdf5 - 1));
    assert_false(probe_text("# 0.5 1\n# 0 0 0 1 1 1\n# 0.1 0.1 0 0 0 0\n"));
    assert_false(probe_text("1 0 0 0 1 1 \n0.1 0.2 0.3 0 0 0 0.05 0 0 0 0 0 0 0\n"));
    assert_false(probe_text("1 0 0 0 0 1 1 1\n0.5 0.5 0 0 0.1 0 0 1\n"));
    assert_false(probe_text("-2 0.5 0 0 0 1 1 1\n0.1 0.2 0.3 0 0 0 0.05 0 0 0 0 0 0 0\n"));
    assert_false(probe_text("2.5 0.5 0 0 0 1 1 1\n0.1 0.2 0.3 0 0 0 0.05 0 0 0 0 0 0 0\n"));
    assert_false(probe_text("2 0.5 0 0 0 1 1\n0.1 0.2 0.3 0 0 0 0.05 0 0 0 0 0 0 0\n"));
    assert_false(probe_text("2 0.5 0 0 0 1 1 1\n0.1 0.2 x 0 0 0 0.05 0 0 0 0 0 0 0\n"));
    assert_false(probe_text("2 0.5 0 0 0 1 1 1"));
    assert_false(probe_text(""));
}

/* ---- the 3-D pair box3d.data + box3d.fstat ---------------------------------- */

static void check_frame_a_particles(const mimas_frame *f)
{
    const mimas_particles *p = &f->particles;
    assert_int_equal(p->n, 5);
    assert_int_equal(p->present, MIMAS_P_ID | MIMAS_P_TYPE | MIMAS_P_RADIUS | MIMAS_P_MASS |
                                     MIMAS_P_POS | MIMAS_P_VEL | MIMAS_P_OMEGA);
    for (size_t k = 0; k < 5; k++)
        assert_int_equal(p->id[k], (int64_t)k); /* the row index */
    /* row 1: 0.002 0.005 0.001 0.1 -0.2 0.3 0.001 0 0 0 1 2 3 0 */
    assert_vec(p->pos[0], 0.002, 0.005, 0.001);
    assert_vec(p->vel[0], 0.1, -0.2, 0.3);
    assert_vec(p->omega[0], 1, 2, 3);
    assert_close(p->radius[0], 0.001, 0.0);
    /* m = rho 4/3 pi r^3 = 2500 * 4.18879020478639e-9 */
    assert_close(p->mass[0], 1.0471975511965977e-05, 1e-20);
    assert_close(p->mass[1], 1.8095573684677205e-05, 1e-20); /* r = 1.2 mm */
    assert_int_equal(p->type[0], 0);
    assert_int_equal(p->type[3], 1);
    assert_vec(p->vel[2], 0, 0, -0.05);
    assert_vec(p->omega[4], 0, 0, -4); /* theta columns 0.1 0.2 0.3 are not omega */
    assert_close(f->box.lo[0], 0.0, 0.0);
    assert_close(f->box.hi[2], 0.01, 0.0);
    assert_true(!f->box.periodic[0] && !f->box.periodic[1] && !f->box.periodic[2]);
    assert_false(mimas_box_is_triclinic(&f->box));
}

/* Pair 0-1, written from both sides:
 *   0.5 0 1 0.0029 0.005 0.001 0.0002 3e-05 2.5 0.5 -1 0 0 0 0 1
 *   0.5 1 0 0.0029 0.005 0.001 0.0002 3e-05 2.5 0.5  1 0 0 0 0 -1
 * Particle 1 sits at larger x, so the force on 0 must point to -x (away
 * from 1).  Row "0 1": n = (-1,0,0) points from j = 1 to i = 0 and
 *   f_01 = fn n + ft t = 2.5 (-1,0,0) + 0.5 (0,0,1) = (-2.5, 0, 0.5);
 * row "1 0" gives f_10 = 2.5 (1,0,0) + 0.5 (0,0,-1) = -f_01, consistent, so
 * one contact i = 0, j = 1 remains.  Overlap 1 + 1.2 - 2 mm = 0.2 mm; the
 * contact point r_0 - (R_0 - delta/2) n = 0.002 + 0.0009 = 0.0029 in x.
 *
 * Pair 3-4 has one row only, "4 3" (particle 3 is fixed: MercuryDPM writes
 * no row from a fixed particle's side): n = (0,0,1) from 3 up to 4, f_43 =
 * 0.8 (0,0,1); stored as i = 3, j = 4 with f_34 = -f_43 = (0,0,-0.8).
 *
 * Wall rows: j = -1 is wall 0, j = -4 is wall 3.  MercuryDPM writes n and t
 * of wall rows pointing from the particle into the wall, so the force on
 * the particle is -(fn n + ft t):
 *   particle 2 on the floor z = 0: n = (0,0,-1), t = (-1,0,0), fn = 3,
 *   ft = 0.4: f = -(3 (0,0,-1) + 0.4 (-1,0,0)) = (0.4, 0, 3), upwards;
 *   particle 4 on the plane x = 0.0016 (wall 3, on its -x side):
 *   n = (-1,0,0), t = (0,-1,0), fn = 0.6, ft = 0.2: f = (0.6, 0.2, 0). */
static void check_frame_a_contacts(const mimas_frame *f)
{
    const mimas_contacts *c = &f->contacts;
    assert_true(f->has_contacts && f->has_walls);
    assert_int_equal(c->n, 2);
    assert_int_equal(c->i[0], 0);
    assert_int_equal(c->j[0], 1);
    assert_vec(c->force[0], -2.5, 0, 0.5);
    assert_vec(c->force_n[0], -2.5, 0, 0);
    assert_vec(c->force_t[0], 0, 0, 0.5);
    assert_vec(c->point[0], 0.0029, 0.005, 0.001);
    assert_close(c->overlap[0], 0.0002, 0.0);
    /* repulsive: the force on i points along r_i - r_j */
    const double *ri = f->particles.pos[0], *rj = f->particles.pos[1];
    assert_true(c->force[0][0] * (ri[0] - rj[0]) > 0);

    assert_int_equal(c->i[1], 3);
    assert_int_equal(c->j[1], 4);
    assert_vec(c->force[1], 0, 0, -0.8);
    assert_vec(c->force_n[1], 0, 0, -0.8);
    assert_vec(c->force_t[1], 0, 0, 0);
    assert_vec(c->point[1], 0.002, 0.002, 0.00075);

    const mimas_wall_contacts *w = &f->walls;
    assert_int_equal(w->n, 2);
    assert_int_equal(w->particle[0], 2);
    assert_int_equal(w->wall[0], 0);
    assert_vec(w->force[0], 0.4, 0, 3);
    assert_vec(w->force_n[0], 0, 0, 3);
    assert_vec(w->force_t[0], 0.4, 0, 0);
    assert_vec(w->point[0], 0.007, 0.005, -0.0001);
    assert_close(w->overlap[0], 0.0002, 0.0);
    assert_int_equal(w->particle[1], 4);
    assert_int_equal(w->wall[1], 3);
    assert_vec(w->force[1], 0.6, 0.2, 0);
    assert_vec(w->point[1], 0.00155, 0.002, 0.0012);
}

/* Frame B (t = 1): pair 0-1 again, the row "1 0" first: n = (1,0,0),
 * t = (0,1,0), fn = 1.2, ft = 0.3 give f_10 = (1.2, 0.3, 0), so the kept
 * contact i = 0, j = 1 has f_01 = (-1.2, -0.3, 0). */
static void check_frame_b(const mimas_frame *f)
{
    assert_close(f->time, 1.0, 0.0);
    assert_int_equal(f->step, 1);
    assert_int_equal(f->particles.n, 3);
    assert_vec(f->particles.pos[1], 0.0039, 0.005, 0.001);
    assert_int_equal(f->contacts.n, 1);
    assert_int_equal(f->contacts.i[0], 0);
    assert_int_equal(f->contacts.j[0], 1);
    assert_vec(f->contacts.force[0], -1.2, -0.3, 0);
    assert_vec(f->contacts.point[0], 0.00295, 0.005, 0.001);
    assert_int_equal(f->walls.n, 0);
    assert_true(f->has_contacts && f->has_walls);
}

static void read_box3d(const char *const *data, size_t ndata, const char *const *fstat,
                       size_t nfstat)
{
    void *st;
    mimas_error err;
    mimas_frame f;
    mimas_frame_init(&f);
    int rc = open_mercury(&st, data, ndata, fstat, nfstat, 2500.0, 0, &err);
    if (rc)
        fail_msg("open: %s", err.msg);
    rc = reader_mercury.next(st, &f, &err);
    if (rc)
        fail_msg("next: %s", err.msg);
    assert_close(f.time, 0.5, 0.0);
    assert_int_equal(f.step, 0);
    check_frame_a_particles(&f);
    check_frame_a_contacts(&f);
    rc = reader_mercury.next(st, &f, &err);
    if (rc)
        fail_msg("next: %s", err.msg);
    check_frame_b(&f);
    assert_int_equal(reader_mercury.next(st, &f, &err), MIMAS_END);
    assert_int_equal(reader_mercury.skipped(st), 0);
    reader_mercury.close(st);
    mimas_frame_free(&f);
}

static void test_3d_with_contacts(void **state)
{
    (void)state;
    const char *d[] = {shipped("box3d.data")}, *c[] = {shipped("box3d.fstat")};
    read_box3d(d, 1, c, 1);
}

/* The same time steps split over several files, the .fstat ones given as a
 * '*' pattern, the .data file compressed. */
static void test_split_and_gzip_inputs(void **state)
{
    (void)state;
    const char *a = "5 0.5 0 0 0 0.01 0.01 0.01 \n"
                    "0.002 0.005 0.001 0.1 -0.2 0.3 0.001 0 0 0 1 2 3 0\n"
                    "0.004 0.005 0.001 0 0 0 0.0012 0 0 0 0 0 0 0\n"
                    "0.007 0.005 0.0008 0 0 -0.05 0.001 0 0 0 0 0 0 0\n"
                    "0.002 0.002 0.0004 0 0 0 0.0004 0 0 0 0 0 0 1\n"
                    "0.002 0.002 0.0012 0 0 0 0.0005 0.1 0.2 0.3 0 0 -4 0\n";
    const char *b = "3 1 0 0 0 0.01 0.01 0.01 \n"
                    "0.002 0.005 0.001 0 0 0 0.001 0 0 0 0 0 0 0\n"
                    "0.0039 0.005 0.001 -0.01 0 0 0.001 0 0 0 0 0 0 0\n"
                    "0.007 0.005 0.002 0 0 0 0.001 0 0 0 0 0 0 0\n";
    const char *fa = "# 0.5 1\n# 0 0 0 0.01 0.01 0.01\n# 0.0004 0.0012 0 0 0 0\n"
                     "0.5 0 1 0.0029 0.005 0.001 0.0002 3e-05 2.5 0.5 -1 0 0 0 0 1\n"
                     "0.5 1 0 0.0029 0.005 0.001 0.0002 3e-05 2.5 0.5 1 0 0 0 0 -1\n"
                     "0.5 2 -1 0.007 0.005 -0.0001 0.0002 1e-05 3 0.4 0 0 -1 -1 0 0\n"
                     "0.5 4 3 0.002 0.002 0.00075 0.0001 0 0.8 0 0 0 1 0 0 0\n"
                     "0.5 4 -4 0.00155 0.002 0.0012 0.0001 2e-05 0.6 0.2 -1 0 0 0 -1 0\n";
    const char *fb = "# 1 1\n# 0 0 0 0.01 0.01 0.01\n# 0.001 0.001 0 0 0 0\n"
                     "1 1 0 0.00295 0.005 0.001 0.0001 0 1.2 0.3 1 0 0 0 1 0\n"
                     "1 0 1 0.00295 0.005 0.001 0.0001 0 1.2 0.3 -1 0 0 0 -1 0\n";
    const char *d[] = {write_text("split.data.0", a), write_text("split.data.1", b)};
    write_text("split.fstat.0", fa);
    write_text("split.fstat.1", fb);
    const char *pattern[] = {scratch_path("split.fstat.*")};
    read_box3d(d, 2, pattern, 1);

    gzFile gz = gzopen(scratch_path("box3d.data.gz"), "wb");
    assert_non_null(gz);
    assert_true(gzputs(gz, a) > 0 && gzputs(gz, b) > 0);
    assert_int_equal(gzclose(gz), Z_OK);
    const char *dz[] = {scratch_path("box3d.data.gz")}, *c[] = {shipped("box3d.fstat")};
    read_box3d(dz, 1, c, 1);
}

/* Files written before MercuryDPM had contact points (marker 0 in the
 * '# t marker' line) have the middle between the centres (pairs) or the
 * point r - (R - delta) n_in on the wall surface in the point columns; the
 * reader rebuilds the contact points of the marker-1 file from positions,
 * radii, overlaps and normals. */
static void test_marker0_contact_points(void **state)
{
    (void)state;
    const char *fs = "# 0.5 0\n# 0 0 0 0.01 0.01 0.01\n# 0.0004 0.0012 0 0 0 0\n"
                     "0.1 0 1 0.003 0.005 0.001 0.0002 3e-05 2.5 0.5 -1 0 0 0 0 1\n"
                     "0.1 1 0 0.003 0.005 0.001 0.0002 3e-05 2.5 0.5 1 0 0 0 0 -1\n"
                     "0.2 2 -1 0.007 0.005 0 0.0002 1e-05 3 0.4 0 0 -1 -1 0 0\n"
                     "0 4 3 0.002 0.002 0.0008 0.0001 0 0.8 0 0 0 1 0 0 0\n"
                     "0 4 -4 0.0016 0.002 0.0012 0.0001 2e-05 0.6 0.2 -1 0 0 0 -1 0\n"
                     "# 1 0\n# 0 0 0 0.01 0.01 0.01\n# 0.001 0.001 0 0 0 0\n"
                     "0.7 1 0 0.00295 0.005 0.001 0.0001 0 1.2 0.3 1 0 0 0 1 0\n"
                     "0.7 0 1 0.00295 0.005 0.001 0.0001 0 1.2 0.3 -1 0 0 0 -1 0\n";
    const char *d[] = {shipped("box3d.data")}, *c[] = {write_text("old.fstat", fs)};
    read_box3d(d, 1, c, 1);
}

/* ---- 2-D -------------------------------------------------------------------- */

/* disks2d.data rows are "x y vx vy r theta omega info", and MercuryDPM writes
 * -omega_z in the omega column: "... 0.5 -2 0" is omega_z = +2. */
static void test_2d_mapping(void **state)
{
    (void)state;
    const char *d[] = {shipped("disks2d.data")};
    void *st;
    mimas_error err;
    mimas_frame f;
    mimas_frame_init(&f);
    assert_int_equal(open_mercury(&st, d, 1, NULL, 0, 0.0, 0, &err), MIMAS_OK);
    assert_int_equal(reader_mercury.next(st, &f, &err), MIMAS_OK);
    const mimas_particles *p = &f.particles;
    assert_int_equal(p->n, 2);
    assert_close(f.time, 0.25, 0.0);
    assert_false(p->present & MIMAS_P_MASS); /* density 0: no masses */
    assert_null(p->mass);
    assert_vec(p->pos[0], 0.005, 0.004, 0);
    assert_vec(p->vel[0], 0.1, -0.3, 0);
    assert_vec(p->omega[0], 0, 0, 2);
    assert_vec(p->omega[1], 0, 0, -3);
    assert_close(p->radius[1], 0.0015, 0.0);
    assert_int_equal(p->type[1], 2);
    assert_vec(f.box.lo, 0, 0, 0);
    assert_vec(f.box.hi, 0.02, 0.01, 0);
    assert_false(f.has_contacts || f.has_walls);
    assert_int_equal(f.contacts.n, 0);
    assert_int_equal(reader_mercury.next(st, &f, &err), MIMAS_OK);
    assert_int_equal(f.particles.n, 1);
    assert_close(f.time, 0.5, 0.0);
    assert_vec(f.particles.pos[0], 0.005, 0.0035, 0);
    assert_int_equal(reader_mercury.next(st, &f, &err), MIMAS_END);
    reader_mercury.close(st);

    /* masses from the sphere volume also in 2-D: 1000 * 4/3 pi 1.5e-3^3 */
    assert_int_equal(open_mercury(&st, d, 1, NULL, 0, 1000.0, 0, &err), MIMAS_OK);
    assert_int_equal(reader_mercury.next(st, &f, &err), MIMAS_OK);
    assert_close(f.particles.mass[1], 1.4137166941154069e-05, 1e-20);
    reader_mercury.close(st);
    mimas_frame_free(&f);
}

/* ---- time matching ------------------------------------------------------------ */

#define P2 "0.2 0.5 0.5 0 0 0 0.1 0 0 0 0 0 0 0\n0.4 0.5 0.5 0 0 0 0.1 0 0 0 0 0 0 0\n"
#define HDR(t) "# " t " 1\n# 0 0 0 1 1 1\n# 0.1 0.1 0 0 0 0\n"
#define ROW(t) t " 0 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n" t " 1 0 0.3 0.5 0.5 0 0 1 0 1 0 0 0 0 0\n"

static const char three_steps[] = "2 0.5 0 0 0 1 1 1\n" P2 "2 1 0 0 0 1 1 1\n" P2
                                  "2 1.5 0 0 0 1 1 1\n" P2;

static void test_missing_time_steps(void **state)
{
    (void)state;
    const char *data = write_text("three.data", three_steps);
    size_t skipped;
    const char *same = write_text("same.fstat", HDR("0.5") ROW("0.5") HDR("1") HDR("1.5"));
    assert_int_equal(count_frames(data, same, 0, &skipped), 3); /* t = 1: zero contacts */

    /* t = 1 missing in the .fstat: the .data header line 4 is named */
    const char *gap = write_text("gap.fstat", HDR("0.5") ROW("0.5") HDR("1.5") ROW("1.5"));
    expect_error(data, gap, 0, data, 4, "t = 1 has no contacts in the .fstat input");
    assert_int_equal(count_frames(data, gap, 1, &skipped), 2);
    assert_int_equal(skipped, 1);

    /* a .fstat time step between two .data ones: its line 6 is named */
    const char *extra = write_text("extra.fstat", HDR("0.5") ROW("0.5") HDR("0.75") ROW("0.75")
                                                      HDR("1") HDR("1.5"));
    expect_error(data, extra, 0, extra, 6, "t = 0.75 has no time step in the .data input");
    assert_int_equal(count_frames(data, extra, 1, &skipped), 3);
    assert_int_equal(skipped, 0);

    /* the .fstat ends early / goes on after the .data */
    const char *shrt = write_text("short.fstat", HDR("0.5") HDR("1"));
    expect_error(data, shrt, 0, data, 7, "t = 1.5 has no contacts: the .fstat input ends");
    assert_int_equal(count_frames(data, shrt, 1, &skipped), 2);
    assert_int_equal(skipped, 1);
    const char *lng = write_text("long.fstat", HDR("0.5") HDR("1") HDR("1.5") HDR("2") ROW("2"));
    expect_error(data, lng, 0, lng, 10, "t = 2 has no time step in the .data input");
    assert_int_equal(count_frames(data, lng, 1, &skipped), 3);

    /* times printed with different precision still match; 1e-4 apart do not */
    const char *close = write_text("close.fstat", HDR("0.5000000001") HDR("1.0000") HDR("1.5"));
    assert_int_equal(count_frames(data, close, 0, &skipped), 3);
    const char *apart = write_text("apart.fstat", HDR("0.5001") HDR("1") HDR("1.5"));
    expect_error(data, apart, 0, data, 1, "t = 0.5 has no contacts");
}

/* ---- contact rows --------------------------------------------------------------- */

static const char two[] = "2 0.5 0 0 0 1 1 1\n" P2;

static void expect_fstat_error(const char *name, const char *fstat, long line,
                               const char *fragment)
{
    const char *data = write_text("two.data", two);
    const char *path = write_text(name, fstat);
    expect_error(data, path, 0, path, line, fragment);
}

/* A particle with several partners, the rows of its pairs interleaved (each pair written from
 * both sides, far apart): every pair found, one contact each, written with i < j, in the
 * order of their first rows */
static void test_pairs_interleaved(void **state)
{
    (void)state;
    const char *data = write_text(
        "three.data", "3 0.5 0 0 0 1 1 1\n" P2 "0.3 0.2 0.3 0 0 0 0.05 0 0 0 0 0 0 0\n");
    const char *fstat = write_text("three.fstat",
                                   HDR("0.5") "0.5 0 2 0.3 0.5 0.5 0 0 2 0 -1 0 0 0 0 0\n"
                                              "0.5 1 0 0.3 0.5 0.5 0 0 1 0 1 0 0 0 0 0\n"
                                              "0.5 2 1 0.3 0.5 0.5 0 0 3 0 1 0 0 0 0 0\n"
                                              "0.5 2 0 0.3 0.5 0.5 0 0 2 0 1 0 0 0 0 0\n"
                                              "0.5 0 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n"
                                              "0.5 1 2 0.3 0.5 0.5 0 0 3 0 -1 0 0 0 0 0\n");
    const char *d[1] = {data}, *c[1] = {fstat};
    void *st;
    mimas_error err;
    mimas_frame f;
    mimas_frame_init(&f);
    if (open_mercury(&st, d, 1, c, 1, 0.0, 0, &err))
        fail_msg("open: %s", err.msg);
    if (reader_mercury.next(st, &f, &err))
        fail_msg("next: %s", err.msg);
    assert_int_equal(f.contacts.n, 3);
    const size_t want[3][2] = {{0, 2}, {0, 1}, {1, 2}};
    for (size_t k = 0; k < 3; k++) {
        assert_int_equal(f.contacts.i[k], want[k][0]);
        assert_int_equal(f.contacts.j[k], want[k][1]);
    }
    reader_mercury.close(st);
    mimas_frame_free(&f);
}

static void test_bad_contacts(void **state)
{
    (void)state;
    expect_fstat_error("index.fstat", HDR("0.5") "0.5 0 7 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n",
                       4, "particle index j 7 names a particle the time step does not have");
    expect_fstat_error("windex.fstat", HDR("0.5") "0.5 2 -1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n",
                       4, "particle index i 2 names a particle");
    expect_fstat_error("neg.fstat", HDR("0.5") "0.5 -1 0 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n", 4,
                       "is not a particle index");
    expect_fstat_error("self.fstat", HDR("0.5") "0.5 1 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n", 4,
                       "with itself");
    expect_fstat_error("wall.fstat", HDR("0.5") "0.5 1 -1.5 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n",
                       4, "wall index");
    /* the two rows of a pair must agree (fn 1 and 1.1 here) */
    expect_fstat_error("mirror.fstat",
                       HDR("0.5") "0.5 0 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n"
                                  "0.5 1 0 0.3 0.5 0.5 0 0 1.1 0 1 0 0 0 0 0\n",
                       5, "disagree (this line and line 4): normal force");
    expect_fstat_error("side.fstat", HDR("0.5") ROW("0.5") "0.5 0 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n",
                       6, "third contact row");
    /* four particles, the rows of two pairs interleaved and a third row of one pair last:
     * the pairs are found whatever the order of their rows, and the message names the
     * third row's line and the other two */
    {
        const char *four = write_text("four.data", "4 0.5 0 0 0 1 1 1\n" P2 P2);
        const char *path = write_text("interleaved.fstat",
                                      HDR("0.5") "0.5 2 3 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n"
                                                 "0.5 0 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n"
                                                 "0.5 3 2 0.3 0.5 0.5 0 0 1 0 1 0 0 0 0 0\n"
                                                 "0.5 1 0 0.3 0.5 0.5 0 0 1 0 1 0 0 0 0 0\n"
                                                 "0.5 0 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n");
        expect_error(four, path, 0, path, 8, "particles 0 and 1 have a third contact row "
                                             "(lines 5 and 7 have the other two)");
    }
    expect_fstat_error("twice.fstat",
                       HDR("0.5") "0.5 0 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n"
                                  "0.5 0 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n",
                       5, "listed twice from the same side");
    expect_fstat_error("few.fstat", HDR("0.5") "0.5 0 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0\n", 4,
                       "has 15 values");
    expect_fstat_error("many.fstat", HDR("0.5") "0.5 0 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0 7\n",
                       4, "has 17 values");
    expect_fstat_error("nan.fstat", HDR("0.5") "0.5 0 1 0.3 0.5 0.5 0 0 nan 0 -1 0 0 0 0 0\n",
                       4, "value 9 ('nan') is not a finite number");
    expect_fstat_error("unit.fstat", HDR("0.5") "0.5 0 1 0.3 0.5 0.5 0 0 1 0 -2 0 0 0 0 0\n", 4,
                       "not a unit vector");
    expect_fstat_error("rowfirst.fstat", "0.5 0 1 0.3 0.5 0.5 0 0 1 0 -1 0 0 0 0 0\n", 1,
                       "expected the line '# t marker'");
    expect_fstat_error("marker.fstat", "# 0.5 2\n", 1, "marker 2");
    expect_fstat_error("hash.fstat", HDR("0.5") ROW("0.5") "# a comment\n", 6,
                       "unexpected '#' line");
    expect_fstat_error("empty.fstat", "", 1, "empty file");
    const char *data = write_text("two.data", two);
    const char *bin = write_bytes("bin.fstat", "# 0.5 1\n\x01\x02\0\x03\n", 13);
    expect_error(data, bin, 0, bin, 2, "binary data");
}

/* ---- bad .data files ------------------------------------------------------------ */

static void expect_data_error(const char *name, const char *text, long line,
                              const char *fragment)
{
    const char *path = write_text(name, text);
    expect_error(path, NULL, 0, path, line, fragment);
}

#define R3 "0.1 0.2 0.3 0 0 0 0.05 0 0 0 0 0 0 0\n"

static void test_bad_data(void **state)
{
    (void)state;
    expect_data_error("trunc.data", "3 0 0 0 0 1 1 1\n" R3 R3, 3, "truncated");
    expect_data_error("few.data", "1 0 0 0 0 1 1 1\n0.1 0.2 0.3 0 0 0 0.05 0 0 0 0 0 0\n", 2,
                      "has 13 values");
    expect_data_error("many.data", "1 0 0 0 0 1 1 1\n0.1 0.2 0.3 0 0 0 0.05 0 0 0 0 0 0 0 9\n",
                      2, "has 15 values");
    expect_data_error("word.data", "1 0 0 0 0 1 1 1\n0.1 0.2 0.3 0 zero 0 0.05 0 0 0 0 0 0 0\n",
                      2, "value 5 ('zero') is not a finite number");
    /* a carriage return inside a line separates values (regression: it
     * once made the value counting loop forever) */
    expect_data_error("cr.data", "1 0 0 0 0 1 1 1\n0.1 0.2 0.3 0 0 0 0.05 0 0 0 0 0 0 0 9\r9\n",
                      2, "has 16 values");
    /* tabs, vertical tabs and form feeds separate values as spaces do, runs of them too */
    expect_data_error("ws.data",
                      "1 0 0 0 0 1 1 1\n0.1\t0.2 \v0.3\f\f0 0 0 0.05 0 0 0 0 0 0 0 9 9\n", 2,
                      "has 16 values");
    expect_data_error("nan.data", "1 0 0 0 0 1 1 1\n0.1 0.2 nan 0 0 0 0.05 0 0 0 0 0 0 0\n", 2,
                      "value 3 ('nan')");
    expect_data_error("inf.data", "1 inf 0 0 0 1 1 1\n" R3, 1, "value 2 ('inf')");
    expect_data_error("empty.data", "", 1, "empty file");
    expect_data_error("blank.data", "\n  \n", 1, "empty file");
    expect_data_error("neg.data", "-1 0 0 0 0 1 1 1\n", 1, "negative particle count -1");
    expect_data_error("absurd.data", "99999999999 0 0 0 0 1 1 1\n" R3, 1, "absurd");
    expect_data_error("count.data", "1.5 0 0 0 0 1 1 1\n" R3, 1, "'1.5' is not a particle count");
    expect_data_error("seven.data", "1 0 0 0 0 1 1\n" R3, 1, "this line has 7");
    expect_data_error("extra.data", "1 0 0 0 0 1 1 1\n" R3 R3, 3,
                      "this line has 14 (more particle rows than the header announced?)");
    expect_data_error("box.data", "1 0 0 2 0 1 1 1\n" R3, 1, "exceeds maximum 1 in y");
    expect_data_error("info.data", "1 0 0 0 0 1 1 1\n0.1 0.2 0.3 0 0 0 0.05 0 0 0 0 0 0 0.5\n",
                      2, "not a species index");
    expect_data_error("radius.data", "1 0 0 0 0 1 1 1\n0.1 0.2 0.3 0 0 0 -0.05 0 0 0 0 0 0 0\n",
                      2, "negative radius");
    expect_data_error("mixed.data", "0 0 0 0 1 1\n0 1 0 0 0 1 1 1\n", 2,
                      "3-D time-step header in a file whose first time step is 2-D");
    expect_data_error("short2d.data", "2 0 0 0 1 1\n0.5 0.5 0 0 0.1 0 0 1\n1 0.5 0 0 1 1\n", 3,
                      "particle row 2 of 2 has 6 values");
    const char *bin = write_bytes("bin.data", "1 0 0 0 0 1 1 1\n\x01\x02\0\x03\n", 21);
    expect_error(bin, NULL, 0, bin, 2, "binary data");
    static const char hdf5[] = "\x89HDF\r\n\x1a\n\0\0\0\0\0\x08\x08\0";
    const char *h5 = write_bytes("fake.h5", hdf5, sizeof hdf5 - 1);
    expect_error(h5, NULL, 0, h5, 1, "value 1 ('?HDF') is not a finite number");
}

static void test_options(void **state)
{
    (void)state;
    const char *d[] = {shipped("box3d.data")};
    void *st;
    mimas_error err;
    mimas_reader_options o;
    memset(&o, 0, sizeof o);
    o.nwalls = 1;
    assert_int_equal(reader_mercury.open(&st, d, 1, &o, &err), MIMAS_EUSAGE);
    o.nwalls = 0;
    o.contact_columns = "id1 id2";
    assert_int_equal(reader_mercury.open(&st, d, 1, &o, &err), MIMAS_EUSAGE);
    o.contact_columns = NULL;
    o.density = -1;
    assert_int_equal(reader_mercury.open(&st, d, 1, &o, &err), MIMAS_EUSAGE);
    o.density = 0;
    assert_int_equal(reader_mercury.open(&st, d, 0, &o, &err), MIMAS_EUSAGE);
    const char *missing[] = {scratch_path("does-not-exist.data")};
    assert_int_equal(reader_mercury.open(&st, missing, 1, &o, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "does-not-exist.data: cannot open"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_probe),
        cmocka_unit_test(test_3d_with_contacts),
        cmocka_unit_test(test_split_and_gzip_inputs),
        cmocka_unit_test(test_marker0_contact_points),
        cmocka_unit_test(test_2d_mapping),
        cmocka_unit_test(test_missing_time_steps),
        cmocka_unit_test(test_pairs_interleaved),
        cmocka_unit_test(test_bad_contacts),
        cmocka_unit_test(test_bad_data),
        cmocka_unit_test(test_options),
    };
    return cmocka_run_group_tests_name("mercury", tests, scratch_setup, scratch_teardown);
}
