C     rollcon test routine (suite user-forces): a VTOSUB, a torsional spring-damper turning
C     marker PAR(1) back toward marker PAR(2): stiffness PAR(3) on the angles AX, AY, AZ of
C     PAR(1) about PAR(2) and damping PAR(4) on their relative angular velocity, components
C     in marker PAR(2)'s axes (SYSFNC's AX, AY, AZ and SYSARY's RVEL(I, J, J)).
      SUBROUTINE VTOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(3)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(3), NSTATE
      DOUBLE PRECISION OMEGA(3), ANGLE(3)
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      IPAR(3) = NINT(PAR(2))
      CALL SYSARY('RVEL', IPAR, 3, OMEGA, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY RVEL failed', ID, 'STOP')
      CALL SYSFNC('AX', IPAR, 2, ANGLE(1), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC AX failed', ID, 'STOP')
      CALL SYSFNC('AY', IPAR, 2, ANGLE(2), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC AY failed', ID, 'STOP')
      CALL SYSFNC('AZ', IPAR, 2, ANGLE(3), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC AZ failed', ID, 'STOP')
      RESULT(1) = -PAR(3)*ANGLE(1) - PAR(4)*OMEGA(1)
      RESULT(2) = -PAR(3)*ANGLE(2) - PAR(4)*OMEGA(2)
      RESULT(3) = -PAR(3)*ANGLE(3) - PAR(4)*OMEGA(3)
      END
