C     rollcon test routines (suite force-measures): a VARSUB reading a joint's reaction, and a
C     DIFSUB integrating it.
C     VARSUB: PAR(1) = 1: |F| of JOINT/1 at its I, SYSFNC('JOINT', 1, 0, 1); PAR(1) = 2: the
C     same through FM(20, 10); PAR(1) = 3: the torque TM(20, 10) (variable_cycle.adm).
C     DIFSUB: SYSFNC('JOINT', 1, 0, 1), the rate of a DIFF integrating the reaction.
      SUBROUTINE VARSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(3)
      LOGICAL ERRFLG
      IF (NINT(PAR(1)) .EQ. 1) THEN
         IPAR(1) = 1
         IPAR(2) = 0
         IPAR(3) = 1
         CALL SYSFNC('JOINT', IPAR, 3, VALUE, ERRFLG)
         CALL ERRMES(ERRFLG, 'SYSFNC JOINT failed', ID, 'STOP')
      ELSE IF (NINT(PAR(1)) .EQ. 2) THEN
         IPAR(1) = 20
         IPAR(2) = 10
         CALL SYSFNC('FM', IPAR, 2, VALUE, ERRFLG)
         CALL ERRMES(ERRFLG, 'SYSFNC FM failed', ID, 'STOP')
      ELSE
         IPAR(1) = 20
         IPAR(2) = 10
         CALL SYSFNC('TM', IPAR, 2, VALUE, ERRFLG)
         CALL ERRMES(ERRFLG, 'SYSFNC TM failed', ID, 'STOP')
      END IF
      END

      SUBROUTINE DIFSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(3)
      LOGICAL ERRFLG
      IPAR(1) = 1
      IPAR(2) = 0
      IPAR(3) = 1
      CALL SYSFNC('JOINT', IPAR, 3, VALUE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC JOINT failed', ID, 'STOP')
      END
