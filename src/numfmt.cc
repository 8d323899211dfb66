// The shortest round-trip form of a double (src/numfmt.h), by double-conversion.
#include <config.h>

#include "numfmt.h"

#include <cmath>

#include <double-conversion/double-to-string.h>

using double_conversion::DoubleToStringConverter;
using double_conversion::StringBuilder;

static const DoubleToStringConverter converter(
    DoubleToStringConverter::EMIT_POSITIVE_EXPONENT_SIGN, "inf", "nan", 'e',
    -4,  // decimal_in_shortest_low: 0.0001 is written as a decimal, 0.00001 as 1e-05
    17,  // decimal_in_shortest_high: 1e17 and beyond in exponent form
    0, 0);

extern "C" size_t mimas_format_double(double v, char *buf)
{
    if (v == 0 && !std::signbit(v)) { // empty cells: many zeros
        buf[0] = '0';
        buf[1] = '\0';
        return 1;
    }
    StringBuilder b(buf, MIMAS_NUMFMT_MAX);
    converter.ToShortest(v, &b);
    size_t n = static_cast<size_t>(b.position());
    b.Finalize();
    return n;
}
