/* The text of the pictures (src/plot.h): field names into gnuplot's
 * enhanced-text symbols, and literal text with the characters enhanced text
 * would interpret escaped. */
#include <config.h>

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_symbols),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
