C     rollcon test routine (suite user-routine-check): an SFOSUB reading a VARSUB's VARIABLE
C     through SYSFNC('VARVAL'): a dry friction -PAR(2) SIGN(1, VARVAL(PAR(1))), a jump where
C     the VARIABLE (variable_stretch.f's stretch) changes sign, which rollcon check must find.
      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(1)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(1)
      DOUBLE PRECISION STRETCH
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      CALL SYSFNC('VARVAL', IPAR, 1, STRETCH, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC VARVAL failed', ID, 'STOP')
      RESULT(1) = -SIGN(PAR(2), STRETCH)
      END
