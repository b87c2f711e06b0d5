C     rollcon test routine (suite user-forces): a spring-damper SFOSUB between markers
C     PAR(1) and PAR(2), stiffness PAR(3), damping PAR(4), free length PAR(5):
C     F = -PAR(3)*(DM - PAR(5)) - PAR(4)*VR, read with SYSFNC.
      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2)
      DOUBLE PRECISION DM, VR
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSFNC('DM', IPAR, 2, DM, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC DM failed', ID, 'STOP')
      CALL SYSFNC('VR', IPAR, 2, VR, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC VR failed', ID, 'STOP')
      RESULT = -PAR(3)*(DM - PAR(5)) - PAR(4)*VR
      END
