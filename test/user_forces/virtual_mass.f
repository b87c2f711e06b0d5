C     rollcon test routines (suite user-forces): a virtual mass read through the
C     accelerations. The SFOSUB returns -PAR(3) ACCZ(PAR(1), PAR(2)) (SYSFNC: the
C     acceleration of marker PAR(1) from PAR(2) along ground Z); the VFOSUB returns
C     (PAR(2), 0, 0) - PAR(3) TACC(PAR(1)) (SYSARY: the marker's acceleration, ground axes).
      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(1)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2)
      DOUBLE PRECISION ACC
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSFNC('ACCZ', IPAR, 2, ACC, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC ACCZ failed', ID, 'STOP')
      RESULT(1) = -PAR(3)*ACC
      END

      SUBROUTINE VFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(3)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(1), NSTATE
      DOUBLE PRECISION ACC(3)
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      CALL SYSARY('TACC', IPAR, 1, ACC, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY TACC failed', ID, 'STOP')
      RESULT(1) = PAR(2) - PAR(3)*ACC(1)
      RESULT(2) = -PAR(3)*ACC(2)
      RESULT(3) = -PAR(3)*ACC(3)
      END
