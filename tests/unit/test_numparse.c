/* The fast number parser agrees with strtod to the last bit. */
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

#include "numparse.h"
#include "text_input.h"

/* parse_double_in_line on a line in a buffer of exactly the padding text_line
 * guarantees (so that AddressSanitizer sees any read beyond it) gives what
 * parse_double gives: the code, the value's bits and the end of the token. */
static int in_line_agrees(const char *text, double *v)
{
    size_t n = strlen(text);
    char *line = malloc(n + 1 + TEXT_LINE_PAD), buf[256];
    assert_non_null(line);
    memcpy(line, text, n + 1);
    memset(line + n + 1, '7', TEXT_LINE_PAD); /* digits after the end: must not be read as the token's */
    snprintf(buf, sizeof buf, "%s", text);
    char *p = buf, *q = line;
    double w = -1.0;
    *v = -2.0;
    int rc = parse_double(&p, v), rq = parse_double_in_line(&q, &w);
    if (rc != rq || (rc == 0 && (memcmp(v, &w, sizeof w) != 0 || p - buf != q - line)))
        fail_msg("'%s': parse_double %d %.17g, in a line %d %.17g", text, rc, *v, rq, w);
    free(line);
    return rc;
}

static void same_as_strtod(const char *text)
{
    double v;
    if (in_line_agrees(text, &v) != 0)
        fail_msg("'%s' is not read", text);
    double ref = strtod(text, NULL);
    if (memcmp(&v, &ref, sizeof v) != 0)
        fail_msg("'%s': %.17g, strtod %.17g", text, v, ref);
}

/* Runs of digits about the eight read at a time and the 19 kept: 1 to 30 digits before
 * and after the point, with leading zeros, an exponent, or a byte that ends the run
 * early (letters and bytes from 0xFA, whose +6 carries into the next byte). */
static void test_digit_runs(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 11);
    char text[96];
    const char *tails[5] = {"", "e-7", "E+12", "x", "\xfa" "1"};
    for (int k = 0; k < 100000; k++) {
        int a = (int)gsl_rng_uniform_int(rng, 31), b = (int)gsl_rng_uniform_int(rng, 31);
        int z = (int)gsl_rng_uniform_int(rng, 4), t = (int)gsl_rng_uniform_int(rng, 5), n = 0;
        if (gsl_rng_uniform(rng) < 0.3)
            text[n++] = '-';
        for (int i = 0; i < z; i++)
            text[n++] = '0';
        for (int i = 0; i < a; i++)
            text[n++] = (char)('0' + gsl_rng_uniform_int(rng, 10));
        if (b || !a) {
            text[n++] = '.';
            for (int i = 0; i < z && a == 0; i++)
                text[n++] = '0';
            for (int i = 0; i < b; i++)
                text[n++] = (char)('0' + gsl_rng_uniform_int(rng, 10));
        }
        snprintf(text + n, sizeof text - (size_t)n, "%s", tails[t]);
        double v;
        int rc = in_line_agrees(text, &v);
        if (t < 3 && (a || b || z)) {
            double ref = strtod(text, NULL);
            if (rc != 0 || memcmp(&v, &ref, sizeof v) != 0)
                fail_msg("'%s': %d %.17g, strtod %.17g", text, rc, v, ref);
        } else if (t >= 3) {
            assert_int_equal(rc, -2);
        }
    }
    gsl_rng_free(rng);
}

static void test_fixed_cases(void **state)
{
    (void)state;
    const char *cases[] = {"0", "-0", "1", "-1", "0.5", ".5", "5.", "1e5", "1E-5", "-2.5e+3",
                           "0.000123", "123456789012345678", "9007199254740993",
                           "0.1", "0.3", "1e22", "1e23", "4.9406564584124654e-324",
                           "2.2250738585072014e-308", "1.7976931348623157e308",
                           "0.0293135", "-0.00153673", "8.37758e-05", "3.14159265358979323846",
                           "00012.50", "1234567890123456789e-10"};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++)
        same_as_strtod(cases[k]);
}

/* Numbers printed the way LAMMPS does (%g), and with 17 digits. */
static void test_random_numbers(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    char text[64];
    for (int k = 0; k < 200000; k++) {
        double x = (gsl_rng_uniform(rng) - 0.5) * pow(10.0, (double)gsl_rng_uniform_int(rng, 40) - 20.0);
        const char *fmt[4] = {"%g", "%.17g", "%.9e", "%.12f"};
        snprintf(text, sizeof text, fmt[k % 4], x);
        same_as_strtod(text);
    }
    gsl_rng_free(rng);
}

/* The numbers the fast path leaves to from_chars: 17 to 25 significant digits,
 * numbers a hair off the midpoint of two neighbouring doubles (rounding's hard
 * cases, from the exact long double midpoint), signs, subnormals and the edges of
 * the range (which strtod takes). */
static void test_long_and_halfway(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 7);
    char text[128];
    for (int k = 0; k < 300000; k++) {
        uint64_t bits = ((uint64_t)gsl_rng_get(rng) << 32) ^ (uint64_t)gsl_rng_get(rng);
        double x;
        memcpy(&x, &bits, sizeof x);
        if (!isfinite(x))
            continue;
        int n = 17 + (int)gsl_rng_uniform_int(rng, 9);
        snprintf(text, sizeof text, "%.*e", n - 1, x);
        same_as_strtod(text);
        long double mid = 0.5L * ((long double)x + (long double)nextafter(x, INFINITY));
        if (isfinite((double)mid)) {
            snprintf(text, sizeof text, "%.*Le", 17 + (int)gsl_rng_uniform_int(rng, 6), mid);
            same_as_strtod(text);
        }
        snprintf(text, sizeof text, "%+.17g", x);
        same_as_strtod(text);
    }
    const char *cases[] = {"2.4703282292062327e-324", "2.4703282292062328e-324", "1e-400",
                           "4.9406564584124654e-324", "1.7976931348623158e308",
                           "0.30000000000000000555111512312578270211815834045410156250001",
                           "+0.1", "-0.0e0", "9007199254740992.9999999999"};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++)
        same_as_strtod(cases[k]);
    gsl_rng_free(rng);
}

static void test_tokens_and_errors(void **state)
{
    (void)state;
    char line[] = "  12\t-3.5e2 abc 7 1.5x nan inf 1e999";
    char *p = line;
    double v;
    int64_t i;
    assert_int_equal(parse_int64(&p, &i), 0);
    assert_int_equal(i, 12);
    assert_int_equal(parse_double(&p, &v), 0);
    assert_true(v == -350.0);
    assert_int_equal(parse_double(&p, &v), -2); /* abc */
    assert_int_equal(skip_token(&p), 0);
    assert_int_equal(parse_double(&p, &v), 0);
    assert_true(v == 7.0);
    assert_int_equal(parse_double(&p, &v), -2); /* 1.5x */
    skip_token(&p);
    assert_int_equal(parse_double(&p, &v), -2); /* nan */
    skip_token(&p);
    assert_int_equal(parse_double(&p, &v), -2); /* inf */
    skip_token(&p);
    assert_int_equal(parse_double(&p, &v), -2); /* overflow */
    skip_token(&p);
    assert_int_equal(parse_double(&p, &v), -1); /* end of line */
    char signs[] = "+-1.25 -+3 0x1p3 1.7976931348623159e308";
    p = signs;
    assert_int_equal(parse_double(&p, &v), -2);
    skip_token(&p);
    assert_int_equal(parse_double(&p, &v), -2);
    skip_token(&p);
    assert_int_equal(parse_double(&p, &v), 0); /* strtod reads hexadecimal */
    assert_true(v == 8.0);
    assert_int_equal(parse_double(&p, &v), -2); /* rounds to infinity */
    char ints[] = "12.0 99999999999999999999";
    p = ints;
    assert_int_equal(parse_int64(&p, &i), -2);
    skip_token(&p);
    assert_int_equal(parse_int64(&p, &i), -2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fixed_cases),
        cmocka_unit_test(test_random_numbers),
        cmocka_unit_test(test_digit_runs),
        cmocka_unit_test(test_long_and_halfway),
        cmocka_unit_test(test_tokens_and_errors),
    };
    return cmocka_run_group_tests_name("numparse", tests, NULL, NULL);
}
