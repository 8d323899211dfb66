// Numbers to and from text (src/numfmt.h): the C++ standard library's exact
// conversions, std::to_chars (the shortest round trip; libstdc++ implements it with
// Ryu, Adams 2018) and std::from_chars (correctly rounded; libstdc++ uses the
// Eisel-Lemire algorithm of fast_float, Lemire 2021), laid out as mimas writes and
// reads numbers.
#include <config.h>

#include "numfmt.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <system_error>

// The shortest digits d1 d2 ... dn and the decimal exponent E of v = d1.d2...dn x 10^E
// come from to_chars' scientific form ("-1.2345e-05"); they are laid out as a plain
// decimal for -4 <= E < 17 (as %g would: 0.0001, 123456.5, 12000) and as d.ddde+X /
// d.ddde-X otherwise (1e-05 is "1e-5", 1e17 is "1e+17").
extern "C" size_t mimas_format_double(double v, char *buf)
{
    if (v == 0 && !std::signbit(v)) { // empty cells: many zeros
        buf[0] = '0';
        buf[1] = '\0';
        return 1;
    }
    if (!std::isfinite(v)) {
        const char *s = std::isnan(v) ? "nan" : (v < 0 ? "-inf" : "inf");
        size_t n = std::strlen(s);
        std::memcpy(buf, s, n + 1);
        return n;
    }
    char sci[MIMAS_NUMFMT_MAX];
    std::to_chars_result r = std::to_chars(sci, sci + sizeof sci, v, std::chars_format::scientific);
    const char *p = sci, *end = r.ptr;
    char *o = buf;
    if (*p == '-')
        *o++ = *p++;
    // "d.ddde+XX": the exponent (a sign and 2 or 3 digits) ends the text; the digits are
    // p[0] and, when there is a '.', p[2] .. the 'e'
    const char *ep = end[-4] == 'e' ? end - 4 : end - 5;
    int e = ep[2] - '0';
    for (const char *q = ep + 3; q < end; q++)
        e = 10 * e + (*q - '0');
    if (ep[1] == '-')
        e = -e;
    const char *frac = p + 2; // the digits after the first
    int nf = ep - p > 1 ? (int)(ep - frac) : 0, nd = nf + 1;
    if (e >= -4 && e < 17) {
        int point = e + 1; // digits before the decimal point
        if (point <= 0) {
            std::memcpy(o, "0.0000", (size_t)(2 - point));
            o += 2 - point;
            *o++ = p[0];
            std::memcpy(o, frac, (size_t)nf);
            o += nf;
        } else if (point >= nd) {
            *o++ = p[0];
            std::memcpy(o, frac, (size_t)nf);
            o += nf;
            for (int k = nd; k < point; k++)
                *o++ = '0';
        } else {
            *o++ = p[0];
            std::memcpy(o, frac, (size_t)(point - 1));
            o += point - 1;
            *o++ = '.';
            std::memcpy(o, frac + point - 1, (size_t)(nd - point));
            o += nd - point;
        }
    } else {
        *o++ = p[0];
        if (nf > 0) {
            *o++ = '.';
            std::memcpy(o, frac, (size_t)nf);
            o += nf;
        }
        *o++ = 'e';
        *o++ = e < 0 ? '-' : '+';
        int a = e < 0 ? -e : e;
        if (a >= 100)
            *o++ = (char)('0' + a / 100);
        if (a >= 10)
            *o++ = (char)('0' + a / 10 % 10);
        *o++ = (char)('0' + a % 10);
    }
    *o = '\0';
    return (size_t)(o - buf);
}

extern "C" int mimas_scan_double(const char *begin, const char *end, double *v)
{
    double x;
    std::from_chars_result r = std::from_chars(begin, end, x, std::chars_format::general);
    if (r.ec != std::errc() || r.ptr == begin)
        return -1;
    *v = x;
    return (int)(r.ptr - begin);
}
