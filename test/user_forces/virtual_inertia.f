C     rollcon test routine (suite user-forces): a VTOSUB with a virtual inertia read through
C     the angular accelerations: (0, 0, PAR(2)) - PAR(3) RACC(PAR(1)) (SYSARY: the marker's
C     angular acceleration, ground axes).
      SUBROUTINE VTOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(3)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(1), NSTATE
      DOUBLE PRECISION ALPHA(3)
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      CALL SYSARY('RACC', IPAR, 1, ALPHA, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY RACC failed', ID, 'STOP')
      RESULT(1) = -PAR(3)*ALPHA(1)
      RESULT(2) = -PAR(3)*ALPHA(2)
      RESULT(3) = PAR(2) - PAR(3)*ALPHA(3)
      END
