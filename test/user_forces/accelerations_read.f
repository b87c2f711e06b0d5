C     rollcon test routines (suite user-forces): a VARSUB, an SFOSUB, a DIFSUB and a REQSUB
C     reading the accelerations (SYSFNC's ACCZ, SYSARY's TACC and RACC).
C     VARSUB: PAR(2) ACCZ(PAR(1)), a virtual mass's force read by a force through VARVAL.
C     SFOSUB: -VARVAL(PAR(1)) (SYSFNC('VARVAL')), the force of such a VARIABLE.
C     DIFSUB: ACCZ(PAR(1)) (PAR(2) = 0, an explicit DIFF: the rate), or the residual
C     DIF1 - ACCZ(PAR(1)) (PAR(2) = 1, an IMPLICIT DIFF): either integrates the marker's
C     vertical acceleration to its vertical velocity less its initial one.
C     REQSUB: marker PAR(1)'s TACC into RESULT(2:4) and RACC into RESULT(6:8), ground axes;
C     RESULT(1) and RESULT(5), which ADAMS does not write, their magnitudes.
      SUBROUTINE VARSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(1)
      DOUBLE PRECISION ACC
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      CALL SYSFNC('ACCZ', IPAR, 1, ACC, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC ACCZ failed', ID, 'STOP')
      VALUE = PAR(2)*ACC
      END

      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(1)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(1)
      DOUBLE PRECISION VALUE
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      CALL SYSFNC('VARVAL', IPAR, 1, VALUE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC VARVAL failed', ID, 'STOP')
      RESULT(1) = -VALUE
      END

      SUBROUTINE DIFSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(1)
      DOUBLE PRECISION ACC, DIF1
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      CALL SYSFNC('ACCZ', IPAR, 1, ACC, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC ACCZ failed', ID, 'STOP')
      IF (PAR(2) .GT. 0.5D0) THEN
          IPAR(1) = ID
          CALL SYSFNC('DIF1', IPAR, 1, DIF1, ERRFLG)
          CALL ERRMES(ERRFLG, 'SYSFNC DIF1 failed', ID, 'STOP')
          VALUE = DIF1 - ACC
      ELSE
          VALUE = ACC
      END IF
      END

      SUBROUTINE REQSUB(ID, TIME, PAR, NPAR, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(8)
      LOGICAL IFLAG
      INTEGER IPAR(1), NSTATE
      DOUBLE PRECISION ACC(3)
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      CALL SYSARY('TACC', IPAR, 1, ACC, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY TACC failed', ID, 'STOP')
      RESULT(2) = ACC(1)
      RESULT(3) = ACC(2)
      RESULT(4) = ACC(3)
      RESULT(1) = SQRT(ACC(1)**2 + ACC(2)**2 + ACC(3)**2)
      CALL SYSARY('RACC', IPAR, 1, ACC, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY RACC failed', ID, 'STOP')
      RESULT(6) = ACC(1)
      RESULT(7) = ACC(2)
      RESULT(8) = ACC(3)
      RESULT(5) = SQRT(ACC(1)**2 + ACC(2)**2 + ACC(3)**2)
      END
