C     rollcon test routine (suite user-routine-check): motsub_sine.f's MOTSUB with hidden
C     state, as `rollcon check` must report it: a SAVEd call counter adds +-1e-3 to the
C     acceleration (IORD = 2) at each call, so the same TIME gives another VALUE each time.
      SUBROUTINE MOTSUB(ID, TIME, PAR, NPAR, IORD, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR, IORD, CALLS
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL IFLAG
      SAVE CALLS
      DATA CALLS /0/
      IF (IFLAG) RETURN
      CALLS = CALLS + 1
      IF (IORD .EQ. 0) THEN
         VALUE = PAR(1)*SIN(PAR(2)*TIME)
      ELSE IF (IORD .EQ. 1) THEN
         VALUE = PAR(1)*(COS(PAR(2)*TIME)*PAR(2))
      ELSE
         VALUE = PAR(1)*(-SIN(PAR(2)*TIME)*PAR(2)*PAR(2))
     &           + 1.0D-3*(-1)**CALLS
      END IF
      END
