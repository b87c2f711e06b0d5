C     rollcon test routine (suite user-forces): sforce_spring.f's SFOSUB with hidden state,
C     as `rollcon check` must report it: a SAVEd call counter adds 1e-3 N a call, so the same
C     inputs give another RESULT each time.
      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2), CALLS
      DOUBLE PRECISION DM, VR
      LOGICAL ERRFLG
      SAVE CALLS
      DATA CALLS /0/
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSFNC('DM', IPAR, 2, DM, ERRFLG)
      CALL SYSFNC('VR', IPAR, 2, VR, ERRFLG)
      CALLS = CALLS + 1
      RESULT = -PAR(3)*(DM - PAR(5)) - PAR(4)*VR + 1.0D-3*CALLS
      END
