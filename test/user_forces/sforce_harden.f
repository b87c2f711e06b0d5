C     rollcon test routine (suite user-forces): sforce_cubic.f's hardening
C     spring under a name of its own, HARDEN, with SFOSUB's calling
C     sequence (named by ROUTINE=sforce_harden::HARDEN):
C     F = -PAR(3)*(1 + PAR(6)*T)*(DM - PAR(4)) - PAR(5)*(DM - PAR(4))**3.
      SUBROUTINE HARDEN(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2)
      DOUBLE PRECISION DM, T, S
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSFNC('DM', IPAR, 2, DM, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC DM failed', ID, 'STOP')
      CALL TIMGET(T)
      S = DM - PAR(4)
      RESULT = -PAR(3)*(1.0D0 + PAR(6)*T)*S - PAR(5)*S**3
      END
