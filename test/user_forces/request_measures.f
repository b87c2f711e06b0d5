C     rollcon test routine (suite user-forces): a REQSUB writing marker PAR(1)'s displacement
C     from marker PAR(2) in PAR(2)'s axes (SYSARY's TDISP) into RESULT(2:4) and PAR(3) times
C     its angular velocity relative to PAR(2), in PAR(2)'s axes (SYSFNC's WX, WY, WZ), into
C     RESULT(6:8); RESULT(1) and RESULT(5), which ADAMS does not write, their magnitudes.
      SUBROUTINE REQSUB(ID, TIME, PAR, NPAR, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(8)
      LOGICAL IFLAG
      INTEGER IPAR(3), NSTATE
      DOUBLE PRECISION DISP(3), OMEGA
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      IPAR(3) = NINT(PAR(2))
      CALL SYSARY('TDISP', IPAR, 3, DISP, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY TDISP failed', ID, 'STOP')
      RESULT(2) = DISP(1)
      RESULT(3) = DISP(2)
      RESULT(4) = DISP(3)
      RESULT(1) = SQRT(DISP(1)**2 + DISP(2)**2 + DISP(3)**2)
      CALL SYSFNC('WX', IPAR, 3, OMEGA, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC WX failed', ID, 'STOP')
      RESULT(6) = PAR(3)*OMEGA
      CALL SYSFNC('WY', IPAR, 3, OMEGA, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC WY failed', ID, 'STOP')
      RESULT(7) = PAR(3)*OMEGA
      CALL SYSFNC('WZ', IPAR, 3, OMEGA, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC WZ failed', ID, 'STOP')
      RESULT(8) = PAR(3)*OMEGA
      RESULT(5) = SQRT(RESULT(6)**2 + RESULT(7)**2 + RESULT(8)**2)
      END
