C     rollcon test data (suite user-forces): the spring-damper SFOSUB of ../sforce_spring.f
C     with one planted fault, run on ../user_forces.adm (test/unit/job/test_user_forces.f90).
C     FAULT: every call after the initialisation call changes an argument the routine may
C     only read: TIME, moved on by 1 s.
C     EXPECTED: the error: SFORCE/2's SFOSUB changed TIME, which it may only read.
      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(*)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2), IZERO
      DOUBLE PRECISION DM, VR
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSFNC('DM', IPAR, 2, DM, ERRFLG)
      CALL SYSFNC('VR', IPAR, 2, VR, ERRFLG)
C     PAR(2) - 2 is zero: an index or divisor the compiler cannot see
      IZERO = NINT(PAR(2)) - 2
      RESULT(1) = -PAR(3)*(DM - PAR(5)) - PAR(4)*VR
      IF (.NOT. IFLAG) TIME = TIME + 1.0D0
      END
