C     rollcon test routine (suite user-forces): a DIFSUB, the first-order lag of marker
C     PAR(1)'s DX with time constant PAR(2): d DIF/dt = (DX - DIF)/PAR(2) (PAR(3) = 0, an
C     explicit DIFF: VALUE is the rate), or 0 = PAR(2) DIF1 - (DX - DIF) (PAR(3) = 1, an
C     IMPLICIT DIFF: VALUE is the residual), read through SYSFNC's DX, DIF and DIF1.
      SUBROUTINE DIFSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(1)
      DOUBLE PRECISION DX, DIF, DIF1
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      CALL SYSFNC('DX', IPAR, 1, DX, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC DX failed', ID, 'STOP')
      IPAR(1) = ID
      CALL SYSFNC('DIF', IPAR, 1, DIF, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC DIF failed', ID, 'STOP')
      IF (PAR(3) .GT. 0.5D0) THEN
          CALL SYSFNC('DIF1', IPAR, 1, DIF1, ERRFLG)
          CALL ERRMES(ERRFLG, 'SYSFNC DIF1 failed', ID, 'STOP')
          VALUE = PAR(2)*DIF1 - (DX - DIF)
      ELSE
          VALUE = (DX - DIF)/PAR(2)
      END IF
      END
