/* The FFT correlations (averaging/msd.h) against the direct O(T^2) sums
 * computed here, to 1e-10 relative: T a power of two and not, lags up to
 * T-1 and fewer, particles that start late, end early, have gaps, appear
 * once or never; split into several flushes the sums add up the same, and
 * sums over a window of lags hold the same numbers. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assert_close.h"
#include "msd.h"

#define NC 3
#define STRIDE 4 /* records carry a fourth value the correlations ignore */

/* Random walks of n particles over T frames (records of STRIDE values),
 * offset far from the origin, with every kind of absence. */
static double *walks(size_t n, size_t T, unsigned long seed)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, seed);
    double *x = malloc(n * T * STRIDE * sizeof *x);
    for (size_t j = 0; j < n; j++) {
        double p[NC] = {3.0 + j, -2.0, 0.5 * j};
        for (size_t t = 0; t < T; t++) {
            double *r = x + (j * T + t) * STRIDE;
            for (int c = 0; c < NC; c++) {
                p[c] += gsl_ran_gaussian(rng, 0.01 * (c + 1)) + 1e-3 * c;
                r[c] = p[c];
            }
            r[3] = 99;
            int absent = 0;
            switch (j % 6) {
            case 1: absent = t < T / 3; break;                 /* inserted late */
            case 2: absent = t > T / 2; break;                 /* removed early */
            case 3: absent = gsl_rng_uniform(rng) < 0.3; break; /* gaps */
            case 4: absent = t != T / 2; break;                /* seen once */
            case 5: absent = j == 5; break;                    /* never (one particle) */
            }
            if (absent)
                for (int c = 0; c < STRIDE; c++)
                    r[c] = NAN;
        }
    }
    gsl_rng_free(rng);
    return x;
}

/* The direct sums over every pair of frames. */
static void direct(const double *x, size_t n, size_t T, size_t K, int disp, double *num,
                   double *count)
{
    memset(num, 0, NC * (K + 1) * sizeof *num);
    memset(count, 0, (K + 1) * sizeof *count);
    for (size_t j = 0; j < n; j++)
        for (size_t k = 0; k <= K; k++)
            for (size_t t = 0; t + k < T; t++) {
                const double *a = x + (j * T + t) * STRIDE, *b = a + k * STRIDE;
                if (isnan(a[0]) || isnan(b[0]))
                    continue;
                count[k] += 1;
                for (int c = 0; c < NC; c++)
                    num[c * (K + 1) + k] += disp ? (b[c] - a[c]) * (b[c] - a[c]) : a[c] * b[c];
            }
}

static void compare(size_t n, size_t T, size_t K, mimas_msd_kind kind, size_t pieces)
{
    double *x = walks(n, T, 7 + T);
    double *num = malloc(NC * (K + 1) * sizeof *num), *count = malloc((K + 1) * sizeof *count);
    int disp = kind == MIMAS_MSD_DISPLACEMENT;
    direct(x, n, T, K, disp, num, count);
    mimas_msd *m;
    mimas_error err;
    assert_int_equal(mimas_msd_create(&m, kind, T, K, NC, &err), MIMAS_OK);
    mimas_msd_sums s, window;
    /* a window of lags: sums over lags 2 .. K/2 beside those of every lag */
    size_t w0 = 2, wn = K / 2 > 2 ? K / 2 - 1 : 0;
    assert_int_equal(mimas_msd_sums_init(&s, NC, 0, K + 1, &err), MIMAS_OK);
    assert_int_equal(mimas_msd_sums_init(&window, NC, w0, wn, &err), MIMAS_OK);
    /* pieces flushes of unequal parts: the sums add */
    size_t done = 0;
    for (size_t p = 0; p < pieces; p++) {
        size_t take = p + 1 == pieces ? n - done : (n - done) / 3;
        assert_int_equal(mimas_msd_add(m, x + done * T * STRIDE, take, STRIDE, &err), MIMAS_OK);
        mimas_msd_sums part[2];
        part[0] = window;
        assert_int_equal(mimas_msd_sums_init(&part[1], NC, 0, K + 1, &err), MIMAS_OK);
        assert_int_equal(mimas_msd_flush(m, part, 2, &err), MIMAS_OK);
        window = part[0];
        mimas_msd_sums_add(&s, &part[1]);
        mimas_msd_sums_free(&part[1]);
        done += take;
    }
    for (size_t k = w0; k < w0 + wn; k++) {
        assert_true(window.count[k - w0] == s.count[k]);
        for (int c = 0; c < NC; c++)
            assert_true(window.num[c * wn + k - w0] == s.num[c * (K + 1) + k]);
    }
    mimas_msd_sums_free(&window);
    for (size_t k = 0; k <= K; k++) {
        assert_true(s.count[k] == count[k]);
        for (int c = 0; c < NC; c++) {
            double want = num[c * (K + 1) + k], got = s.num[c * (K + 1) + k];
            if (disp && k == 0)
                assert_true(got == 0);
            else
                assert_close(got, want, 1e-10 * fabs(want));
        }
    }
    mimas_msd_sums_free(&s);
    mimas_msd_free(m);
    free(num);
    free(count);
    free(x);
}

static void test_displacement_power_of_two(void **state)
{
    (void)state;
    compare(40, 256, 255, MIMAS_MSD_DISPLACEMENT, 1);
    compare(40, 256, 31, MIMAS_MSD_DISPLACEMENT, 3);
}

static void test_displacement_other_lengths(void **state)
{
    (void)state;
    compare(37, 300, 299, MIMAS_MSD_DISPLACEMENT, 2);
    compare(23, 127, 100, MIMAS_MSD_DISPLACEMENT, 1);
    compare(3, 2, 1, MIMAS_MSD_DISPLACEMENT, 1);
}

static void test_autocorrelation(void **state)
{
    (void)state;
    compare(40, 256, 255, MIMAS_MSD_AUTOCORRELATION, 2);
    compare(37, 300, 120, MIMAS_MSD_AUTOCORRELATION, 1);
}

static void test_fft_length(void **state)
{
    (void)state;
    /* the smallest even 7-smooth number of at least frames + max_lag */
    assert_int_equal(mimas_msd_fft_length(1024, 1023), 2048);
    assert_int_equal(mimas_msd_fft_length(1000, 999), 2000);
    assert_int_equal(mimas_msd_fft_length(300, 299), 600);
    assert_int_equal(mimas_msd_fft_length(127, 100), 240);
    assert_int_equal(mimas_msd_fft_length(1, 0), 2);
    mimas_msd *m;
    mimas_error err;
    assert_int_equal(mimas_msd_create(&m, MIMAS_MSD_DISPLACEMENT, 10, 10, 3, &err),
                     MIMAS_EUSAGE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_displacement_power_of_two),
        cmocka_unit_test(test_displacement_other_lengths),
        cmocka_unit_test(test_autocorrelation),
        cmocka_unit_test(test_fft_length),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
