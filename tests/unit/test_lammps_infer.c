/* LIGGGHTS local-dump columns told from their count, and the check of the
 * guess on contacts whose geometry is known. */
#include <config.h>

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "frame.h"
#include "lammps_infer.h"

/* The counts LIGGGHTS' compute_pair_gran_local makes: nvalues = 6 pos + 6 vel
 * + 3 id + 3 force [+ 3 fn + 3 ft + 9 torques] + 3 torque + H history + 1
 * area [+ 1 delta + 3 contactPoint]. */
static void test_counts(void **state)
{
    (void)state;
    char kw[512];
    assert_int_equal(gran_infer_keywords(25, kw, sizeof kw), 0);
    assert_string_equal(kw, "pos,vel,id,force,torque,history:3,contactArea");
    assert_int_equal(gran_infer_keywords(41, kw, sizeof kw), 0);
    assert_string_equal(kw, "pos,vel,id,force,force_normal,force_tangential,torque,"
                            "torque_normal,torque_tangential,history:3,contactArea,delta,"
                            "contactPoint");
    assert_int_equal(gran_infer_keywords(38, kw, sizeof kw), 0);
    assert_null(strstr(kw, "history"));
    assert_int_equal(gran_infer_keywords(23, kw, sizeof kw), 0);
    assert_non_null(strstr(kw, "history:1,contactArea"));
    /* 22: the default set would need a history of 0, which LIGGGHTS refuses */
    assert_int_equal(gran_infer_keywords(22, kw, sizeof kw), -1);
    assert_int_equal(gran_infer_keywords(5, kw, sizeof kw), -1);
}

/* Two spheres of radii 0.002 and 0.003 whose centres are 0.0049 apart along
 * a tilted direction, with a wall contact of the first on the plane z = 0. */
static void make_frame(mimas_frame *f)
{
    mimas_frame_init(f);
    mimas_particles *p = &f->particles;
    assert_int_equal(mimas_table_set_present(p, &mimas_particles_desc,
                                             MIMAS_P_ID | MIMAS_P_POS | MIMAS_P_RADIUS, NULL), 0);
    assert_int_equal(mimas_table_resize(p, &mimas_particles_desc, 2, NULL), 0);
    double u[3] = {0.6, 0.0, 0.8};
    p->id[0] = 1, p->id[1] = 2;
    p->radius[0] = 0.002, p->radius[1] = 0.003;
    for (int d = 0; d < 3; d++) {
        p->pos[0][d] = 0.01 + (d == 2 ? 0.00199 - 0.01 : 0);
        p->pos[1][d] = p->pos[0][d] + 0.0049 * u[d];
    }
    for (int d = 0; d < 3; d++)
        f->box.lo[d] = 0, f->box.hi[d] = 0.1;
    mimas_contacts *c = &f->contacts;
    assert_int_equal(mimas_table_set_present(c, &mimas_contacts_desc,
                                             MIMAS_C_I | MIMAS_C_J | MIMAS_C_POINT |
                                                 MIMAS_C_FORCE | MIMAS_C_FORCE_N |
                                                 MIMAS_C_FORCE_T | MIMAS_C_OVERLAP, NULL), 0);
    assert_int_equal(mimas_table_resize(c, &mimas_contacts_desc, 1, NULL), 0);
    size_t e;
    assert_int_equal(mimas_table_add_extra(c, &mimas_contacts_desc, "contact_area", 1, &e, NULL), 0);
    c->i[0] = 0, c->j[0] = 1;
    c->overlap[0] = 0.0001;
    /* the circle where the spheres meet: its centre at distance
     * h = (r^2 + ri^2 - rj^2)/(2r) from i, its radius sqrt(ri^2 - h^2) */
    double r = 0.0049, h = (r * r + 0.002 * 0.002 - 0.003 * 0.003) / (2 * r);
    c->extra[e].data[0] = M_PI * (0.002 * 0.002 - h * h);
    double t[3] = {0.8, 0.0, -0.6}; /* perpendicular to u */
    for (int d = 0; d < 3; d++) {
        c->point[0][d] = p->pos[0][d] + h * u[d];
        c->force_n[0][d] = -5.0 * u[d];
        c->force_t[0][d] = 0.5 * t[d];
        c->force[0][d] = c->force_n[0][d] + c->force_t[0][d];
    }
    mimas_wall_contacts *w = &f->walls;
    assert_int_equal(mimas_table_set_present(w, &mimas_walls_desc,
                                             MIMAS_W_PARTICLE | MIMAS_W_WALL | MIMAS_W_POINT |
                                                 MIMAS_W_OVERLAP, NULL), 0);
    assert_int_equal(mimas_table_resize(w, &mimas_walls_desc, 1, NULL), 0);
    w->particle[0] = 0;
    w->wall[0] = 0;
    for (int d = 0; d < 3; d++)
        w->point[0][d] = d == 2 ? 0.0 : p->pos[0][d];
    w->overlap[0] = 0.002 - 0.00199;
}

static void test_checks(void **state)
{
    (void)state;
    mimas_frame f;
    make_frame(&f);
    char why[256] = "";
    int ok = gran_check_inferred(&f, 0, why, sizeof why);
    if (ok)
        fprintf(stderr, "why: %s\n", why);
    assert_int_equal(ok, 0);
    assert_int_equal(gran_check_inferred(&f, 1, why, sizeof why), 0);
    /* columns read as the wrong quantity do not fit */
    f.contacts.overlap[0] = 0.0003;
    assert_int_equal(gran_check_inferred(&f, 0, why, sizeof why), -1);
    assert_non_null(strstr(why, "overlap"));
    f.contacts.overlap[0] = 0.0001;
    f.contacts.extra[0].data[0] *= 1.5;
    assert_int_equal(gran_check_inferred(&f, 0, why, sizeof why), -1);
    assert_non_null(strstr(why, "contact area"));
    f.contacts.extra[0].data[0] /= 1.5;
    f.contacts.force_t[0][1] = 0.5;
    assert_int_equal(gran_check_inferred(&f, 0, why, sizeof why), -1);
    f.contacts.force_t[0][1] = 0.0;
    f.contacts.point[0][0] += 0.001;
    assert_int_equal(gran_check_inferred(&f, 0, why, sizeof why), -1);
    assert_non_null(strstr(why, "between"));
    f.walls.overlap[0] = 0.001;
    assert_int_equal(gran_check_inferred(&f, 1, why, sizeof why), -1);
    mimas_frame_free(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_counts),
        cmocka_unit_test(test_checks),
    };
    return cmocka_run_group_tests_name("lammps_infer", tests, NULL, NULL);
}
