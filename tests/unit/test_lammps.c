/* LAMMPS/LIGGGHTS dump reader on real LIGGGHTS output (tests/data/liggghts):
 * counts and values checked against the text itself (read here with zlib
 * and strtod, independently of the reader), contacts matched to the right
 * particles (the overlap LIGGGHTS reports equals the geometric one). */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#include "assert_close.h"
#include "liggghts_set.h"
#include "reader.h"

static const char *data(const char *rel)
{
    return liggghts_data(rel);
}

static mimas_reader *open_set(const char *atoms, const char *pgl, const char *wgl)
{
    mimas_reader *r;
    mimas_error err;
    if (liggghts_open(&r, atoms, pgl, wgl, &err))
        fail_msg("%s", err.msg);
    return r;
}

/* Row counts of every snapshot, counted from the text: the lines between an
 * "ITEM: ATOMS"/"ITEM: ENTRIES" line and the next "ITEM:" line. */
static size_t count_rows(const char *path, size_t *counts, size_t max)
{
    gzFile gz = gzopen(path, "rb");
    assert_non_null(gz);
    char line[8192];
    size_t snaps = 0;
    int in_rows = 0;
    while (gzgets(gz, line, sizeof line)) {
        if (!strncmp(line, "ITEM:", 5)) {
            in_rows = !strncmp(line, "ITEM: ATOMS", 11) || !strncmp(line, "ITEM: ENTRIES", 13);
            if (in_rows) {
                assert_true(snaps < max);
                counts[snaps++] = 0;
            }
        } else if (in_rows) {
            counts[snaps - 1]++;
        }
    }
    gzclose(gz);
    return snaps;
}

/* The k-th data row of snapshot s, split into up to 64 numbers by strtod. */
static int text_row(const char *path, size_t snap, size_t row, double *v)
{
    gzFile gz = gzopen(path, "rb");
    char line[8192];
    size_t s = 0, r = 0;
    int in_rows = 0, n = -1;
    while (gzgets(gz, line, sizeof line)) {
        if (!strncmp(line, "ITEM:", 5)) {
            in_rows = !strncmp(line, "ITEM: ATOMS", 11) || !strncmp(line, "ITEM: ENTRIES", 13);
            if (in_rows)
                s++, r = 0;
            continue;
        }
        if (in_rows && s == snap + 1 && r++ == row) {
            char *p = line, *end;
            n = 0;
            while (n < 64) {
                double x = strtod(p, &end);
                if (end == p)
                    break;
                v[n++] = x;
                p = end;
            }
            break;
        }
    }
    gzclose(gz);
    return n;
}

static size_t find_id(const mimas_particles *p, int64_t id)
{
    for (size_t k = 0; k < p->n; k++)
        if (p->id[k] == id)
            return k;
    fail_msg("id %lld not found", (long long)id);
    return 0;
}

static void test_periodic_counts_and_values(void **state)
{
    (void)state;
    const char *atoms = data("periodic_box/dump.periodic.atom.gz");
    const char *pgl = data("periodic_box/dump.periodic.pgl.gz");
    size_t natoms[32], ncont[32];
    size_t snaps = count_rows(atoms, natoms, 32);
    assert_int_equal(count_rows(pgl, ncont, 32), snaps);
    mimas_reader *r = open_set(atoms, pgl, NULL);
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    size_t k = 0;
    int rc;
    while ((rc = mimas_reader_next(r, &f, &err)) == MIMAS_OK) {
        assert_true(k < snaps);
        assert_int_equal(f.particles.n, natoms[k]);
        assert_int_equal(f.contacts.n, ncont[k]);
        assert_true(f.box.periodic[0] && f.box.periodic[1] && f.box.periodic[2]);
        /* the third row of the snapshot, value by value as strtod reads it:
         * id type x y z ix iy iz vx vy vz fx fy fz wx wy wz radius mass s1..s6 */
        double v[64];
        assert_int_equal(text_row(atoms, k, 2, v), 25);
        size_t i = find_id(&f.particles, (int64_t)v[0]);
        assert_int_equal(f.particles.type[i], (int32_t)v[1]);
        for (int d = 0; d < 3; d++) {
            assert_true(f.particles.pos[i][d] == v[2 + d]);
            assert_int_equal(f.particles.image[i][d], (int32_t)v[5 + d]);
            assert_true(f.particles.vel[i][d] == v[8 + d]);
            assert_true(f.particles.force[i][d] == v[11 + d]);
            assert_true(f.particles.omega[i][d] == v[14 + d]);
        }
        assert_true(f.particles.radius[i] == v[17]);
        assert_true(f.particles.mass[i] == v[18]);
        assert_string_equal(f.particles.extra[0].name, "c_stress");
        for (int c = 0; c < 6; c++)
            assert_true(f.particles.extra[0].data[6 * i + (size_t)c] == v[19 + c]);
        /* the first contact row: ids, force, delta, contact point */
        if (ncont[k] > 0) {
            assert_int_equal(text_row(pgl, k, 0, v), 41);
            assert_int_equal(f.particles.id[f.contacts.i[0]], (int64_t)v[12]);
            assert_int_equal(f.particles.id[f.contacts.j[0]], (int64_t)v[13]);
            for (int d = 0; d < 3; d++) {
                assert_true(f.contacts.force[0][d] == v[15 + d]);
                assert_true(f.contacts.force_n[0][d] == v[18 + d]);
                assert_true(f.contacts.force_t[0][d] == v[21 + d]);
                assert_true(f.contacts.point[0][d] == v[38 + d]);
            }
            assert_true(f.contacts.overlap[0] == v[37]);
        }
        k++;
    }
    assert_int_equal(rc, MIMAS_END);
    assert_int_equal(k, snaps);
    mimas_frame_free(&f);
    mimas_reader_close(r);
}

/* Every contact joins the particles its ids name: LIGGGHTS' overlap equals
 * R_i + R_j - |x_i - x_j| (minimum image) within the 6 printed digits, and
 * the force on i pushes i away from j. */
static void check_geometry(const char *atoms, const char *pgl, size_t *total)
{
    mimas_reader *r = open_set(atoms, pgl, NULL);
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    int rc;
    while ((rc = mimas_reader_next(r, &f, &err)) == MIMAS_OK) {
        const mimas_particles *p = &f.particles;
        for (size_t c = 0; c < f.contacts.n; c++) {
            size_t i = f.contacts.i[c], j = f.contacts.j[c];
            double d[3];
            for (int m = 0; m < 3; m++)
                d[m] = p->pos[i][m] - p->pos[j][m];
            mimas_box_min_image(&f.box, d);
            double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            assert_close(p->radius[i] + p->radius[j] - dist, f.contacts.overlap[c], 3e-7);
            double push = d[0] * f.contacts.force[c][0] + d[1] * f.contacts.force[c][1] +
                          d[2] * f.contacts.force[c][2];
            assert_true(push > 0);
            (*total)++;
        }
    }
    if (rc != MIMAS_END)
        fail_msg("%s", err.msg);
    mimas_frame_free(&f);
    mimas_reader_close(r);
}

static void test_contacts_match_particles_periodic(void **state)
{
    (void)state;
    size_t n = 0;
    check_geometry(data("periodic_box/dump.periodic.atom.gz"),
                   data("periodic_box/dump.periodic.pgl.gz"), &n);
    assert_true(n > 4000);
}

static void test_contacts_match_particles_triclinic(void **state)
{
    (void)state;
    size_t n = 0;
    /* 107 of these contacts cross the tilted faces */
    check_geometry(data("triclinic/dump.triclinic_complete.atom"),
                   data("triclinic/dump.triclinic_complete.pgl"), &n);
    size_t counts[4];
    assert_int_equal(count_rows(data("triclinic/dump.triclinic_complete.pgl"), counts, 4), 1);
    assert_int_equal(n, counts[0]);
}

static void test_triclinic_box_from_bounds(void **state)
{
    (void)state;
    /* LAMMPS dump docs: xlo = xlo_bound - min(0, xy, xz, xy + xz), xhi = xhi_bound -
     * max(...), ylo = ylo_bound - min(0, yz), yhi = yhi_bound - max(0, yz) */
    mimas_reader *r = open_set(data("triclinic/dump.triclinic_complete.atom"), NULL, NULL);
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    assert_int_equal(mimas_reader_next(r, &f, &err), MIMAS_OK);
    /* the header: -0.00131278 0.0243726 0.00219534 / 0 0.0235213 -0.00153673 /
     * -0.000223957 0.0226252 0.00112006 */
    assert_true(f.box.xy == 0.00219534 && f.box.xz == -0.00153673 && f.box.yz == 0.00112006);
    assert_close(f.box.lo[0], -0.00131278 + 0.00153673, 1e-18);
    assert_close(f.box.hi[0], 0.0243726 - 0.00219534, 1e-18);
    assert_close(f.box.lo[1], 0.0, 0.0);
    assert_close(f.box.hi[1], 0.0235213 - 0.00112006, 1e-18);
    assert_true(f.box.lo[2] == -0.000223957 && f.box.hi[2] == 0.0226252);
    mimas_frame_free(&f);
    mimas_reader_close(r);
}

/* Wall contacts of the mesh hopper: the contact point is on the wall at
 * distance R - delta from the particle centre. */
static void test_wall_contacts(void **state)
{
    (void)state;
    mimas_reader *r = open_set(data("hopper_walls/dump.hopper.atom.gz"),
                               data("hopper_walls/dump.hopper.pgl.gz"),
                               data("hopper_walls/dump.hopper.wgl"));
    size_t nw[32];
    size_t snaps = count_rows(data("hopper_walls/dump.hopper.wgl"), nw, 32);
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    size_t k = 0;
    int rc;
    while ((rc = mimas_reader_next(r, &f, &err)) == MIMAS_OK) {
        assert_true(f.has_walls && f.has_contacts);
        assert_int_equal(f.walls.n, nw[k]);
        for (size_t c = 0; c < f.walls.n; c++) {
            size_t i = f.walls.particle[c];
            double d[3], dist = 0;
            for (int m = 0; m < 3; m++) {
                d[m] = f.particles.pos[i][m] - f.walls.point[c][m];
                dist += d[m] * d[m];
            }
            assert_close(f.particles.radius[i] - sqrt(dist), f.walls.overlap[c], 3e-7);
            assert_int_equal(f.walls.wall[c], 0);
        }
        k++;
    }
    assert_int_equal(rc, MIMAS_END);
    assert_int_equal(k, snaps);
    mimas_frame_free(&f);
    mimas_reader_close(r);
}

/* Scaled coordinates in a tilted box, diameters, masses from --density, ITEM: TIME. */
static void test_scaled_diameter_density(void **state)
{
    (void)state;
    char path[] = "/tmp/mimas-test-scaled-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *fp = fdopen(fd, "w");
    /* bounds: x 0..2 with xy = 0.5, xz = 0, yz = 0  ->  xlo = 0, xhi = 1.5 */
    fputs("ITEM: TIME\n0.25\nITEM: TIMESTEP\n7\nITEM: NUMBER OF ATOMS\n2\n"
          "ITEM: BOX BOUNDS xy xz yz pp pp ff\n0 2 0.5\n0 1 0\n-1 1 0\n"
          "ITEM: ATOMS id xs ys zs diameter\n5 0.5 0.5 0.5 0.2\n9 0 1 0 0.4\n", fp);
    fclose(fp);
    const char *inputs[1] = {path};
    mimas_reader_options o;
    mimas_reader_options_default(&o);
    o.density = 2000;
    mimas_reader *r;
    mimas_error err;
    assert_int_equal(mimas_reader_open(&r, inputs, 1, &o, &err), MIMAS_OK);
    mimas_frame f;
    mimas_frame_init(&f);
    assert_int_equal(mimas_reader_next(r, &f, &err), MIMAS_OK);
    assert_true(f.time == 0.25 && f.step == 7);
    assert_true(f.box.lo[0] == 0 && f.box.hi[0] == 1.5 && f.box.xy == 0.5);
    assert_true(f.box.periodic[0] && f.box.periodic[1] && !f.box.periodic[2]);
    /* x = lo + xs Lx + ys xy: (0.5*1.5 + 0.5*0.5, 0.5, -1 + 0.5*2) = (1.0, 0.5, 0) */
    assert_close(f.particles.pos[0][0], 1.0, 1e-15);
    assert_close(f.particles.pos[0][1], 0.5, 1e-15);
    assert_close(f.particles.pos[0][2], 0.0, 1e-15);
    /* ys = 1 (x shifted by xy) is the upper face of the periodic y: the reader
     * wraps it to ys = 0, the same point of the periodic box */
    assert_close(f.particles.pos[1][0], 0.0, 1e-15);
    assert_close(f.particles.pos[1][1], 0.0, 1e-15);
    assert_true(f.particles.radius[0] == 0.1 && f.particles.radius[1] == 0.2);
    assert_close(f.particles.mass[1], 2000 * 4.0 / 3.0 * M_PI * 0.008, 1e-12);
    assert_false(f.particles.present & MIMAS_P_TYPE);
    assert_int_equal(mimas_reader_next(r, &f, &err), MIMAS_END);
    mimas_frame_free(&f);
    mimas_reader_close(r);
    remove(path);
}

/* LAMMPS pair/local + property/local with anonymous columns named by
 * --contact-columns: overlap from the distance, the contact point derived
 * along the branch (docs/theory.md §2), across a periodic face too. */
static void test_lammps_pair_local_derived_point(void **state)
{
    (void)state;
    char atoms[] = "/tmp/mimas-test-pl-atoms-XXXXXX", pairs[] = "/tmp/mimas-test-pl-XXXXXX";
    FILE *fa = fdopen(mkstemp(atoms), "w"), *fp = fdopen(mkstemp(pairs), "w");
    assert_non_null(fa);
    assert_non_null(fp);
    /* 1 and 2 touch along x (gap 0.18, radii 0.1 and 0.1); 3 and 4 across
     * the periodic x face: x = 0.05 and x = 0.97 are 0.08 apart */
    fputs("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n4\nITEM: BOX BOUNDS pp pp pp\n"
          "0 1\n0 1\n0 1\nITEM: ATOMS id x y z radius\n1 0.1 0.5 0.5 0.1\n"
          "2 0.28 0.5 0.5 0.1\n3 0.05 0.2 0.2 0.05\n4 0.97 0.2 0.2 0.04\n", fa);
    fputs("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ENTRIES\n2\nITEM: BOX BOUNDS pp pp pp\n"
          "0 1\n0 1\n0 1\nITEM: ENTRIES c_pa[1] c_pa[2] c_pl[1] c_pl[2] c_pl[3] c_pl[4]\n"
          "2 1 0.18 0.3 0 0\n3 4 0.08 0.2 0 0\n", fp);
    fclose(fa);
    fclose(fp);
    const char *inputs[1] = {atoms}, *contacts[1] = {pairs};
    mimas_reader_options o;
    mimas_reader_options_default(&o);
    o.contacts = contacts;
    o.ncontacts = 1;
    o.contact_columns = "patom1,patom2,dist,fx,fy,fz";
    mimas_reader *r;
    mimas_error err;
    assert_int_equal(mimas_reader_open(&r, inputs, 1, &o, &err), MIMAS_OK);
    mimas_frame f;
    mimas_frame_init(&f);
    if (mimas_reader_next(r, &f, &err))
        fail_msg("%s", err.msg);
    assert_int_equal(f.contacts.n, 2);
    /* contact 0: i = atom 2 (x 0.28), j = atom 1: delta = 0.2 - 0.18 = 0.02,
     * n = +x (from j to i), c = r_i - (R_i - delta/2) n = 0.28 - 0.09 = 0.19 */
    assert_int_equal(f.particles.id[f.contacts.i[0]], 2);
    assert_close(f.contacts.overlap[0], 0.02, 1e-15);
    assert_close(f.contacts.point[0][0], 0.19, 1e-15);
    assert_close(f.contacts.point[0][1], 0.5, 1e-15);
    assert_true(f.contacts.force[0][0] == 0.3);
    /* contact 1: i = atom 3 (x 0.05), j = atom 4 imaged to x = -0.03:
     * delta = 0.09 - 0.08 = 0.01, n = +x, c = 0.05 - (0.05 - 0.005) = 0.005 */
    assert_close(f.contacts.overlap[1], 0.01, 1e-15);
    assert_close(f.contacts.point[1][0], 0.005, 1e-15);
    mimas_frame_free(&f);
    mimas_reader_close(r);
    remove(atoms);
    remove(pairs);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_periodic_counts_and_values),
        cmocka_unit_test(test_contacts_match_particles_periodic),
        cmocka_unit_test(test_contacts_match_particles_triclinic),
        cmocka_unit_test(test_triclinic_box_from_bounds),
        cmocka_unit_test(test_wall_contacts),
        cmocka_unit_test(test_scaled_diameter_density),
        cmocka_unit_test(test_lammps_pair_local_derived_point),
    };
    return cmocka_run_group_tests_name("lammps", tests, NULL, NULL);
}
