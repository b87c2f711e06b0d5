C     rollcon test routine (suite user-forces): a VARSUB, the stretch of a spring between
C     markers PAR(1) and PAR(2) of free length PAR(3): DM(PAR(1), PAR(2)) - PAR(3) (SYSFNC).
      SUBROUTINE VARSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2)
      DOUBLE PRECISION DM
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSFNC('DM', IPAR, 2, DM, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC DM failed', ID, 'STOP')
      VALUE = DM - PAR(3)
      END
