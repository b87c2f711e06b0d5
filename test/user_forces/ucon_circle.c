/* rollcon test routine (suite user-forces): ucon_circle.f's CIRCLE written in C, named by
 * the same ROUTINE=ucon_circle::circle when this file is given in place of it. A part's
 * centre held on a circle of radius R = PAR(2) about ground Z, at position level:
 * F = X**2 + Y**2 - R**2 = 0 (PAR(1): the part's id). UCOSUB's calling sequence in Fortran's
 * convention, as ADAMS calls a C routine: every argument by address, the name in lower case
 * with a trailing underscore, XMATRX(30, 30) in column order. */
#include <math.h>

void ucovar_(const int *id, const int *nparts, const int *lparts, const int *nvars,
             const int *lvars);

void circle_(const int *id, const double *time, const double *q, const double *par,
             const int *npar, const int *idrsel, const int *iflag, double *scalar,
             double *array, double *xmatrx)
{
    static const int codes[2] = {11, 12};
    int parts[2];
    int two = 2;

    (void)time;
    (void)npar;
    if (*iflag == 3) {
        parts[0] = (int)lround(par[0]);
        parts[1] = parts[0];
        ucovar_(id, &two, parts, &two, codes);
        return;
    }
    if (idrsel[0] == 1) *scalar = q[0] * q[0] + q[1] * q[1] - par[1] * par[1];
    if (idrsel[1] == 1) {
        array[0] = 2.0 * q[0];
        array[1] = 2.0 * q[1];
    }
    if (idrsel[2] == 1) {
        /* XMATRX(1, 1) and XMATRX(2, 2): column order, leading dimension 30 */
        xmatrx[0] = 2.0;
        xmatrx[30 + 1] = 2.0;
    }
}
