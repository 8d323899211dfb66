/* Shortest round-trip text for doubles: every value reads back (strtod) as the
 * same double, and no shorter printf("%.Ng") form does; the text is the same as
 * that of an independent implementation (double-conversion, numfmt_reference.cc),
 * which also picks the shortest form nearest to the value, and its digits and
 * exponent are those of a third (std::to_chars, Ryu). */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "numfmt.h"

size_t reference_shortest(double v, char *buf, int size);
int reference_ryu_digits(double v, char *digits, int *exponent);
static void same_as_reference(double v);

/* The significant digits (no leading or trailing zeros) and the decimal exponent of the
 * first of them in a number as mimas writes it ("-0.00125" is "125" and -3). */
static void text_digits(const char *s, char *digits, int *exponent)
{
    int n = 0, point = -1, lead = 0, e = 0;
    if (*s == '-')
        s++;
    for (; *s && *s != 'e'; s++) {
        if (*s == '.') {
            point = n + lead;
            continue;
        }
        if (n == 0 && *s == '0') {
            lead++;
            continue;
        }
        digits[n++] = *s;
    }
    if (*s == 'e')
        e = atoi(s + 1);
    int before = point < 0 ? n + lead : point; /* digits before the point */
    *exponent = e + before - lead - 1;
    while (n > 1 && digits[n - 1] == '0')
        n--;
    digits[n] = '\0';
}

/* the same digits and exponent as std::to_chars (Ryu), and the same text as double-conversion */
static void same_as_both(double v)
{
    char buf[MIMAS_NUMFMT_MAX], ours[64], ryu[64];
    int e_ours, e_ryu;
    size_t n = mimas_format_double(v, buf);
    assert_int_equal(n, strlen(buf));
    text_digits(buf, ours, &e_ours);
    reference_ryu_digits(v, ryu, &e_ryu);
    if (strcmp(ours, ryu) != 0 || e_ours != e_ryu)
        fail_msg("%.17g printed as '%s' (%s e%d), std::to_chars has %s e%d", v, buf, ours, e_ours,
                 ryu, e_ryu);
    same_as_reference(v);
}

/* the same text as the reference, and it reads back as v */
static void same_as_reference(double v)
{
    char buf[MIMAS_NUMFMT_MAX], ref[64];
    size_t n = mimas_format_double(v, buf);
    assert_int_equal(n, strlen(buf));
    reference_shortest(v, ref, sizeof ref);
    if (strcmp(buf, ref) != 0)
        fail_msg("%.17g printed as '%s', the reference prints '%s'", v, buf, ref);
    if (isfinite(v)) {
        double back = strtod(buf, NULL);
        if (memcmp(&back, &v, sizeof v) != 0)
            fail_msg("%.17g printed as '%s' reads back as %.17g", v, buf, back);
    }
}

/* significant digits of a decimal string (mantissa digits without leading zeros) */
static int digits(const char *s)
{
    int n = 0, started = 0;
    for (; *s && *s != 'e' && *s != 'E'; s++)
        if (*s >= '0' && *s <= '9') {
            started |= *s != '0';
            if (started)
                n++;
        }
    /* trailing zeros of an integer written as a decimal do not count */
    return n;
}

static void check(double v)
{
    char buf[MIMAS_NUMFMT_MAX];
    size_t n = mimas_format_double(v, buf);
    assert_int_equal(n, strlen(buf));
    double back = strtod(buf, NULL);
    if (memcmp(&back, &v, sizeof v) != 0)
        fail_msg("%.17g printed as '%s' reads back as %.17g", v, buf, back);
    /* the shortest %.Ng that reads back has as many significant digits */
    if (v != 0 && isfinite(v)) {
        int shortest = 17;
        for (int p = 1; p <= 17; p++) {
            char t[64];
            snprintf(t, sizeof t, "%.*e", p - 1, v);
            if (strtod(t, NULL) == v) {
                shortest = p;
                break;
            }
        }
        char mant[64];
        snprintf(mant, sizeof mant, "%s", buf);
        int got = digits(mant);
        /* integers like 1200 carry trailing zeros that are not significant */
        if (fabs(v) >= 1 && !strchr(buf, 'e') && !strchr(buf, '.')) {
            int z = 0;
            for (size_t k = strlen(buf); k > 0 && buf[k - 1] == '0'; k--)
                z++;
            got -= z;
        }
        if (got != shortest)
            fail_msg("%.17g printed as '%s' (%d digits), the shortest has %d", v, buf, got,
                     shortest);
    }
}

/* a double of random bits: every exponent, subnormals, infinities and NaNs */
static double random_bits(gsl_rng *rng)
{
    uint64_t bits = ((uint64_t)gsl_rng_get(rng) << 32) ^ (uint64_t)gsl_rng_get(rng);
    double v;
    memcpy(&v, &bits, sizeof v);
    return v;
}

static void test_special(void **state)
{
    (void)state;
    char buf[MIMAS_NUMFMT_MAX];
    mimas_format_double(NAN, buf);
    assert_string_equal(buf, "nan");
    mimas_format_double(INFINITY, buf);
    assert_string_equal(buf, "inf");
    mimas_format_double(-INFINITY, buf);
    assert_string_equal(buf, "-inf");
    mimas_format_double(0.0, buf);
    assert_string_equal(buf, "0");
    mimas_format_double(-0.0, buf);
    assert_string_equal(buf, "-0");
    mimas_format_double(0.1, buf);
    assert_string_equal(buf, "0.1");
    mimas_format_double(1e-5, buf);
    assert_true(strchr(buf, 'e') != NULL);
    const double edge[] = {5e-324, 2.2250738585072014e-308, 2.2250738585072009e-308,
                           1.7976931348623157e308, 1e23, 9007199254740993.0, 0.3, 2.0 / 3.0,
                           1e16, 1e17, 123456789012345680.0, 0.0001, 0.00012345, 1e-4 * 0.99};
    for (size_t k = 0; k < sizeof edge / sizeof edge[0]; k++) {
        check(edge[k]);
        check(-edge[k]);
        same_as_reference(edge[k]);
        same_as_reference(-edge[k]);
    }
    same_as_reference(NAN);
    same_as_reference(INFINITY);
    same_as_reference(-INFINITY);
    same_as_reference(-0.0);
    /* every power of two and of ten, and their neighbours (the uneven gaps) */
    for (int e = -1074; e <= 1023; e++)
        for (int d = -1; d <= 1; d++) {
            double x = nextafter(ldexp(1.0, e), d < 0 ? 0.0 : (d > 0 ? INFINITY : ldexp(1.0, e)));
            same_as_reference(x);
        }
    for (int e = -323; e <= 308; e++) {
        double x = pow(10.0, e);
        same_as_reference(x);
        same_as_reference(nextafter(x, 0.0));
        same_as_reference(nextafter(x, INFINITY));
    }
}

/* millions of random bit patterns and decimals of every length: the reference's text */
static void test_against_reference(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 2024);
    for (int k = 0; k < 2000000; k++)
        same_as_reference(random_bits(rng));
    char text[64];
    for (int k = 0; k < 500000; k++) {
        /* n significant digits: values whose shortest form has exactly those */
        int n = 1 + (int)gsl_rng_uniform_int(rng, 17);
        snprintf(text, sizeof text, "%.*e", n - 1,
                 gsl_rng_uniform_pos(rng) * pow(10.0, (double)gsl_rng_uniform_int(rng, 60) - 30));
        same_as_reference(strtod(text, NULL));
    }
    gsl_rng_free(rng);
}

/* random bit patterns (all exponents) and random values of field-like magnitude */
static void test_random(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    for (int k = 0; k < 200000; k++) {
        double v = random_bits(rng);
        if (isnan(v))
            continue;
        check(v);
        check((gsl_rng_uniform(rng) - 0.3) * pow(10.0, (int)(gsl_rng_uniform_int(rng, 30)) - 15));
    }
    gsl_rng_free(rng);
}

/* values like a field table's (every sign and decade, 1 to 17 digits), integers with
 * trailing zeros up to 10^17, random bit patterns: against both references */
static void test_against_ryu(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 14);
    for (int k = 0; k < 1500000; k++) {
        double v = random_bits(rng);
        if (!isnan(v))
            same_as_both(v);
        same_as_both((gsl_rng_uniform(rng) - 0.5) *
                     pow(10.0, (double)gsl_rng_uniform_int(rng, 40) - 20));
        double i = floor(gsl_rng_uniform(rng) * pow(10.0, (double)gsl_rng_uniform_int(rng, 18)));
        if (i > 0)
            same_as_both(i * pow(10.0, (double)gsl_rng_uniform_int(rng, 18 - (int)log10(i) + 1)));
    }
    /* the layout's edges: 1 to 17 digits at 1e-5 .. 1e-4 and 1e16 .. 1e17 */
    char text[64];
    for (int digits = 1; digits <= 17; digits++)
        for (int e = -6; e <= 18; e++)
            for (int k = 0; k < 200; k++) {
                snprintf(text, sizeof text, "%.*fe%d", digits - 1,
                         1 + 9 * gsl_rng_uniform(rng), e);
                same_as_both(strtod(text, NULL));
                same_as_both(-strtod(text, NULL));
            }
    gsl_rng_free(rng);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_special),
        cmocka_unit_test(test_random),
        cmocka_unit_test(test_against_reference),
        cmocka_unit_test(test_against_ryu),
    };
    return cmocka_run_group_tests_name("numfmt", tests, NULL, NULL);
}
