C     rollcon test routine (suite force-measures): the driving torque of motion_crank.adm's
C     MOTION/PAR(1) read through SYSFNC at each output row: RESULT(2:4) = TZ(20, 10),
C     TM(20, 10), MOTION(id, 0, 8) (its torque's Z at I); RESULT(6:8) = MOTION(id, 1, 8) (at
C     J), FM(20, 10), FX(20, 10).
      SUBROUTINE REQSUB(ID, TIME, PAR, NPAR, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(8)
      LOGICAL IFLAG
      INTEGER IPAR(3)
      LOGICAL ERRFLG
      IPAR(1) = 20
      IPAR(2) = 10
      CALL SYSFNC('TZ', IPAR, 2, RESULT(2), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC TZ failed', ID, 'STOP')
      CALL SYSFNC('TM', IPAR, 2, RESULT(3), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC TM failed', ID, 'STOP')
      CALL SYSFNC('FM', IPAR, 2, RESULT(7), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC FM failed', ID, 'STOP')
      CALL SYSFNC('FX', IPAR, 2, RESULT(8), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC FX failed', ID, 'STOP')
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = 0
      IPAR(3) = 8
      CALL SYSFNC('MOTION', IPAR, 3, RESULT(4), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC MOTION failed', ID, 'STOP')
      IPAR(2) = 1
      CALL SYSFNC('MOTION', IPAR, 3, RESULT(6), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC MOTION failed', ID, 'STOP')
      END
