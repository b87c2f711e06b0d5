C     rollcon test data (suite user-forces): the spring-damper SFOSUB of ../sforce_spring.f
C     with one planted fault, run on ../user_forces.adm (test/unit/job/test_user_forces.f90).
C     FAULT: an integer division by zero, NPAR / IZERO, in the calls after the initialisation
C     call (1 / IZERO would not trap: GCC folds it into a compare, as 1 / n is 0 unless n is
C     1 or -1).
C     EXPECTED: killed by SIGFPE inside an SFOSUB call, the run stopped, SFORCE/2 named.
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
      IF (.NOT. IFLAG) RESULT(1) = RESULT(1) + DBLE(NPAR / IZERO)
      END
