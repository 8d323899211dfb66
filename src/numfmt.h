/* Exact and fast text for doubles: the shortest decimal form that reads back
 * (strtod, awk, gnuplot, Python) as the same double, from Google's
 * double-conversion library (Debian libdouble-conversion; Grisu3 with an exact
 * bignum fallback).  About 3x faster than printf("%.17g"), which prints
 * 17 digits through multi-precision arithmetic, and never longer. */
#ifndef MIMAS_NUMFMT_H
#define MIMAS_NUMFMT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Room a formatted double needs, with its terminating NUL. */
#define MIMAS_NUMFMT_MAX 32

/* Writes v into buf (MIMAS_NUMFMT_MAX bytes) and returns its length: "nan", "inf",
 * "-inf", plain decimals for 1e-4 <= |v| < 1e17 (as %g would), otherwise d.ddde+XX /
 * d.ddde-XX; "-0" for negative zero. */
size_t mimas_format_double(double v, char *buf);

#ifdef __cplusplus
}
#endif
#endif
