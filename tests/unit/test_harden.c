/* Unit tests of the shared safety nets of issue 15: the frame validation
 * every reader applies, the wrapping into periodic boxes (orthogonal and
 * triclinic, image flags kept consistent), the registry of temporary files,
 * and the native file of zero frames. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "assert_close.h"
#include "frame.h"
#include "native.h"
#include "scratch.h"
#include "tmpfiles.h"

static void one_particle(mimas_frame *f, const double x[3])
{
    mimas_error err;
    mimas_frame_clear(f);
    f->time = 0;
    f->box = (mimas_box){{-1, 0, 2}, {1, 3, 6}, 0, 0, 0, {1, 1, 0}};
    assert_int_equal(mimas_table_set_present(&f->particles, &mimas_particles_desc,
                                             MIMAS_P_ID | MIMAS_P_POS | MIMAS_P_RADIUS |
                                                 MIMAS_P_VEL | MIMAS_P_IMAGE,
                                             &err),
                     MIMAS_OK);
    assert_int_equal(mimas_table_resize(&f->particles, &mimas_particles_desc, 1, &err), MIMAS_OK);
    f->particles.id[0] = 42;
    f->particles.radius[0] = 0.1;
    memcpy(f->particles.pos[0], x, 3 * sizeof *x);
    memset(f->particles.vel[0], 0, sizeof f->particles.vel[0]);
    memset(f->particles.image[0], 0, sizeof f->particles.image[0]);
}

/* Orthogonal box, periodic in x and y: whole box lengths come off and go to
 * the image flags; z (walls) is left alone. */
static void test_wrap_orthogonal(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    double x[3] = {-1 + 0.25 + 3 * 2.0, 0.5 - 2 * 3.0, 7.5};
    one_particle(&f, x);
    mimas_error err;
    assert_int_equal(mimas_frame_wrap(&f, &err), MIMAS_OK);
    assert_close(f.particles.pos[0][0], -0.75, 1e-14);
    assert_close(f.particles.pos[0][1], 0.5, 1e-14);
    assert_true(f.particles.pos[0][2] == 7.5);
    assert_int_equal(f.particles.image[0][0], 3);
    assert_int_equal(f.particles.image[0][1], -2);
    assert_int_equal(f.particles.image[0][2], 0);
    /* the upper face of a periodic direction is its lower face */
    double top[3] = {1.0, 1.0, 3.0};
    one_particle(&f, top);
    assert_int_equal(mimas_frame_wrap(&f, &err), MIMAS_OK);
    assert_true(f.particles.pos[0][0] == -1.0 && f.particles.image[0][0] == 1);
    /* too far to count in image flags */
    double far[3] = {1e300, 1, 3};
    one_particle(&f, far);
    assert_int_equal(mimas_frame_wrap(&f, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "particle id 42"));
    mimas_frame_free(&f);
}

/* Triclinic, periodic in all three: the point shifted by 2a - b + c comes
 * back (a = (2,0,0), b = (0.5,3,0), c = (-0.3,0.4,4)). */
static void test_wrap_triclinic(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    double in[3] = {0.2, 1.1, 3.0}, x[3];
    double a[3] = {2, 0, 0}, b[3] = {0.5, 3, 0}, c[3] = {-0.3, 0.4, 4};
    for (int d = 0; d < 3; d++)
        x[d] = in[d] + 2 * a[d] - b[d] + c[d];
    one_particle(&f, x);
    f.box.xy = 0.5;
    f.box.xz = -0.3;
    f.box.yz = 0.4;
    f.box.periodic[2] = 1;
    mimas_error err;
    assert_int_equal(mimas_frame_wrap(&f, &err), MIMAS_OK);
    for (int d = 0; d < 3; d++)
        assert_close(f.particles.pos[0][d], in[d], 1e-13);
    assert_int_equal(f.particles.image[0][0], 2);
    assert_int_equal(f.particles.image[0][1], -1);
    assert_int_equal(f.particles.image[0][2], 1);
    mimas_frame_free(&f);
}

static void test_frame_check(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    double x[3] = {0, 1, 3};
    one_particle(&f, x);
    mimas_error err;
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_OK);
    f.particles.vel[0][2] = NAN;
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_EDATA);
    assert_string_equal(err.msg, "particle id 42 (row 0): velocity component 3 is nan");
    f.particles.vel[0][2] = 0;
    f.particles.radius[0] = 0;
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "radius is not positive"));
    f.particles.radius[0] = 0.1;
    f.box.hi[1] = f.box.lo[1];
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "box bounds in y"));
    f.box.hi[1] = 3;
    /* a contact naming a particle the frame does not have */
    f.has_contacts = 1;
    assert_int_equal(mimas_table_resize(&f.contacts, &mimas_contacts_desc, 1, &err), MIMAS_OK);
    f.contacts.i[0] = 0;
    f.contacts.j[0] = 5;
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_EDATA);
    assert_string_equal(err.msg, "contacts row 0: j refers to row 5 of 1 particles");
    /* the first bad row of several, in the column checked first (the indices) */
    assert_int_equal(mimas_table_set_present(&f.contacts, &mimas_contacts_desc, MIMAS_C_FORCE,
                                             &err), MIMAS_OK);
    assert_int_equal(mimas_table_resize(&f.contacts, &mimas_contacts_desc, 5, &err), MIMAS_OK);
    for (size_t k = 0; k < 5; k++) {
        f.contacts.i[k] = f.contacts.j[k] = 0;
        for (int d = 0; d < 3; d++)
            f.contacts.force[k][d] = 1.0;
    }
    f.contacts.j[3] = 7;
    f.contacts.i[4] = 9;
    f.contacts.force[2][1] = NAN;
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_EDATA);
    assert_string_equal(err.msg, "contacts row 4: i refers to row 9 of 1 particles");
    f.contacts.i[4] = 0;
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_EDATA);
    assert_string_equal(err.msg, "contacts row 3: j refers to row 7 of 1 particles");
    f.contacts.j[3] = 0;
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_EDATA);
    assert_string_equal(err.msg, "contacts row 2: force is nan");
    f.contacts.force[2][1] = -INFINITY;
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_EDATA);
    assert_string_equal(err.msg, "contacts row 2: force is -inf");
    f.contacts.force[2][1] = 1.0;
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_OK);
    assert_int_equal(mimas_table_resize(&f.contacts, &mimas_contacts_desc, 1, &err), MIMAS_OK);
    f.time = INFINITY;
    f.contacts.j[0] = 0;
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_EDATA);
    f.time = NAN; /* unknown: allowed */
    assert_int_equal(mimas_frame_check(&f, &err), MIMAS_OK);
    mimas_frame_free(&f);
}

static void test_tmpfiles(void **state)
{
    (void)state;
    char name[64];
    assert_int_equal(mimas_tmpfile_name(name, sizeof name, "a.h5"), 0);
    char want[64];
    snprintf(want, sizeof want, "a.h5.tmp%ld", (long)getpid());
    assert_string_equal(name, want);
    assert_int_equal(mimas_tmpfile_name(name, 8, "a-long-name.h5"), -1);
    const char *p1 = scratch_path("t1.tmp"), *p2 = scratch_path("t2.tmp");
    FILE *f1 = fopen(p1, "w"), *f2 = fopen(p2, "w");
    assert_non_null(f1);
    assert_non_null(f2);
    fclose(f1);
    fclose(f2);
    int s1 = mimas_tmpfile_add(p1), s2 = mimas_tmpfile_add(p2);
    assert_true(s1 >= 0 && s2 >= 0 && s1 != s2);
    mimas_tmpfile_forget(s2); /* renamed into place: must stay */
    mimas_tmpfile_remove_all();
    assert_int_equal(access(p1, F_OK), -1);
    assert_int_equal(access(p2, F_OK), 0);
    mimas_tmpfile_forget(s1);
    remove(p2);
}

/* A writer's file exists only once its header is on disk, and reads as a
 * file of zero frames until the first frame comes. */
static void test_zero_frames(void **state)
{
    (void)state;
    const char *path = scratch_path("zero.h5");
    mimas_writer *w;
    mimas_error err;
    assert_int_equal(mimas_writer_open(&w, path, NULL, &err), MIMAS_OK);
    assert_int_equal(access(path, F_OK), 0);
    assert_int_equal(mimas_writer_close(w, &err), MIMAS_OK);
    mimas_native *r;
    assert_int_equal(mimas_native_open(&r, path, &err), MIMAS_OK);
    assert_int_equal(mimas_native_frames(r), 0);
    mimas_native_close(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wrap_orthogonal), cmocka_unit_test(test_wrap_triclinic),
        cmocka_unit_test(test_frame_check), cmocka_unit_test(test_tmpfiles),
        cmocka_unit_test(test_zero_frames),
    };
    return cmocka_run_group_tests_name("harden", tests, scratch_setup, scratch_teardown);
}
