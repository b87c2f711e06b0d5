C     rollcon test routine (suite force-measures): a VFORCE reading another element's force
C     through SYSFNC: RESULT = (PAR(1) SFORCE(1, 0, 2, 2), 0, PAR(2) FZ(I, J, 2)), the
C     markers I = PAR(3), J = PAR(4).
      SUBROUTINE VFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(3)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(4)
      DOUBLE PRECISION ELEMENT, NET
      LOGICAL ERRFLG
      IPAR(1) = 1
      IPAR(2) = 0
      IPAR(3) = 2
      IPAR(4) = 2
      CALL SYSFNC('SFORCE', IPAR, 4, ELEMENT, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC SFORCE failed', ID, 'STOP')
      IPAR(1) = NINT(PAR(3))
      IPAR(2) = NINT(PAR(4))
      IPAR(3) = 2
      CALL SYSFNC('FZ', IPAR, 3, NET, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC FZ failed', ID, 'STOP')
      RESULT(1) = PAR(1)*ELEMENT
      RESULT(2) = 0.0D0
      RESULT(3) = PAR(2)*NET
      END
