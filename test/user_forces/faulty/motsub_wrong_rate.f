C     rollcon test data (suite user-forces): the MOTSUB of ../motsub_sine.f with one planted
C     fault, run on ../motion.adm (test/unit/job/test_user_forces.f90).
C     FAULT: IORD = 1 returns twice the rate of the displacement IORD = 0 returns.
C     EXPECTED: the start check names MOTION/1, IORD = 1, the value returned (3 at TIME = 0)
C     and the differences' value (1.5).
      SUBROUTINE MOTSUB(ID, TIME, PAR, NPAR, IORD, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR, IORD
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL IFLAG
      IF (IFLAG) RETURN
      IF (IORD .EQ. 0) THEN
         VALUE = PAR(1)*SIN(PAR(2)*TIME)
      ELSE IF (IORD .EQ. 1) THEN
         VALUE = 2.0D0*PAR(1)*(COS(PAR(2)*TIME)*PAR(2))
      ELSE
         VALUE = PAR(1)*(-SIN(PAR(2)*TIME)*PAR(2)*PAR(2))
      END IF
      END
