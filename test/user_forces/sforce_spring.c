/* rollcon test routine (suite user-forces): sforce_spring.f written in C, the same
 * spring-damper SFOSUB between markers PAR(1) and PAR(2), stiffness PAR(3), damping PAR(4),
 * free length PAR(5): F = -PAR(3)*(DM - PAR(5)) - PAR(4)*VR, read with SYSFNC. Fortran's
 * calling convention: every argument by address, the name in lower case with a trailing
 * underscore, a LOGICAL an int, a character argument's length appended as a size_t. */
#include <math.h>
#include <stddef.h>

void sysfnc_(const char *fncnam, const int *ipar, const int *nsize, double *value,
             int *errflg, size_t fncnam_length);
void errmes_(const int *errflg, const char *mesage, const int *id, const char *endflg,
             size_t mesage_length, size_t endflg_length);

void sfosub_(const int *id, const double *time, const double *par, const int *npar,
             const int *dflag, const int *iflag, double *result)
{
    int ipar[2];
    int two = 2;
    int errflg;
    double dm, vr;

    (void)time;
    (void)npar;
    (void)dflag;
    (void)iflag;
    ipar[0] = (int)lround(par[0]);
    ipar[1] = (int)lround(par[1]);
    sysfnc_("DM", ipar, &two, &dm, &errflg, 2);
    errmes_(&errflg, "SYSFNC DM failed", id, "STOP", 16, 4);
    sysfnc_("VR", ipar, &two, &vr, &errflg, 2);
    errmes_(&errflg, "SYSFNC VR failed", id, "STOP", 16, 4);
    *result = -par[2] * (dm - par[4]) - par[3] * vr;
}
