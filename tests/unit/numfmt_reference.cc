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

// A second one, for the digits alone: the C++ library's std::to_chars (Ryu in libstdc++) in
// scientific form, "d.ddde+XX" taken apart into the digits "dddd" and the exponent.
#include <charconv>
#include <cstring>

extern "C" int reference_ryu_digits(double v, char *digits, int *exponent);

extern "C" int reference_ryu_digits(double v, char *digits, int *exponent)
{
    char sci[64];
    std::to_chars_result r = std::to_chars(sci, sci + sizeof sci, v, std::chars_format::scientific);
    *r.ptr = '\0';
    const char *p = sci[0] == '-' ? sci + 1 : sci;
    int n = 0;
    for (; *p && *p != 'e'; p++)
        if (*p != '.')
            digits[n++] = *p;
    digits[n] = '\0';
    *exponent = *p == 'e' ? static_cast<int>(std::strtol(p + 1, nullptr, 10)) : 0;
    return n;
}
