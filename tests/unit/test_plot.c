/* The text of the pictures (src/plot.h): field names into gnuplot's
 * enhanced-text symbols, and literal text with the characters enhanced text
 * would interpret escaped. */
#include <config.h>

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "field_table.h"
#include "plot.h"

static void test_symbols(void **state)
{
    (void)state;
    static const char *const cases[][2] = {
        {"nu", "ν"},
        {"rho", "ρ"},
        {"v_x", "v_{x}"},
        {"v_phi", "v_{φ}"},
        {"omega", "ω"},
        {"stress_rz", "σ_{rz}"},
        {"stress_rphi", "σ_{rφ}"},
        {"kstress_phiphi", "σ^{k}_{φφ}"},
        {"cstress_xy", "σ^{c}_{xy}"},
        {"tau", "τ"},
        {"tau_phi", "τ_{φ}"},
        {"mu", "μ"},
        {"Z_nr", "Z_{nr}"},
        {"fabric_zz", "F_{zz}"},
        {"wall_force_phi", "f^{w}_{φ}"},
        {"shear_rate", "γ̇"},
        {"shear_rate_luding", "γ̇_{L}"},
        {"eta", "η"},
        {"I", "I"},
        {"voronoi_nu", "voronoi\\_nu"},
        {"a^b{c}", "a\\^b\\{c\\}"},
    };
    char buf[64];
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        mimas_plot_symbol(cases[k][0], buf, sizeof buf);
        assert_string_equal(buf, cases[k][1]);
    }
    /* every field of the table has a symbol without raw enhanced-text specials */
    for (size_t k = 0; k < mimas_fields_count(); k++)
        for (int cyl = 0; cyl < 2; cyl++) {
            const char *name = mimas_field_name(k, cyl);
            if (!name)
                continue;
            mimas_plot_symbol(name, buf, sizeof buf);
            assert_true(buf[0] != '\0');
            assert_null(strchr(buf, '@'));
        }
    /* a short buffer is cut, never overrun */
    char small[4] = "xyz";
    mimas_plot_literal("a_b_c_d", small, sizeof small);
    assert_string_equal(small, "a");     /* "\\_" does not fit after it */
    mimas_plot_symbol("stress_rphi", small, sizeof small);
    assert_true(strlen(small) < sizeof small);
}

/* Fitted values in a key: the value to the decimal place of the error's
 * second significant digit (the expected strings written out by hand). */
static void test_value_error(void **state)
{
    (void)state;
    static const struct {
        double v, e;
        const char *want;
    } cases[] = {
        {0.17, 0.026, "0.170 ± 0.026"},          /* the trailing zero is kept */
        {0.387, 0.034, "0.387 ± 0.034"},
        {-6.7, 3.1, "-6.7 ± 3.1"},
        {41.1, 6.1, "41.1 ± 6.1"},
        {0.0029, 0.0018, "0.0029 ± 0.0018"},
        {0.5, 0.0996, "0.50 ± 0.10"},            /* 0.0996 rounds to two digits: 0.10 */
        {410.3, 61, "410 ± 61"},
        {-7.3, 12, "-7 ± 12"},
        {4123, 612, "4120 ± 610"},
        {-0.004, 0.31, "0.00 ± 0.31"},           /* no "-0.00" */
        {1.234e-7, 4.5e-8, "(1.23 ± 0.45)×10^{-7}"},
        {2.5e6, 1.2e5, "(2.50 ± 0.12)×10^{6}"},
        {1.5, 0, "1.5"},                         /* no error: the value alone */
        {1.5, NAN, "1.5"},
        {41, 1e-12, "41"},                       /* an error below 1e-9 of the value */
    };
    char buf[64];
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        mimas_plot_value_error(cases[k].v, cases[k].e, buf, sizeof buf);
        assert_string_equal(buf, cases[k].want);
    }
    char small[6];
    mimas_plot_value_error(0.17, 0.026, small, sizeof small);
    assert_true(strlen(small) < sizeof small);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_symbols),
        cmocka_unit_test(test_value_error),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
