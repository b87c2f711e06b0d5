C     rollcon test routine (suite force-measures): a pivot friction proportional to the
C     joint's reaction, -PAR(1) FM(20, 10) WZ(20, 10), both read through SYSFNC.
      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(1)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2)
      DOUBLE PRECISION REACTION, RATE
      LOGICAL ERRFLG
      IPAR(1) = 20
      IPAR(2) = 10
      CALL SYSFNC('FM', IPAR, 2, REACTION, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC FM failed', ID, 'STOP')
      CALL SYSFNC('WZ', IPAR, 2, RATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC WZ failed', ID, 'STOP')
      RESULT(1) = -PAR(1)*REACTION*RATE
      END

C     The joint's reaction and the friction read by a REQSUB at each output row:
C     RESULT(2:4) = FM(20, 10), FX(20, 10, 22), TZ(20, 10), as REQUEST/6 reads them in
C     expressions.
      SUBROUTINE REQSUB(ID, TIME, PAR, NPAR, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(8)
      LOGICAL IFLAG
      INTEGER IPAR(3)
      LOGICAL ERRFLG
      IPAR(1) = 20
      IPAR(2) = 10
      IPAR(3) = 22
      CALL SYSFNC('FM', IPAR, 2, RESULT(2), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC FM failed', ID, 'STOP')
      CALL SYSFNC('FX', IPAR, 3, RESULT(3), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC FX failed', ID, 'STOP')
      CALL SYSFNC('TZ', IPAR, 2, RESULT(4), ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC TZ failed', ID, 'STOP')
      END
