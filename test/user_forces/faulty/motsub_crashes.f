C     rollcon test data (suite user-forces): the MOTSUB of ../motsub_sine.f with one planted
C     fault, run on ../motion.adm (test/unit/job/test_user_forces.f90).
C     FAULT: a write through a wild index, VALUE(200000000), after the initialisation call.
C     EXPECTED: killed by SIGSEGV inside a MOTSUB call, the run stopped, MOTION/1 named.
      SUBROUTINE MOTSUB(ID, TIME, PAR, NPAR, IORD, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR, IORD
      DOUBLE PRECISION TIME, PAR(*), VALUE(*)
      LOGICAL IFLAG
      INTEGER IZERO
C     PAR(2) - 3 is zero: an index the compiler cannot see
      IZERO = NINT(PAR(2)) - 3
      VALUE(1) = PAR(1)*SIN(PAR(2)*TIME)
      IF (.NOT. IFLAG) VALUE(200000000 + IZERO) = 1.0D0
      END
