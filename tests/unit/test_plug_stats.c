/* The plug measurements of the validation (bench/plug_stats.c) on
 * constructed data: slice porosity of spheres with known overlaps, plugs of
 * a known profile, velocities of shifted plugs, the slope of a line. */
#include <config.h>

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "assert_close.h"
#include "plug_stats.h"

static void test_porosity(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    assert_int_equal(mimas_table_set_present(&f.particles, &mimas_particles_desc,
                                             MIMAS_P_RADIUS | MIMAS_P_TYPE, NULL), MIMAS_OK);
    assert_int_equal(mimas_table_resize(&f.particles, &mimas_particles_desc, 3, NULL), MIMAS_OK);
    /* one sphere inside slice 1, one cut in half by the plane z = 0.02 (slices 1 and 2),
     * one of type 2 (left out) */
    double z[3] = {0.015, 0.02, 0.015};
    for (int k = 0; k < 3; k++) {
        f.particles.id[k] = k + 1;
        f.particles.type[k] = k == 2 ? 2 : 1;
        f.particles.radius[k] = 0.002;
        f.particles.pos[k][0] = f.particles.pos[k][1] = 0;
        f.particles.pos[k][2] = z[k];
    }
    double phi[4], R = 0.005, w = 0.01, V = 4.0 / 3.0 * M_PI * 8e-9, A = M_PI * R * R * w;
    plug_porosity(&f, R, 4, w, 2, phi);
    assert_close(phi[0], 1, 1e-15);
    assert_close(phi[1], 1 - 1.5 * V / A, 1e-12);
    assert_close(phi[2], 1 - 0.5 * V / A, 1e-12);
    assert_close(phi[3], 1, 1e-15);
    mimas_frame_free(&f);
}

static void test_find_and_match(void **state)
{
    (void)state;
    /* runs below 0.6: slices 2-4 (solid 0.5, 0.6, 0.5: centre at slice 3) and 8-9; the
     * one-slice run at 12 is too short */
    double phi[14] = {1, 0.9, 0.5, 0.4, 0.5, 0.7, 1, 1, 0.45, 0.45, 0.8, 1, 0.5, 1};
    plug p[8];
    size_t n = plug_find(phi, 14, 0.01, 0.6, 2, p, 8);
    assert_int_equal(n, 2);
    assert_close(p[0].lo, 0.02, 1e-15);
    assert_close(p[0].hi, 0.05, 1e-15);
    assert_close(p[0].centre, 0.035, 1e-15);
    assert_close(p[1].centre, 0.09, 1e-15);
    /* the same plugs 2 mm and 5 mm further on, 0.01 s later, and a new one far away */
    plug q[3] = {{0.022, 0.052, 0.037}, {0.2, 0.21, 0.205}, {0.085, 0.105, 0.095}};
    double v[3];
    assert_int_equal(plug_match(p, 2, q, 3, 0.01, 0.02, v), 2);
    assert_close(v[0], 0.2, 1e-12);
    assert_true(isnan(v[1]));
    assert_close(v[2], 0.5, 1e-12);
}

static void test_slope(void **state)
{
    (void)state;
    double t[5] = {0.1, 0.2, 0.3, 0.4, 0.5}, s2[5];
    for (int k = 0; k < 5; k++)
        s2[k] = 1e-3 + 2 * 3.8e-4 * t[k];
    assert_close(plug_slope(t, s2, 5) / 2, 3.8e-4, 1e-15);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_porosity),
        cmocka_unit_test(test_find_and_match),
        cmocka_unit_test(test_slope),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
