/* SPDX-License-Identifier: MIT */
/* Reals as text and back for rollcon_text, without Fortran's formatted I/O.
 *
 * rollcon_decimal_value: the double of a decimal text (a dataset's numbers), by strtod, which
 * is what libgfortran's list-directed READ of a real ends in (read.c: convert_real), with a D
 * exponent letter read as E as Fortran does: the same double for every text, at a fraction of
 * the cost (about 4,000 instructions a number through libgfortran's list-directed machinery).
 *
 * rollcon_es_compact: a finite double as Fortran's ESw.dE3 edit descriptor writes it, without
 * the blanks before: libgfortran writes ES (ROUND unspecified) by snprintf's "%+-#.*e" at
 * precision d (write_float.def) and its exponent with a sign and three digits; the same here.
 *
 * rollcon_shortest_digits: the shortest significant digits of a double that read back as it
 * (rollcon_text's real_to_text), the same digits as the search by Fortran's formatted I/O it
 * replaces, at a fraction of its cost (about 250,000 instructions a number: up to 17 pairs of
 * an es40.(d-1)e3 WRITE and a list-directed READ, each through libgfortran's format
 * machinery).
 *
 * The old search took the first d = 1, 2, ..., 17 for which the number written with d
 * significant digits reads back as the same double. libgfortran writes ES with an unspecified
 * ROUND mode by snprintf's "%+-#.*e" at precision d - 1 (write_float.def: determine_precision,
 * DTOA), so its digits are the C library's correctly rounded ones, and a list-directed READ of
 * a real ends in strtod (read.c: convert_real). Here the same: snprintf "%.*e" and strtod.
 *
 * Fewer candidates are tried, with the same answer: for a normal double v and d <= 15
 * (DBL_DIG), if the d-digit rounding D of v reads back as v, then every d' from d to 15 does
 * too: D (padded with zeros) is a d'-digit decimal that reads as v, and a decimal of at most
 * DBL_DIG digits read into a double and written back with as many digits is unchanged (C's
 * definition of DBL_DIG), so the d'-digit rounding of v is D again. Reading back is therefore
 * monotone in d over 1..15, and the least such d is found by bisection after one try at 15;
 * when 15 fails, 16 then 17 (17 always reads back). Subnormals, which have fewer than 53 bits,
 * are searched one d at a time as before. The text suite compares every digit with the old
 * Fortran search over random bit patterns, subnormals, powers of 2 and 10 and their
 * neighbours, short decimals, extremes and integers.
 *
 * snprintf and strtod follow the thread's LC_NUMERIC, which a program using the library may
 * have set (a decimal comma: "1,5"); libgfortran's I/O does not. Each function here works in
 * the "C" locale (uselocale, POSIX 2008: the calling thread's alone, put back on return), so
 * a dataset's "1.5" reads and the texts hold a point whatever the host set (test
 * text/numbers-under-a-decimal-comma-locale). */
#include <float.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* The "C" locale, made once ((locale_t)0 when it cannot be made: the thread's own is kept) */
static locale_t c_locale(void)
{
    static locale_t made = (locale_t)0;
    if (made == (locale_t)0) made = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    return made;
}

/* Make the "C" locale the calling thread's; what to give leave_c_locale */
static locale_t enter_c_locale(void)
{
    locale_t c = c_locale();
    return c == (locale_t)0 ? (locale_t)0 : uselocale(c);
}

/* Give the thread back the locale enter_c_locale found */
static void leave_c_locale(locale_t before)
{
    if (before != (locale_t)0) uselocale(before);
}

/* Room for "-d.ddddddddddddddddde-308" and its terminating zero */
#define ROOM 40

/* |value| with digits significant digits into text (snprintf "%.*e"); true when it reads
 * back (strtod) as |value|. */
static int reads_back(double value, int digits, char *text)
{
    snprintf(text, ROOM, "%.*e", digits - 1, value);
    return strtod(text, NULL) == value;
}

/* The shortest significant digits (1 to 17) of the finite, nonzero |value| that read back as
 * it: the digits without point or sign into digits (at least 17 characters; not terminated),
 * the decimal exponent of the first into *exponent (|value| = d.ddd 10^exponent), their
 * number into *count. */
void rollcon_shortest_digits(double value, char *digits, int *exponent, int *count_out)
{
    char text[ROOM];
    int count, low, high, middle, printed, i, n;
    char *e;
    locale_t before = enter_c_locale();

    value = fabs(value);
    if (value < DBL_MIN) {
        for (count = 1; count < 17; ++count)
            if (reads_back(value, count, text)) break;
        if (count == 17) reads_back(value, count, text);
    } else if (!reads_back(value, 15, text)) {
        count = reads_back(value, 16, text) ? 16 : 17;
        if (count == 17) reads_back(value, count, text);
    } else {
        /* 15 reads back: the least count in 1..15 that does */
        low = 1;
        high = 15;
        printed = 15;
        while (low < high) {
            middle = (low + high) / 2;
            printed = middle;
            if (reads_back(value, middle, text))
                high = middle;
            else
                low = middle + 1;
        }
        count = high;
        if (printed != count) reads_back(value, count, text);
    }
    /* text is "d.ddde+XX" (or "de+XX" for one digit) */
    n = 0;
    for (i = 0; text[i] != 'e' && text[i] != '\0'; ++i)
        if (text[i] >= '0' && text[i] <= '9') digits[n++] = text[i];
    e = text + i;
    *exponent = (*e == 'e') ? (int)strtol(e + 1, NULL, 10) : 0;
    *count_out = n;
    leave_c_locale(before);
}

/* The double of the decimal text (length characters, not terminated; D or d taken as the
 * exponent letter E) into *value by strtod; *read_all is 1 when strtod took every character,
 * else 0. */
void rollcon_decimal_value(const char *text, int length, double *value, int *read_all)
{
    char room[64], *copy = room, *end;
    int i;
    locale_t before;

    *read_all = 0;
    *value = 0.0;
    if (length < 0) return;
    if (length >= (int)sizeof room) {
        copy = malloc((size_t)length + 1);
        if (copy == NULL) return;
    }
    for (i = 0; i < length; ++i)
        copy[i] = (text[i] == 'D' || text[i] == 'd') ? 'E' : text[i];
    copy[length] = '\0';
    before = enter_c_locale();
    *value = strtod(copy, &end);
    leave_c_locale(before);
    *read_all = length > 0 && end == copy + length;
    if (copy != room) free(copy);
}

/* The finite value with decimals digits after the point as "[-]d.ddd...E+xxx" (Fortran's
 * ES with a three-digit exponent, blanks before it left out: a zero's sign as its sign bit,
 * as gfortran writes -0.0) into out (at least decimals + 9 characters; not terminated), its
 * length into *length. decimals from 0 to 40. */
void rollcon_es_compact(double value, int decimals, char *out, int *length)
{
    char text[64];
    int n = 0, i, exponent;
    locale_t before = enter_c_locale();

    snprintf(text, sizeof text, "%#.*e", decimals, value);
    leave_c_locale(before);
    for (i = 0; text[i] != 'e' && text[i] != '\0'; ++i) out[n++] = text[i];
    exponent = (text[i] == 'e') ? (int)strtol(text + i + 1, NULL, 10) : 0;
    out[n++] = 'E';
    out[n++] = exponent < 0 ? '-' : '+';
    if (exponent < 0) exponent = -exponent;
    out[n++] = (char)('0' + exponent / 100 % 10);
    out[n++] = (char)('0' + exponent / 10 % 10);
    out[n++] = (char)('0' + exponent % 10);
    *length = n;
}
