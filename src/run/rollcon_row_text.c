/* SPDX-License-Identifier: MIT */
/* One CSV row of numbers as text, through the C library's conversion of a double to decimal
 * (strfromd, C23 and glibc since 2.25: printf's conversion without parsing a format per call):
 * the same characters as Fortran's '(*(es24.16e3, :, ","))' followed by trim
 * (rollcon_csv_writer), at a fraction of the cost of Fortran's formatted write
 * (docs/benchmark.md, "Costs of the parts of a step"). In C so that a whole row is one call. */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Characters of one number: es24.16e3 */
#define FIELD 24

/* One finite number as es24.16e3: a blank or '-', 17 significant digits, E, the exponent's
 * sign and three digits. Returns the characters written (24). */
static int put_finite(double x, char *out)
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
    return FIELD;
}

/* A NaN or an infinity as gfortran writes it in a field of 24: right-justified. */
static int put_special(double x, char *out)
{
    const char *word = isnan(x) ? "NaN" : (x > 0 ? "Infinity" : "-Infinity");
    size_t length = strlen(word);

    memset(out, ' ', FIELD - length);
    memcpy(out + FIELD - length, word, length);
    return FIELD;
}

/* values(1:count) as one line without its line end, numbers separated by commas, into
 * line(1:capacity); returns its length, or -1 when capacity (25 per number) is too small. */
int rollcon_row_text(const double *values, int count, char *line, int capacity)
{
    int i, used = 0;

    if (capacity < (FIELD + 1) * count) return -1;
    for (i = 0; i < count; i++) {
        if (i > 0) line[used++] = ',';
        if (isfinite(values[i]))
            used += put_finite(values[i], line + used);
        else
            used += put_special(values[i], line + used);
    }
    return used;
}
