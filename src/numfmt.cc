// Numbers to and from text (src/numfmt.h).  Doubles to text: the shortest decimal
// significand and its exponent from the Dragonbox algorithm (Jeon 2020, "Dragonbox: a new
// floating-point binary-to-decimal conversion algorithm"), in the implementation of the
// fmt library (used header-only, with its full 10 kB table of powers of ten rather than
// the compressed one it would expand on every call), its digits written eight at a time
// with integer arithmetic, laid out as mimas writes numbers.  Text to doubles:
// std::from_chars (correctly rounded; libstdc++ uses the Eisel-Lemire algorithm of
// fast_float, Lemire 2021).
#include <config.h>

#include "numfmt.h"

// fmt header-only and hidden: its functions are compiled here and not exported from
// libmimas, where they could stand in for those of a program's own libfmt (the standard
// headers it uses come first, with their usual visibility)
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstddef>
#include <cstdio>
#include <cwchar>
#include <exception>
#include <iterator>
#include <limits>
#include <locale>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#define FMT_HEADER_ONLY
#define FMT_USE_FULL_CACHE_DRAGONBOX 1
#pragma GCC visibility push(hidden)
#include <fmt/format.h>
#pragma GCC visibility pop

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include <charconv>
#include <cstdint>
#include <cstring>
#include <system_error>

namespace {

// Without SSE2: the eight decimal digits of x < 10^8, most significant first, as ASCII into
// o[0..7]: x = 10^4 hi + lo is split into four pairs of digits (hi/100, hi%100, lo/100, lo%100)
// held in the 16-bit lanes of one 64-bit word, each pair into its tens and units byte
// (the divisions by 100 and 10 as multiplications that are exact in the ranges used:
// 10486/2^20 for x < 10^4, 103/2^10 for x < 100); the lanes are in memory order on a
// little-endian machine, and on a big-endian one the bytes are swapped before the store.
#ifndef __SSE2__
inline void eight_digits(uint32_t x, char *o)
{
    uint64_t hi = x / 10000, lo = x % 10000;
    uint64_t merged = hi | (lo << 32);
    uint64_t hundreds = ((merged * 10486) >> 20) & ((0x7FULL << 32) | 0x7F);
    uint64_t pairs = ((merged - 100 * hundreds) << 16) | hundreds;
    uint64_t tens = ((pairs * 103) >> 10) & 0x000F000F000F000FULL;
    uint64_t w = (tens | ((pairs - 10 * tens) << 8)) | 0x3030303030303030ULL;
#if defined(WORDS_BIGENDIAN)
    w = __builtin_bswap64(w);
#endif
    std::memcpy(o, &w, 8);
}
#endif

constexpr uint64_t pow10_table[18] = {1ULL,
                                      10ULL,
                                      100ULL,
                                      1000ULL,
                                      10000ULL,
                                      100000ULL,
                                      1000000ULL,
                                      10000000ULL,
                                      100000000ULL,
                                      1000000000ULL,
                                      10000000000ULL,
                                      100000000000ULL,
                                      1000000000000ULL,
                                      10000000000000ULL,
                                      100000000000000ULL,
                                      1000000000000000ULL,
                                      10000000000000000ULL,
                                      100000000000000000ULL};

#ifdef __SSE2__
// The sixteen digits of r < 10^16, with leading zeros, into o[0..15]: r = 10^8 b + c, then
// b and c each into two groups of four digits (b / 10^4, b % 10^4, c / 10^4, c % 10^4) in
// the 16-bit lanes 0-3, these into pairs of digits (the quotient and remainder by 100),
// the pairs into tens and units, one byte each; the divisions are multiplications by
// 2^45 / 10^4 (exact below 2^32), 2^19 / 100 (exact below 43699) and 2^16 / 10 (exact
// below 16389), rounded up.
inline void sixteen_digits(uint64_t r, char *o)
{
    uint64_t b = r / 100000000, c = r % 100000000;
    __m128i v = _mm_set_epi64x((long long)c, (long long)b);
    __m128i q4 = _mm_srli_epi64(_mm_mul_epu32(v, _mm_set1_epi32((int)0xD1B71759)), 45);
    __m128i r4 = _mm_sub_epi64(v, _mm_mul_epu32(q4, _mm_set1_epi32(10000)));
    __m128i groups = _mm_shuffle_epi32(_mm_or_si128(q4, _mm_slli_epi64(r4, 16)),
                                       _MM_SHUFFLE(3, 1, 2, 0));
    __m128i q2 = _mm_srli_epi16(_mm_mulhi_epu16(groups, _mm_set1_epi16(5243)), 3);
    __m128i r2 = _mm_sub_epi16(groups, _mm_mullo_epi16(q2, _mm_set1_epi16(100)));
    __m128i pairs = _mm_unpacklo_epi16(q2, r2);
    __m128i tens = _mm_mulhi_epu16(pairs, _mm_set1_epi16(6554));
    __m128i units = _mm_sub_epi16(pairs, _mm_mullo_epi16(tens, _mm_set1_epi16(10)));
    __m128i text =
        _mm_or_si128(_mm_or_si128(tens, _mm_slli_epi16(units, 8)), _mm_set1_epi8('0'));
    _mm_storeu_si128(reinterpret_cast<__m128i *>(o), text);
}
#endif

// The 17 digits of s < 10^17, with leading zeros, into d[0..16].
inline void seventeen_digits(uint64_t s, char *d)
{
    uint64_t a = s / pow10_table[16], r = s % pow10_table[16];
    d[0] = (char)('0' + a);
#ifdef __SSE2__
    sixteen_digits(r, d + 1);
#else
    eight_digits((uint32_t)(r / pow10_table[8]), d + 1);
    eight_digits((uint32_t)(r % pow10_table[8]), d + 9);
#endif
}

// A fixed-size copy of up to 17 digits (two vector moves): the buffers have room past the
// bytes that count.
inline void copy24(char *to, const char *from)
{
    std::memcpy(to, from, 24);
}

} // namespace

// The shortest digits d1 d2 ... dn (no trailing zeros) and the decimal exponent E of
// v = d1.d2...dn x 10^E are laid out as a plain decimal for -4 <= E < 17 (as %g would:
// 0.0001, 123456.5, 12000) and as d.ddde+X / d.ddde-X otherwise (1e-05 is "1e-5", 1e17
// is "1e+17").  The longest text is 24 characters ("-1.2345678901234567e-308",
// "-0.00012345678901234567"); the fixed-size copies below reach at most byte 42 of buf's
// MIMAS_NUMFMT_MAX and byte 41 of d.
#if defined(__GNUC__)
#define MIMAS_FLATTEN __attribute__((flatten)) // Dragonbox inlined: 10 instructions fewer
#else
#define MIMAS_FLATTEN
#endif
extern "C" MIMAS_FLATTEN size_t mimas_format_double(double v, char *buf)
{
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    char *o = buf;
    if (bits >> 63) {
        *o++ = '-';
        v = -v;
    }
    if ((bits << 1) == 0) { // zeros: many in empty cells
        *o++ = '0';
        *o = '\0';
        return (size_t)(o - buf);
    }
    if (((bits >> 52) & 0x7FF) == 0x7FF) { // inf, nan (without a sign)
        if (bits << 12) {
            o = buf;
            std::memcpy(o, "nan", 4);
            return 3;
        }
        std::memcpy(o, "inf", 4);
        return (size_t)(o - buf) + 3;
    }
    fmt::detail::dragonbox::decimal_fp<double> dec = fmt::detail::dragonbox::to_decimal(v);
    uint64_t s = dec.significand; // < 10^17
    int nd = fmt::detail::count_digits(s);
    int e = dec.exponent + nd - 1;
    char d[48]; // the digits of s end at d[16]; d[17..47] is room for the copies
    std::memset(d + 17, 0, sizeof d - 17);
    const char *src = d + 17 - nd;
    if (e >= -4 && e < 17) {
        int point = e + 1; // digits before the decimal point
        if (point <= 0) {  // 0.000ddd
            std::memcpy(o, "0.000000", 8);
            o += 2 - point;
            seventeen_digits(s, d);
            copy24(o, src);
            o += nd;
        } else if (point >= nd) { // an integer: its point digits, s 10^(point - nd) < 10^17
            seventeen_digits(s * pow10_table[point - nd], d);
            src = d + 17 - point;
            copy24(o, src);
            o += point;
        } else { // ddd.ddd
            seventeen_digits(s, d);
            copy24(o, src);
            o[point] = '.';
            copy24(o + point + 1, src + point);
            o += nd + 1;
        }
    } else {
        seventeen_digits(s, d);
        o[0] = src[0];
        if (nd > 1) {
            o[1] = '.';
            copy24(o + 2, src + 1);
            o += nd + 1;
        } else {
            o += 1;
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
