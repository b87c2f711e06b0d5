C     rollcon test routine (suite user-forces): a VFOSUB pulling marker PAR(1) toward the
C     point (0, 0, -PAR(4)) of marker PAR(2) with stiffness PAR(3), components in marker
C     PAR(2)'s axes from SYSARY's TDISP(I, J, J).
      SUBROUTINE VFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(3)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(3), NSTATE
      DOUBLE PRECISION DISP(3)
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      IPAR(3) = NINT(PAR(2))
      CALL SYSARY('TDISP', IPAR, 3, DISP, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY TDISP failed', ID, 'STOP')
      RESULT(1) = -PAR(3)*DISP(1)
      RESULT(2) = -PAR(3)*DISP(2)
      RESULT(3) = -PAR(3)*(DISP(3) + PAR(4))
      END
