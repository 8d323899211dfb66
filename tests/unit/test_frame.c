/* Data model: generic table operations, the id map and box geometry. */
#include <config.h>

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "assert_close.h"

#include "frame.h"
#include "id_index.h"

static void test_required_present_after_init(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    assert_int_equal(mimas_table_present(&f.particles, &mimas_particles_desc),
                     MIMAS_P_ID | MIMAS_P_POS);
    assert_int_equal(mimas_table_present(&f.contacts, &mimas_contacts_desc),
                     MIMAS_C_I | MIMAS_C_J);
    assert_null(f.particles.vel);
    mimas_frame_free(&f);
}

static void test_resize_keeps_values(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    assert_int_equal(mimas_table_set_present(&f.particles, &mimas_particles_desc,
                                             MIMAS_P_VEL | MIMAS_P_RADIUS, &err), MIMAS_OK);
    assert_int_equal(mimas_table_resize(&f.particles, &mimas_particles_desc, 10, &err), 0);
    for (size_t k = 0; k < 10; k++) {
        f.particles.id[k] = (int64_t)k;
        f.particles.vel[k][2] = (double)k;
        f.particles.radius[k] = 0.5 * (double)k;
    }
    size_t e;
    assert_int_equal(mimas_table_add_extra(&f.particles, &mimas_particles_desc, "q", 2, &e,
                                           &err), MIMAS_OK);
    f.particles.extra[e].data[19] = 7.0;
    assert_int_equal(mimas_table_resize(&f.particles, &mimas_particles_desc, 100000, &err), 0);
    assert_true(f.particles.cap >= 100000);
    for (size_t k = 0; k < 10; k++) {
        assert_int_equal(f.particles.id[k], (int64_t)k);
        assert_true(f.particles.vel[k][2] == (double)k);
        assert_true(f.particles.radius[k] == 0.5 * (double)k);
    }
    assert_true(f.particles.extra[e].data[19] == 7.0);
    /* a second add of the same name finds it; a different width is an error */
    size_t e2;
    assert_int_equal(mimas_table_add_extra(&f.particles, &mimas_particles_desc, "q", 2, &e2,
                                           &err), MIMAS_OK);
    assert_int_equal(e2, e);
    assert_int_equal(mimas_table_add_extra(&f.particles, &mimas_particles_desc, "q", 3, &e2,
                                           &err), MIMAS_EDATA);
    assert_int_equal(mimas_table_add_extra(&f.particles, &mimas_particles_desc, "velocity", 3,
                                           &e2, &err), MIMAS_EDATA);
    mimas_frame_free(&f);
}

static void test_require_names_missing(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    assert_int_equal(mimas_table_require(&f.contacts, &mimas_contacts_desc,
                                         MIMAS_C_I | MIMAS_C_POINT, &err), MIMAS_EMISSING);
    assert_string_equal(err.msg, "contacts have no contact_point");
    assert_int_equal(mimas_table_require(&f.particles, &mimas_particles_desc, MIMAS_P_ID, &err),
                     MIMAS_OK);
    mimas_frame_free(&f);
}

static void test_clear_drops_optional(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    mimas_table_set_present(&f.walls, &mimas_walls_desc, MIMAS_W_FORCE, &err);
    mimas_table_resize(&f.walls, &mimas_walls_desc, 5, &err);
    f.has_walls = 1;
    mimas_frame_clear(&f);
    assert_int_equal(f.walls.n, 0);
    assert_null(f.walls.force);
    assert_non_null(f.walls.particle);
    assert_int_equal(f.has_walls, 0);
    mimas_frame_free(&f);
}

static void test_id_index_dense_and_sorted(void **state)
{
    (void)state;
    mimas_id_index x;
    mimas_id_index_init(&x);
    mimas_error err;
    int64_t dense[] = {5, 3, 9, 4};
    assert_int_equal(mimas_id_index_build(&x, dense, 4, &err), MIMAS_OK);
    size_t k;
    assert_true(mimas_id_index_find(&x, 9, &k));
    assert_int_equal(k, 2);
    assert_false(mimas_id_index_find(&x, 6, &k));
    assert_false(mimas_id_index_find(&x, 2, &k));
    assert_false(mimas_id_index_find(&x, 100, &k));
    int64_t sparse[] = {1000000000000LL, -7, 42};
    assert_int_equal(mimas_id_index_build(&x, sparse, 3, &err), MIMAS_OK);
    assert_int_equal(x.span, 0); /* sorted mode */
    assert_true(mimas_id_index_find(&x, -7, &k));
    assert_int_equal(k, 1);
    assert_true(mimas_id_index_find(&x, 1000000000000LL, &k));
    assert_int_equal(k, 0);
    assert_false(mimas_id_index_find(&x, 43, &k));
    int64_t dup[] = {1, 2, 1};
    assert_int_equal(mimas_id_index_build(&x, dup, 3, &err), MIMAS_EDATA);
    assert_string_equal(err.msg, "duplicate particle id 1");
    int64_t dup_sparse[] = {1, 1LL << 40, 1LL << 40};
    assert_int_equal(mimas_id_index_build(&x, dup_sparse, 3, &err), MIMAS_EDATA);
    mimas_id_index_free(&x);
}

static void test_box_geometry(void **state)
{
    (void)state;
    mimas_box b = {{-1, 0, 2}, {1, 3, 6}, 0.5, -0.25, 0.75, {1, 1, 0}};
    assert_true(mimas_box_is_triclinic(&b));
    /* volume = |a . (b x c)| of the edge vectors: the tilt does not change it */
    double e[3][3];
    mimas_box_edges(&b, e);
    double cx = e[1][1] * e[2][2] - e[1][2] * e[2][1];
    double cy = e[1][2] * e[2][0] - e[1][0] * e[2][2];
    double cz = e[1][0] * e[2][1] - e[1][1] * e[2][0];
    double triple = e[0][0] * cx + e[0][1] * cy + e[0][2] * cz;
    assert_close(mimas_box_volume(&b), 24.0, 0.0);
    assert_close(triple, 24.0, 1e-15);
    assert_true(e[1][0] == 0.5 && e[2][0] == -0.25 && e[2][1] == 0.75);
}

/* The gas grid grows, keeps its shape, refuses empty or overflowing sizes,
 * and a cleared frame has neither gas fields nor a tube. */
static void test_gas_grid(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    assert_false(f.gas.present);
    assert_int_equal(mimas_gas_cells(&f.gas), 0);
    assert_int_equal(mimas_gas_resize(&f.gas, 150, 2, 2, &err), MIMAS_OK);
    assert_int_equal(mimas_gas_cells(&f.gas), 600);
    for (size_t c = 0; c < 600; c++)
        f.gas.pressure[c] = (double)c, f.gas.velocity[c][2] = -(double)c;
    assert_int_equal(mimas_gas_resize(&f.gas, 2, 2, 2, &err), MIMAS_OK);
    assert_int_equal(mimas_gas_cells(&f.gas), 8);
    assert_true(f.gas.pressure[7] == 7.0 && f.gas.velocity[7][2] == -7.0);
    assert_int_equal(mimas_gas_resize(&f.gas, 0, 2, 2, &err), MIMAS_EDATA);
    assert_int_equal(mimas_gas_resize(&f.gas, SIZE_MAX / 2, 4, 1, &err), MIMAS_EDATA);
    f.tube.present = 1;
    mimas_frame_clear(&f);
    assert_false(f.gas.present);
    assert_false(f.tube.present);
    assert_int_equal(mimas_gas_cells(&f.gas), 0);
    mimas_frame_free(&f);
}

/* Boxes compare by value: -0 equals 0, the bytes between the fields do not count, and
 * each bound, tilt and periodic flag does. */
static void test_box_equal(void **state)
{
    (void)state;
    mimas_box a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0xff, sizeof b); /* other padding bytes */
    mimas_box ref = {{0, 0, 0}, {1, 2, 3}, 0, 0, 0, {1, 0, 1}};
    for (int d = 0; d < 3; d++) {
        a.lo[d] = ref.lo[d];
        a.hi[d] = ref.hi[d];
        a.periodic[d] = ref.periodic[d];
        b.lo[d] = d == 0 ? -0.0 : ref.lo[d];
        b.hi[d] = ref.hi[d];
        b.periodic[d] = ref.periodic[d];
    }
    a.xy = a.xz = a.yz = 0.0;
    b.xy = -0.0;
    b.xz = b.yz = 0.0;
    assert_true(mimas_box_equal(&a, &b));
    b.hi[2] = 3.0000000000000004;
    assert_false(mimas_box_equal(&a, &b));
    b.hi[2] = 3;
    b.yz = 1e-300;
    assert_false(mimas_box_equal(&a, &b));
    b.yz = 0;
    b.periodic[1] = 1;
    assert_false(mimas_box_equal(&a, &b));
}

/* The minimum image against its definition (LAMMPS' convention): d' = d - k_z e_z - k_y e_y -
 * k_x e_x with whole k, each component of d' within half a period of its axis after the
 * shifts of the axes above it (z, then y, then x), no shift along an axis that is not
 * periodic; a component already within half a period (its boundary included) keeps its
 * bits.  Orthogonal and tilted boxes, every subset of periodic axes, differences up to three
 * periods, on and just past the half periods. */
static void test_min_image(void **state)
{
    (void)state;
    const double tilts[2][3] = {{0, 0, 0}, {0.31, -0.27, 0.45}};
    unsigned long long seed = 88172645463325252ULL;
    for (int t = 0; t < 2; t++)
        for (int per = 0; per < 8; per++) {
            mimas_box b = {{-0.2, 0.1, -1.0}, {0.9, 1.4, 0.6}, 0, 0, 0, {0, 0, 0}};
            b.xy = tilts[t][0], b.xz = tilts[t][1], b.yz = tilts[t][2];
            for (int a = 0; a < 3; a++)
                b.periodic[a] = (per >> a) & 1;
            double L[3], e[3][3];
            mimas_box_edges(&b, e);
            for (int a = 0; a < 3; a++)
                L[a] = b.hi[a] - b.lo[a];
            for (int n = 0; n < 400; n++) {
                double d[3], d0[3];
                for (int a = 0; a < 3; a++) {
                    seed ^= seed << 13, seed ^= seed >> 7, seed ^= seed << 17;
                    double u = (double)(seed >> 11) / 9007199254740992.0; /* [0, 1) */
                    d[a] = (6.0 * u - 3.0) * L[a];
                    if (n % 5 == 1) /* on a half period, or just past it */
                        d[a] = (n % 2 ? -0.5 : 0.5) * L[a];
                    else if (n % 5 == 2)
                        d[a] = nextafter(0.5 * L[a], 1.0) * (n % 2 ? -1 : 1);
                    d0[a] = d[a];
                }
                double k[3];
                mimas_box_min_image_shift(&b, d, k);
                double want[3] = {d0[0], d0[1], d0[2]};
                for (int a = 2; a >= 0; a--) {
                    assert_true(k[a] == nearbyint(k[a]));
                    if (!b.periodic[a])
                        assert_true(k[a] == 0.0);
                    for (int c = 0; c < 3; c++)
                        want[c] -= k[a] * e[a][c];
                }
                for (int a = 0; a < 3; a++) {
                    assert_true(fabs(d[a] - want[a]) <= 1e-12 * 4.0 * L[a]);
                    if (b.periodic[a])
                        assert_true(fabs(d[a]) <= 0.5 * L[a] * (1 + 1e-12));
                }
                /* a component within half a period, with no shift from the axes above it
                 * (they shift it by their tilt), is left as it was, to the bit */
                if (k[2] == 0.0 && fabs(d0[2]) <= 0.5 * L[2])
                    assert_true(d[2] == d0[2]);
                if (k[2] == 0.0 && fabs(d0[1]) <= 0.5 * L[1])
                    assert_true(d[1] == d0[1]);
            }
        }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_required_present_after_init),
        cmocka_unit_test(test_resize_keeps_values),
        cmocka_unit_test(test_require_names_missing),
        cmocka_unit_test(test_clear_drops_optional),
        cmocka_unit_test(test_id_index_dense_and_sorted),
        cmocka_unit_test(test_box_geometry),
        cmocka_unit_test(test_gas_grid),
        cmocka_unit_test(test_box_equal),
        cmocka_unit_test(test_min_image),
    };
    return cmocka_run_group_tests_name("frame", tests, NULL, NULL);
}
