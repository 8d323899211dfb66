/* The fast path is Clinger's: a decimal with at most 19 significant digits
 * whose integer mantissa m is below 2^53 and whose decimal exponent e has
 * |e| <= 22 is exactly m * 10^e or m / 10^-e, both exactly representable
 * operands, so one IEEE operation rounds correctly.  LAMMPS' default "%g"
 * output (6 digits) always takes it; the rest (17-digit numbers) goes to the
 * standard library's correctly rounded from_chars (mimas_scan_double), and what
 * that does not read (hexadecimal, '+', out of range) to strtod. */
#include <config.h>

#include "numparse.h"

#include "numfmt.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double pow10_exact[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                       1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                       1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* Any white space separates tokens (a stray carriage return too). */
static inline int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

static inline int is_end(char c)
{
    return c == '\0' || is_blank(c);
}

int skip_token(char **pp)
{
    char *p = *pp;
    while (is_blank(*p))
        p++;
    if (*p == '\0')
        return -1;
    while (!is_end(*p))
        p++;
    *pp = p;
    return 0;
}

/* 8 ASCII digits at p as their value, when all 8 are digits (SWAR: the check and the
 * multiply-add tree of Lemire, "Number parsing at a gigabyte per second", 2021); 0 when
 * they are not, or when words are not little-endian. */
static inline int eight_digits(const char *p, uint32_t *out)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    uint64_t v;
    memcpy(&v, p, 8);
    if (((v & 0xF0F0F0F0F0F0F0F0u) | (((v + 0x0606060606060606u) & 0xF0F0F0F0F0F0F0F0u) >> 4)) !=
        0x3333333333333333u)
        return 0;
    v -= 0x3030303030303030u;
    v = v * 10 + (v >> 8); /* pairs */
    v = (((v & 0x000000FF000000FFu) * (100 + (1000000ull << 32))) +
         (((v >> 16) & 0x000000FF000000FFu) * (1 + (10000ull << 32)))) >> 32;
    *out = (uint32_t)v;
    return 1;
#else
    (void)p, (void)out;
    return 0;
#endif
}

/* The digits at *pp into m (while digits < 19; past that *dropped counts them), eight at
 * a time where the line's padding allows reading ahead; *any set when there was one. */
static inline char *digit_run(char *p, int padded, uint64_t *m, int *digits, int *dropped,
                              int *any)
{
    uint32_t eight;
    int digit = (unsigned)(*p - '0') < 10u;
    while (padded && digit && *digits <= 11 && eight_digits(p, &eight)) {
        *m = *m * 100000000u + eight;
        *digits += 8;
        p += 8;
        *any = 1;
    }
    while ((unsigned)(*p - '0') < 10u) {
        if (*digits < 19)
            *m = 10 * *m + (uint64_t)(*p - '0');
        else
            (*dropped)++;
        (*digits)++;
        p++;
        *any = 1;
    }
    return p;
}

static inline int parse_double_at(char **pp, double *v, int padded)
{
    char *p = *pp;
    while (is_blank(*p))
        p++;
    if (*p == '\0')
        return -1;
    char *start = p;
    int neg = 0;
    if (*p == '-' || *p == '+')
        neg = *p++ == '-';
    uint64_t m = 0;
    int digits = 0, frac = 0, any = 0;
    while (*p == '0') { /* leading zeros are not significant */
        p++;
        any = 1;
    }
    int dropped = 0; /* dropped digits: only the slow path is exact */
    p = digit_run(p, padded, &m, &digits, &dropped, &any);
    frac -= dropped;
    if (*p == '.') {
        p++;
        if (digits == 0)
            while (*p == '0') {
                p++;
                frac++;
                any = 1;
            }
        int before = digits;
        dropped = 0;
        p = digit_run(p, padded, &m, &digits, &dropped, &any);
        frac += digits - before - dropped; /* the fraction's digits kept in m */
    }
    int e = 0;
    if (any && (*p == 'e' || *p == 'E')) {
        char *q = p + 1;
        int eneg = 0;
        if (*q == '-' || *q == '+')
            eneg = *q++ == '-';
        if ((unsigned)(*q - '0') < 10u) {
            while ((unsigned)(*q - '0') < 10u) {
                if (e < 100000)
                    e = 10 * e + (*q - '0');
                q++;
            }
            if (eneg)
                e = -e;
            p = q;
        }
    }
    if (any && is_end(*p) && digits <= 19) {
        int e10 = e - frac;
        if (m < (1ull << 53) && e10 >= -22 && e10 <= 22) {
            double x = (double)m;
            x = e10 < 0 ? x / pow10_exact[-e10] : x * pow10_exact[e10];
            *v = neg ? -x : x;
            *pp = p;
            return 0;
        }
    }
    /* the token in full by from_chars */
    char *tend = p;
    while (!is_end(*tend))
        tend++;
    const char *digits_at = start + (*start == '+');
    double x;
    if (*digits_at != '+' && !(digits_at > start && *digits_at == '-') &&
        mimas_scan_double(digits_at, tend, &x) == (int)(tend - digits_at) && isfinite(x)) {
        *v = x;
        *pp = tend;
        return 0;
    }
    /* slow path: strtod on the token (the line is NUL-terminated) */
    char *end;
    errno = 0;
    x = strtod(start, &end);
    if (end == start || !is_end(*end) || !isfinite(x))
        return -2;
    *v = x;
    *pp = end;
    return 0;
}

int parse_double(char **pp, double *v)
{
    return parse_double_at(pp, v, 0);
}

int parse_double_in_line(char **pp, double *v)
{
    return parse_double_at(pp, v, 1);
}

int parse_int64(char **pp, int64_t *v)
{
    char *p = *pp;
    while (is_blank(*p))
        p++;
    if (*p == '\0')
        return -1;
    char *end;
    errno = 0;
    long long x = strtoll(p, &end, 10);
    if (end == p || !is_end(*end) || errno == ERANGE)
        return -2;
    *v = (int64_t)x;
    *pp = end;
    return 0;
}
