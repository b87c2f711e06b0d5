/* SPDX-License-Identifier: MIT */
/* One CSV row of numbers as text: the same characters as Fortran's '(*(es24.16e3, :, ","))'
 * followed by trim (rollcon_csv_writer), at a fraction of the cost of Fortran's formatted
 * write (docs/benchmark.md, "Costs of the parts of a step"). In C so that a whole row is one
 * call.
 *
 * A finite number x = m 2^e (m the 53-bit significand, a subnormal's normalised) of magnitude
 * below 1e17, or a zero, is converted exactly in integers (put_exact): its 17 significant
 * digits are x 10^k rounded to the nearest integer, ties to even, for k = 16 - floor(log10 |x|);
 * x 10^k = m 5^k 2^(k+e). For 1e-16 <= |x| m 5^k (k <= 32) fits 128 bits; below, m 5^k is a
 * multi-word integer (k <= 340: at most 14 words of 64 bits), of which the digits are the bits
 * above -(k + e) and the rounding is decided by the bits below: exact in every case, what a
 * correctly rounding printf gives, as glibc and gfortran do. Numbers of 1e17 and more go through
 * the C library's conversion (strfromd, C23 and glibc since 2.25): glibc spends about 0.14 us a
 * number, the exact path about 0.02 (a tiny residual's multi-word path a little more; the
 * digits written sixteen at a time, put_sixteen: about 150 instructions a number). The
 * csv-writer tests compare both with Fortran's formatted write. */
#define _GNU_SOURCE
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* Characters of one number: es24.16e3 */
#define FIELD 24

/* 5^k for k = 0..27, the powers that fit 64 bits */
static const uint64_t five[28] = {
    1u, 5u, 25u, 125u, 625u, 3125u, 15625u, 78125u, 390625u, 1953125u, 9765625u, 48828125u,
    244140625u, 1220703125u, 6103515625u, 30517578125u, 152587890625u, 762939453125u,
    3814697265625u, 19073486328125u, 95367431640625u, 476837158203125u, 2384185791015625u,
    11920928955078125u, 59604644775390625u, 298023223876953125u, 1490116119384765625u,
    7450580596923828125u};

/* "00" to "99", two characters each */
static const char pairs[201] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

/* value (< 10^8) as eight digits. On a little-endian machine all in one 64-bit word, its lanes
 * divided together by multiplications by scaled reciprocals (exact in these ranges): the two
 * halves of four digits in lanes of 32 bits, each split at 100 into lanes of 16 bits
 * (floor(a / 100) = floor(10486 a / 2^20) for a < 10^4), each of those at 10 into bytes
 * (floor(a / 10) = floor(103 a / 2^10) for a < 100), the first digit in the lowest byte: a
 * third of the instructions of two digits at a time (as on other machines). */
static inline __attribute__((always_inline)) void put_eight(uint32_t value, char *out)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    uint64_t x = (uint64_t)(value / 10000u) | (uint64_t)(value % 10000u) << 32, high;

    high = (x * 10486u) >> 20 & UINT64_C(0x0000007f0000007f);
    x = high | (x - high * 100u) << 16;
    high = (x * 103u) >> 10 & UINT64_C(0x000f000f000f000f);
    x = high | (x - high * 10u) << 8;
    x |= UINT64_C(0x3030303030303030);
    memcpy(out, &x, 8);
#else
    int i;

    for (i = 6; i >= 0; i -= 2) {
        memcpy(out + i, pairs + 2 * (value % 100), 2);
        value /= 100;
    }
#endif
}

/* value (< 10^16) as sixteen digits. With SSE2 (every x86-64) its two halves of eight digits
 * in the two 64-bit lanes of one register, split as put_eight splits one: at 10^4 into lanes
 * of 32 bits (floor(a / 10^4) = floor(3518437209 a / 2^45) for a < 10^8), at 100 into lanes of
 * 16 bits (floor(a / 100) = floor(10486 a / 2^20) for a < 10^4), at 10 into bytes
 * (floor(a / 10) = floor(6554 a / 2^16) for a < 100); else put_eight twice. */
static inline __attribute__((always_inline)) void put_sixteen(uint64_t value, char *out)
{
#if defined(__SSE2__)
    const uint64_t ten8 = 100000000u;
    uint64_t high = value / ten8;
    __m128i x = _mm_set_epi64x((long long)(value - high * ten8), (long long)high), q, r;

    q = _mm_srli_epi64(_mm_mul_epu32(x, _mm_set1_epi64x(3518437209)), 45);
    r = _mm_sub_epi64(x, _mm_mul_epu32(q, _mm_set1_epi64x(10000)));
    x = _mm_or_si128(q, _mm_slli_epi64(r, 32));
    q = _mm_srli_epi16(_mm_mulhi_epu16(x, _mm_set1_epi32(10486)), 4);
    r = _mm_sub_epi16(x, _mm_mullo_epi16(q, _mm_set1_epi32(100)));
    x = _mm_or_si128(q, _mm_slli_epi32(r, 16));
    q = _mm_mulhi_epu16(x, _mm_set1_epi16(6554));
    r = _mm_sub_epi16(x, _mm_mullo_epi16(q, _mm_set1_epi16(10)));
    x = _mm_or_si128(q, _mm_slli_epi16(r, 8));
    _mm_storeu_si128((__m128i *)(void *)out, _mm_or_si128(x, _mm_set1_epi8('0')));
#else
    put_eight((uint32_t)(value / 100000000u), out);
    put_eight((uint32_t)(value % 100000000u), out + 8);
#endif
}

/* The sign's character, then d.dddddddddddddddd (digits: 17 of them, 10^16 <= digits < 10^17),
 * E, the exponent's sign and three digits: es24.16e3. */
static void put_digits(int negative, uint64_t digits, int exponent, char *out)
{
    const uint64_t ten16 = 10000000000000000u;
    uint64_t rest = digits % ten16;
    int size = exponent < 0 ? -exponent : exponent;

    out[0] = negative ? '-' : ' ';
    out[1] = (char)('0' + digits / ten16);
    out[2] = '.';
    put_sixteen(rest, out + 3);
    out[19] = 'E';
    out[20] = exponent < 0 ? '-' : '+';
    out[21] = (char)('0' + size / 100);
    memcpy(out + 22, pairs + 2 * (size % 100), 2);
}

/* Words of a multi-word integer: m 5^k for k <= 340 (53 + 790 bits) */
#define WORDS 14

/* The digits of m 5^k 2^-shift (k > 27, shift > 0) rounded to the nearest integer, ties to
 * even, if they are below 2^64; *overflow set when they are not (the caller then takes one
 * more decimal exponent). Not inlined: the rare tiny numbers' path, whose registers inlined
 * cost the usual path a tenth of its instructions. */
static __attribute__((noinline)) uint64_t round_wide(uint64_t m, int k, int shift, int *overflow)
{
    uint64_t n[WORDS + 1] = {0}, digits, below;
    unsigned __int128 product;
    int length = 1, i, j, q, r, top, factor;

    n[0] = m;
    for (j = k; j > 0; j -= factor) {
        factor = j < 27 ? j : 27;
        product = 0;
        for (i = 0; i < length; i++) {
            product += (unsigned __int128)n[i] * five[factor];
            n[i] = (uint64_t)product;
            product >>= 64;
        }
        if (product != 0) n[length++] = (uint64_t)product;
    }
    /* bits of the product: the digits are bits shift ... shift + 63 */
    top = 64 * (length - 1) + (64 - __builtin_clzll(n[length - 1]));
    *overflow = top > shift + 64;
    if (*overflow) return 0;
    q = shift / 64;
    r = shift % 64;
    digits = n[q] >> r;
    if (r > 0) digits |= n[q + 1] << (64 - r);
    /* the bit just below the digits (half), and whether any bit below it is set */
    q = (shift - 1) / 64;
    r = (shift - 1) % 64;
    below = n[q] & ((UINT64_C(1) << r) - 1);
    for (i = 0; i < q && below == 0; i++) below = n[i];
    if ((n[q] >> r & 1u) && (below != 0 || (digits & 1))) digits++;
    return digits;
}

/* x as es24.16e3 in integer arithmetic when |x| < 1e17 or x is a zero: returns 1; 0 (nothing
 * decided) for any other x, which the C library converts. */
static int put_exact(double x, char *out)
{
    const uint64_t ten16 = 10000000000000000u, ten17 = 100000000000000000u;
    uint64_t bits, m, digits;
    int biased, e, exponent, k, shift, overflow;
    unsigned __int128 scaled, below;

    memcpy(&bits, &x, sizeof bits);
    biased = (int)((bits >> 52) & 0x7ff);
    m = bits & ((UINT64_C(1) << 52) - 1);
    if (biased == 0x7ff) return 0; /* not finite: put_special's */
    if (biased == 0) {
        if (m == 0) {
            put_digits((int)(bits >> 63), ten16, 0, out);
            out[1] = '0';
            return 1;
        }
        /* a subnormal, normalised: m 2^e with m of 53 bits */
        e = -1074;
        while (!(m >> 52)) {
            m <<= 1;
            e--;
        }
    } else {
        m |= UINT64_C(1) << 52;
        e = biased - 1075; /* x = m 2^e */
    }
    /* floor(log10 2^(e+52)) (78913 / 2^18 is log10 2 to 8e-7): |x| lies in
     * [2^(e+52), 2^(e+53)), so floor(log10 |x|) is this or one more; the loop below corrects
     * an estimate off by one either way */
    exponent = ((e + 52) * 78913) >> 18;
    for (;;) {
        k = 16 - exponent;
        if (k < 0) return 0;
        shift = -(k + e); /* x 10^k = m 5^k 2^-shift */
        if (k > 32) {
            /* x < 1e-16: shift > 0 and m 5^k is wider than 128 bits */
            digits = round_wide(m, k, shift, &overflow);
            if (overflow || digits >= ten17) {
                exponent++;
                continue;
            }
            if (digits < ten16) {
                exponent--;
                continue;
            }
            if (digits == ten17) {
                digits = ten16;
                exponent++;
            }
            break;
        }
        /* m 5^k < 2^53 5^32 < 2^128 */
        scaled = (unsigned __int128)m * five[k < 27 ? k : 27];
        if (k > 27) scaled *= five[k - 27];
        if (shift <= 0) {
            /* x 10^k < 2 10^17: an integer, exact */
            digits = (uint64_t)(scaled << -shift);
            if (digits >= ten17) {
                exponent++;
                continue;
            }
            break;
        }
        if (shift >= 128) return 0;
        digits = (uint64_t)(scaled >> shift);
        if (digits >= ten17) {
            exponent++;
            continue;
        }
        /* the bits below the digits moved to the top (0 < shift < 128): the highest is the
         * half, any other set makes it more than half */
        below = scaled << (128 - shift);
        if ((below >> 127) && ((below << 1) != 0 || (digits & 1))) digits++;
        if (digits == ten17) {
            digits = ten16;
            exponent++;
        }
        break;
    }
    put_digits((int)(bits >> 63), digits, exponent, out);
    return 1;
}

/* Any finite number as es24.16e3 through the C library: a blank or '-', 17 significant
 * digits, E, the exponent's sign and three digits. */
static void put_library(double x, char *out)
{
    char text[40];
    const char *e, *digit;
    int exponent = 0, length;

    /* "%.16E": d.ddddddddddddddddE+xx (two or three exponent digits), correctly rounded as
     * gfortran's own output */
    strfromd(text, sizeof text, "%.16E", x);
    e = strchr(text, 'E');
    for (digit = e + 2; *digit; digit++) exponent = 10 * exponent + (*digit - '0');
    length = (int)(e - text);
    if (text[0] == '-') {
        memcpy(out, text, (size_t)length);
    } else {
        out[0] = ' ';
        memcpy(out + 1, text, (size_t)length);
        length++;
    }
    out[length] = 'E';
    out[length + 1] = e[1];
    out[length + 2] = (char)('0' + exponent / 100);
    out[length + 3] = (char)('0' + exponent / 10 % 10);
    out[length + 4] = (char)('0' + exponent % 10);
}

/* A NaN or an infinity as gfortran writes it in a field of 24: right-justified. */
static void put_special(double x, char *out)
{
    const char *word = isnan(x) ? "NaN" : (x > 0 ? "Infinity" : "-Infinity");
    size_t length = strlen(word);

    memset(out, ' ', FIELD - length);
    memcpy(out + FIELD - length, word, length);
}

/* values(1:count) as one line without its line end, numbers separated by commas, into
 * line(1:capacity); returns its length, or -1 when capacity (25 per number) is too small. */
int rollcon_row_text(const double *values, int count, char *line, int capacity)
{
    int i;
    char *out = line;

    if (capacity < (FIELD + 1) * count) return -1;
    if (count == 0) return 0;
    /* each number and a comma after it, the last comma then left out of the length */
    for (i = 0; i < count; i++, out += FIELD + 1) {
        if (!put_exact(values[i], out)) {
            if (isfinite(values[i]))
                put_library(values[i], out);
            else
                put_special(values[i], out);
        }
        out[FIELD] = ',';
    }
    return (FIELD + 1) * count - 1;
}
