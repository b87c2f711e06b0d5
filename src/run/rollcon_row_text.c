/* SPDX-License-Identifier: MIT */
/* One CSV row of numbers as text: the same characters as Fortran's '(*(es24.16e3, :, ","))'
 * followed by trim (rollcon_csv_writer), at a fraction of the cost of Fortran's formatted
 * write (docs/benchmark.md, "Costs of the parts of a step"). In C so that a whole row is one
 * call.
 *
 * A number x = m 2^e (m the 53-bit significand) of magnitude 1e-16 to 1e17, or a zero, is
 * converted exactly in integers (put_exact): its 17 significant digits are x 10^k rounded to
 * the nearest integer, ties to even, for k = 16 - floor(log10 |x|); x 10^k = m 5^k 2^(k+e) and
 * m 5^k (k <= 32) fits 128 bits, so the digits, the remainder and the rounding are exact:
 * what a correctly rounding printf gives, as glibc and gfortran do. Every other finite number
 * (the rare tiny residual, a huge value, a subnormal) goes through the C library's conversion
 * (strfromd, C23 and glibc since 2.25), as every number did before issue #25: glibc spends
 * about 0.14 us a number, the exact path about 0.02. The csv-writer tests compare both with
 * Fortran's formatted write. */
#define _GNU_SOURCE
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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

/* value (< 10^8) as eight digits */
static void put_eight(uint32_t value, char *out)
{
    int i;

    for (i = 6; i >= 0; i -= 2) {
        memcpy(out + i, pairs + 2 * (value % 100), 2);
        value /= 100;
    }
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
    put_eight((uint32_t)(rest / 100000000u), out + 3);
    put_eight((uint32_t)(rest % 100000000u), out + 11);
    out[19] = 'E';
    out[20] = exponent < 0 ? '-' : '+';
    out[21] = (char)('0' + size / 100);
    out[22] = (char)('0' + size / 10 % 10);
    out[23] = (char)('0' + size % 10);
}

/* x as es24.16e3 in integer arithmetic when 1e-16 <= |x| < 1e17 or x is a zero: returns 1;
 * 0 (nothing decided) for any other x, which the C library converts. */
static int put_exact(double x, char *out)
{
    const uint64_t ten16 = 10000000000000000u, ten17 = 100000000000000000u;
    uint64_t bits, m, digits;
    int biased, e, exponent, k, shift;
    unsigned __int128 scaled, rest, half;

    memcpy(&bits, &x, sizeof bits);
    biased = (int)((bits >> 52) & 0x7ff);
    m = bits & ((UINT64_C(1) << 52) - 1);
    if (biased == 0) {
        if (m != 0) return 0; /* subnormal */
        put_digits((int)(bits >> 63), ten16, 0, out);
        out[1] = '0';
        return 1;
    }
    m |= UINT64_C(1) << 52;
    e = biased - 1075; /* x = m 2^e */
    /* floor(log10 2^(e+52)) (78913 / 2^18 is log10 2 to 8e-7; exact for every e whose k is
     * 0 to 32, checked in rational arithmetic): |x| lies in [2^(e+52), 2^(e+53)), so
     * floor(log10 |x|) is this or one more */
    exponent = ((e + 52) * 78913) >> 18;
    for (;;) {
        k = 16 - exponent;
        if (k < 0 || k > 32) return 0;
        /* m 5^k < 2^53 5^32 < 2^128 */
        scaled = (unsigned __int128)m * five[k < 27 ? k : 27];
        if (k > 27) scaled *= five[k - 27];
        shift = -(k + e); /* x 10^k = scaled 2^-shift */
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
        rest = scaled & ((((unsigned __int128)1) << shift) - 1);
        half = ((unsigned __int128)1) << (shift - 1);
        if (rest > half || (rest == half && (digits & 1))) digits++;
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
    int i, used = 0;

    if (capacity < (FIELD + 1) * count) return -1;
    for (i = 0; i < count; i++) {
        if (i > 0) line[used++] = ',';
        if (!isfinite(values[i]))
            put_special(values[i], line + used);
        else if (!put_exact(values[i], line + used))
            put_library(values[i], line + used);
        used += FIELD;
    }
    return used;
}
