/* Averaging grids: parsing, cell geometry, axis frames. */
#include <config.h>

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "assert_close.h"
#include "axis.h"
#include "grid.h"

static void test_cartesian_cells_tile_the_box(void **state)
{
    (void)state;
    mimas_grid g;
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&g, "x=0:1:4,z=-1:2:3", NULL, &err), MIMAS_OK);
    mimas_box b = {{0, -0.5, -1}, {1, 0.25, 2}, 0, 0, 0, {0, 0, 0}};
    mimas_grid_fit_box(&g, &b);
    assert_int_equal(mimas_grid_cells(&g), 12);
    double total = 0;
    for (size_t c = 0; c < 12; c++)
        total += mimas_grid_cell_volume(&g, c);
    assert_close(total, mimas_box_volume(&b), 1e-15);
    double lo[3], hi[3];
    int idx[3] = {3, 0, 2};
    mimas_grid_cell_bounds(&g, mimas_grid_index(&g, idx), lo, hi);
    assert_close(lo[0], 0.75, 0);
    assert_true(hi[0] == 1.0 && hi[2] == 2.0); /* the last cell ends exactly on HI */
    assert_true(lo[1] == -0.5 && hi[1] == 0.25);
    int back[3];
    mimas_grid_unindex(&g, mimas_grid_index(&g, idx), back);
    assert_memory_equal(idx, back, sizeof idx);
}

static void test_cylindrical_volumes(void **state)
{
    (void)state;
    mimas_grid g;
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&g, "r=0:2:5,z=0:1:2", NULL, &err), MIMAS_OK);
    double total = 0;
    for (size_t c = 0; c < mimas_grid_cells(&g); c++)
        total += mimas_grid_cell_volume(&g, c);
    assert_close(total, M_PI * 4.0 * 1.0, 1e-14); /* the full cylinder */
    assert_string_equal(mimas_grid_coord_name(&g, 1), "phi");
}

static void test_axis_frame(void **state)
{
    (void)state;
    mimas_grid g;
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&g, "r=0:1:1", "1,2,3,0,0,2", &err), MIMAS_OK);
    double x[3] = {1.5, 2, 7}, a[3];
    mimas_grid_to_axis(&g, x, a);
    assert_close(a[0], 0.5, 1e-15); /* phi = 0 along the global x */
    assert_close(a[1], 0.0, 1e-15);
    assert_close(a[2], 4.0, 1e-15);
    /* an axis along x: frame still right-handed and orthonormal */
    assert_int_equal(mimas_grid_parse(&g, "r=0:1:1", "0,0,0,-3,0,0", &err), MIMAS_OK);
    double cx = g.ex[1] * g.ey[2] - g.ex[2] * g.ey[1];
    double cy = g.ex[2] * g.ey[0] - g.ex[0] * g.ey[2];
    double cz = g.ex[0] * g.ey[1] - g.ex[1] * g.ey[0];
    assert_close(cx, g.ez[0], 1e-15);
    assert_close(cy, g.ez[1], 1e-15);
    assert_close(cz, g.ez[2], 1e-15);
}

static void test_bad_specs(void **state)
{
    (void)state;
    mimas_grid g;
    mimas_error err;
    const char *bad[] = {"x=1:0:3", "x=0:1:0", "q=0:1:2", "x=0:1:2,x=0:1:2", "r=-1:1:2",
                         "x=0:1", "x=0:1:2junk", "r=0:1:2,phi=0:7:2", "x=a:1:2"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        if (mimas_grid_parse(&g, bad[k], NULL, &err) != MIMAS_EUSAGE)
            fail_msg("'%s' accepted", bad[k]);
    assert_int_equal(mimas_grid_parse(&g, "x=0:1:2", "0,0,0,0,0,1", &err), MIMAS_EUSAGE);
    assert_int_equal(mimas_grid_parse(&g, "r=0:1:2", "0,0,0,0,0,0", &err), MIMAS_EUSAGE);
}

static void test_none_and_tilted_box(void **state)
{
    (void)state;
    mimas_grid g;
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&g, "none", NULL, &err), MIMAS_OK);
    mimas_box b = {{0, 0, 0}, {1, 2, 3}, 0.5, -0.25, 0, {0, 1, 1}};
    mimas_grid_fit_box(&g, &b);
    /* x is not periodic: the bounding box of the tilted box, -0.25 .. 1.5;
     * y and z are: lo .. hi, a fundamental domain */
    assert_close(g.lo[0], -0.25, 0);
    assert_close(g.hi[0], 1.5, 0);
    assert_true(g.lo[1] == 0 && g.hi[1] == 2 && g.hi[2] == 3);
    assert_int_equal(mimas_grid_cells(&g), 1);
}

/* mimas_axis: an orthonormal right-handed frame for any direction; points
 * and vectors into it; bad specs refused. */
static void test_axis_module(void **state)
{
    (void)state;
    const double dirs[4][3] = {{1, 1, 0}, {1, 0, 0}, {0, 0, -2}, {0.3, -0.4, 0.8}};
    for (int k = 0; k < 4; k++) {
        mimas_axis a;
        const double o[3] = {1, 2, 3};
        assert_int_equal(mimas_axis_set(&a, o, dirs[k], NULL), MIMAS_OK);
        const double *e[3] = {a.ex, a.ey, a.ez};
        for (int p = 0; p < 3; p++)
            for (int q = 0; q < 3; q++)
                assert_close(e[p][0] * e[q][0] + e[p][1] * e[q][1] + e[p][2] * e[q][2],
                             p == q ? 1.0 : 0.0, 1e-15);
        /* e_x x e_y = e_z */
        assert_close(a.ex[1] * a.ey[2] - a.ex[2] * a.ey[1], a.ez[0], 1e-15);
        double len = sqrt(dirs[k][0] * dirs[k][0] + dirs[k][1] * dirs[k][1] +
                          dirs[k][2] * dirs[k][2]);
        double x[3] = {o[0] + 2 * dirs[k][0] / len, o[1] + 2 * dirs[k][1] / len,
                       o[2] + 2 * dirs[k][2] / len}, l[3];
        mimas_axis_to_local(&a, x, l);
        assert_close(l[0], 0, 1e-15);
        assert_close(l[1], 0, 1e-15);
        assert_close(l[2], 2, 1e-15);
        mimas_axis_vector_to_local(&a, a.ex, l);
        assert_close(l[0], 1, 1e-15);
    }
    mimas_axis a;
    mimas_error err;
    assert_int_equal(mimas_axis_parse(&a, "0,0,0,0,0,0", &err), MIMAS_EUSAGE);
    assert_int_equal(mimas_axis_parse(&a, "0,0,0,1,0", &err), MIMAS_EUSAGE);
    assert_int_equal(mimas_axis_parse(&a, "0,0,0,1,0,1,", &err), MIMAS_EUSAGE);
    assert_int_equal(mimas_axis_parse(&a, NULL, &err), MIMAS_OK);
    assert_true(a.ez[2] == 1.0 && a.ex[0] == 1.0 && a.ey[1] == 1.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cartesian_cells_tile_the_box),
        cmocka_unit_test(test_cylindrical_volumes),
        cmocka_unit_test(test_axis_frame),
        cmocka_unit_test(test_axis_module),
        cmocka_unit_test(test_bad_specs),
        cmocka_unit_test(test_none_and_tilted_box),
    };
    return cmocka_run_group_tests_name("grid", tests, NULL, NULL);
}
