C     rollcon test data (suite user-forces): the MOTSUB of ../motsub_sine.f with one planted
C     fault, run on ../motion.adm (test/unit/job/test_user_forces.f90).
C     FAULT: its initialisation call declares a dependence on the state, SYSFNC('DX') of the
C     pendulum's hinge, which a MOTION (a function of TIME alone) may not read.
C     EXPECTED: refused before the run, MOTION/1 and its line named, with the markers read.
      SUBROUTINE MOTSUB(ID, TIME, PAR, NPAR, IORD, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR, IORD
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL IFLAG
      INTEGER IPAR(2)
      DOUBLE PRECISION DX
      LOGICAL ERRFLG
      IPAR(1) = 31
      IPAR(2) = 1
      IF (IFLAG) THEN
         CALL SYSFNC('DX', IPAR, 2, DX, ERRFLG)
         RETURN
      END IF
      VALUE = PAR(1)*SIN(PAR(2)*TIME)
      END
