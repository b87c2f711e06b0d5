C     rollcon test routine (suite user-forces): sforce_spring.f's SFOSUB with hidden state,
C     as `rollcon check` must report it: a SAVEd call counter flips the sign of a 1000 N term
C     at each call, so the same inputs give another RESULT each time; a run of it stalls (the
C     steps' Newton iterations meet another force at each call) and fails, its message
C     pointing at `rollcon check`.
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
      RESULT = -PAR(3)*(DM - PAR(5)) - PAR(4)*VR + 1.0D3*(-1)**CALLS
      END
