// An independent shortest round-trip conversion for test_numfmt: Google's
// double-conversion (Grisu3 with an exact bignum fallback), laid out as mimas
// writes numbers (plain decimals for exponents -4 to 16, else d.ddde+X).
#include <config.h>

#include <double-conversion/double-to-string.h>

using double_conversion::DoubleToStringConverter;
using double_conversion::StringBuilder;

extern "C" size_t reference_shortest(double v, char *buf, int size);

extern "C" size_t reference_shortest(double v, char *buf, int size)
{
    static const DoubleToStringConverter converter(
        DoubleToStringConverter::EMIT_POSITIVE_EXPONENT_SIGN, "inf", "nan", 'e', -4, 17, 0, 0);
    StringBuilder b(buf, size);
    converter.ToShortest(v, &b);
    size_t n = static_cast<size_t>(b.position());
    b.Finalize();
    return n;
}
