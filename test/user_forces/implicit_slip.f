C     rollcon test routine (suite user-forces): sforce_spring.f's SFOSUB written without
C     IMPLICIT NONE and with two slips of implicit typing, as `rollcon check` must report
C     them: KS (a name from I to N: INTEGER) receives the stiffness PAR(3) and is truncated,
C     and CD (REAL) receives the damping PAR(4) in single precision.
      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2)
      DOUBLE PRECISION DM, VR
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSFNC('DM', IPAR, 2, DM, ERRFLG)
      CALL SYSFNC('VR', IPAR, 2, VR, ERRFLG)
      KS = PAR(3)
      CD = PAR(4)
      RESULT = -KS*(DM - PAR(5)) - CD*VR
      END
