/* voro++ wrapper: cells of lattices have the analytic volumes, and cell
 * volumes sum to the box volume. */
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

#include "voro_cells.h"

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

static void check_lattice(const double (*basis)[3], int nb, int expected_faces)
{
    const int m = 5;
    const double a = 0.37;
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
    };
    return cmocka_run_group_tests_name("voro", tests, NULL, NULL);
}
