/* Radial probe profiles (averaging/radial.c): one particle against probes
 * whose lens volumes are computed here as the sum of two caps; velocities,
 * rotational energy, temperature and the averages over samples. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "assert_close.h"

#include <math.h>
#include <string.h>

#include "axial_profile.h"
#include "radial.h"

#define PI 3.14159265358979323846

static double cap(double R, double h)
{
    return h <= 0 ? 0 : PI * h * h * (3.0 * R - h) / 3.0;
}

/* the lens of two balls d apart, as two caps (independent of overlap.c) */
static double lens(double d, double R1, double R2)
{
    if (d >= R1 + R2)
        return 0;
    if (d <= fabs(R1 - R2)) {
        double r = fmin(R1, R2);
        return 4.0 / 3.0 * PI * r * r * r;
    }
    double x = (d * d + R1 * R1 - R2 * R2) / (2 * d);
    return cap(R1, R1 - x) + cap(R2, R2 - (d - x));
}

static void one_particle(mimas_frame *f, double x, double y, double z, double a, double m,
                         const double v[3], const double w[3])
{
    mimas_frame_init(f);
    mimas_error err;
    assert_int_equal(mimas_table_set_present(&f->particles, &mimas_particles_desc,
                                             MIMAS_P_ID | MIMAS_P_RADIUS | MIMAS_P_MASS |
                                                 MIMAS_P_POS | MIMAS_P_VEL | MIMAS_P_OMEGA,
                                             &err), 0);
    assert_int_equal(mimas_table_resize(&f->particles, &mimas_particles_desc, 1, &err), 0);
    mimas_particles *p = &f->particles;
    p->id[0] = 1;
    p->pos[0][0] = x, p->pos[0][1] = y, p->pos[0][2] = z;
    memcpy(p->vel[0], v, 3 * sizeof *v);
    memcpy(p->omega[0], w, 3 * sizeof *w);
    p->radius[0] = a;
    p->mass[0] = m;
}

/* A particle on the axis: every probe of a circle is at the same distance
 * from it, so nu(r_k) = lens(sqrt(r_k^2 + ds^2)) / V_probe averaged over the
 * planes at the axial offsets ds. */
static void test_particle_on_axis(void **state)
{
    (void)state;
    double a = 1e-3, m = 2e-5, R = 4e-3;
    double v[3] = {0.1, 0.2, 0.3}, w[3] = {10, 0, 0};
    mimas_frame f;
    one_particle(&f, 0, 0, 0.01, a, m, v, w);
    mimas_radial_options o;
    memset(&o, 0, sizeof o);
    mimas_error err;
    assert_int_equal(mimas_tube_geom_resolve(&o.geom, NULL, R, NULL, &err), 0);
    o.probe = 0.5e-3;
    o.dr = 0.25e-3;
    o.check_inside = 1;
    mimas_radial *r;
    assert_int_equal(mimas_radial_create(&r, &o, &err), 0);
    /* radii 0 .. R - probe/2 */
    size_t nr = mimas_radial_nradii(r);
    assert_int_equal(nr, 16); /* 0, 0.25, ..., 3.75 mm */
    assert_close(mimas_radial_radius(r, nr - 1), R - o.probe / 2, 1e-15);
    assert_int_equal(mimas_radial_probes(r, 0), 1);
    assert_int_equal(mimas_radial_probes(r, 4), (size_t)ceil(2 * PI * 1e-3 / 0.5e-3));
    double planes[3] = {0.0097, 0.01, 0.0104};
    assert_int_equal(mimas_radial_sample(r, &f, planes, 3, &err), 0);
    double Vp = PI / 6 * pow(o.probe, 3);
    for (size_t k = 0; k < nr; k++) {
        double rk = mimas_radial_radius(r, k), want = 0;
        for (int q = 0; q < 3; q++)
            want += lens(hypot(rk, planes[q] - 0.01), a, o.probe / 2) / Vp / 3;
        assert_close(mimas_radial_last(r, k, MIMAS_RAD_NU), want, 1e-12);
        assert_close(mimas_radial_last(r, k, MIMAS_RAD_POROSITY), 1 - want, 1e-12);
        if (want > 0) {
            /* on the axis e_r is e_x: v_r = 0.1, v_phi = 0.2, v_s = 0.3; one
             * particle: no fluctuation; E_rot = (1/5) m a^2 w^2 */
            assert_close(mimas_radial_last(r, k, MIMAS_RAD_VR), 0.1, 1e-14);
            assert_close(mimas_radial_last(r, k, MIMAS_RAD_VPHI), 0.2, 1e-14);
            assert_close(mimas_radial_last(r, k, MIMAS_RAD_VS), 0.3, 1e-14);
            assert_close(mimas_radial_last(r, k, MIMAS_RAD_T), 0.0, 1e-20);
            assert_close(mimas_radial_last(r, k, MIMAS_RAD_EROT), 0.2 * m * a * a * 100, 1e-18);
        } else {
            assert_true(isnan(mimas_radial_last(r, k, MIMAS_RAD_VS)));
        }
    }
    /* r = 0: the probe (radius 0.25 mm) lies inside the particle on the
     * middle plane (nu = 1) */
    /* two samples of the same frame: mean equal, standard error 0 */
    assert_int_equal(mimas_radial_sample(r, &f, planes, 3, &err), 0);
    double mean, sem;
    size_t n;
    mimas_radial_result(r, 2, MIMAS_RAD_NU, &mean, &sem, &n);
    assert_int_equal(n, 2);
    assert_close(mean, mimas_radial_last(r, 2, MIMAS_RAD_NU), 1e-15);
    assert_close(sem, 0, 1e-15);
    assert_int_equal(mimas_radial_samples(r), 2);
    mimas_radial_free(r);
    mimas_frame_free(&f);
}

/* A particle off the axis at (r0, phi0): the probes of a circle see it at
 * different distances; nu(r_k) is the mean of the lens over the circle's
 * probes at angles 2 pi j / N_k. */
static void test_particle_off_axis(void **state)
{
    (void)state;
    double a = 1e-3, R = 5e-3, r0 = 2.2e-3, phi0 = 0.7;
    double v[3] = {0, 0, 0}, w[3] = {0, 0, 0};
    mimas_frame f;
    one_particle(&f, r0 * cos(phi0), r0 * sin(phi0), 0.02, a, 1e-5, v, w);
    mimas_radial_options o;
    memset(&o, 0, sizeof o);
    mimas_error err;
    assert_int_equal(mimas_tube_geom_resolve(&o.geom, NULL, R, NULL, &err), 0);
    o.probe = 0.6e-3;
    o.dr = 0.2e-3;
    mimas_radial *r;
    assert_int_equal(mimas_radial_create(&r, &o, &err), 0);
    double plane = 0.0203, Vp = PI / 6 * pow(o.probe, 3);
    assert_int_equal(mimas_radial_sample(r, &f, &plane, 1, &err), 0);
    for (size_t k = 0; k < mimas_radial_nradii(r); k++) {
        double rk = mimas_radial_radius(r, k);
        size_t np = mimas_radial_probes(r, k);
        double want = 0;
        for (size_t j = 0; j < np; j++) {
            double ang = 2 * PI * (double)j / (double)np;
            double dx = r0 * cos(phi0) - rk * cos(ang), dy = r0 * sin(phi0) - rk * sin(ang);
            want += lens(sqrt(dx * dx + dy * dy + 0.0003 * 0.0003), a, o.probe / 2) / Vp;
        }
        assert_close(mimas_radial_last(r, k, MIMAS_RAD_NU), want / (double)np, 1e-12);
    }
    mimas_radial_free(r);
    /* probe errors */
    o.probe = 2 * R;
    assert_int_equal(mimas_radial_create(&r, &o, &err), MIMAS_EUSAGE);
    o.probe = 1e-3;
    o.dr = 0;
    assert_int_equal(mimas_radial_create(&r, &o, &err), MIMAS_EUSAGE);
    mimas_frame_free(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_particle_on_axis),
        cmocka_unit_test(test_particle_off_axis),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
