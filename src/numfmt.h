/* Exact and fast text for doubles: the shortest decimal form that reads back
 * (strtod, awk, gnuplot, Python) as the same double, from the Dragonbox
 * algorithm (the fmt library's, src/numfmt.cc), about 15x faster than
 * printf("%.17g"), which prints 17 digits through multi-precision arithmetic,
 * and never longer; and the correctly rounded reading of a decimal by
 * std::from_chars (Eisel-Lemire in libstdc++), several times faster than strtod. */
#ifndef MIMAS_NUMFMT_H
#define MIMAS_NUMFMT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Room a formatted double needs: the text is at most 24 characters and its
 * terminating NUL, the conversion uses the rest as scratch space. */
#define MIMAS_NUMFMT_MAX 48

/* Writes v into buf (MIMAS_NUMFMT_MAX bytes) and returns its length: "nan", "inf",
 * "-inf", plain decimals for 1e-4 <= |v| < 1e17 (as %g would), otherwise d.ddde+X /
 * d.ddde-X (1e-05 is "1e-5"); "-0" for negative zero. */
size_t mimas_format_double(double v, char *buf);
/* Reads the longest decimal number (optional '-', digits with an optional '.',
 * an optional exponent; also inf, nan) at [begin, end), correctly rounded as
 * strtod would; returns the number of characters read, or -1 if there is no
 * number there or it is out of the range of doubles (strtod's ERANGE cases:
 * leave those to strtod).  No leading blanks or '+', no hexadecimal. */
int mimas_scan_double(const char *begin, const char *end, double *v);

#ifdef __cplusplus
}
#endif
#endif
