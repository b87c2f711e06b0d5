C     rollcon test data (suite user-forces): the torsional spring-damper VTOSUB of
C     ../vtorque_spring.f cut to its stiffness, with one planted fault, run on ../vtorque.adm
C     (test/unit/job/test_user_forces.f90).
C     FAULT: a NaN returned in TY once the run is under way (0/0 at TIME > 0.1).
C     EXPECTED: the error: VTORQUE/5's VTOSUB returned RESULT = (..., NaN, ...) at TIME = ...
      SUBROUTINE VTOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(3)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2), IZERO
      DOUBLE PRECISION ANGLE(3)
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSFNC('AX', IPAR, 2, ANGLE(1), ERRFLG)
      CALL SYSFNC('AY', IPAR, 2, ANGLE(2), ERRFLG)
      CALL SYSFNC('AZ', IPAR, 2, ANGLE(3), ERRFLG)
C     PAR(2) - 2 is zero: a divisor the compiler cannot see
      IZERO = NINT(PAR(2)) - 2
      RESULT(1) = -PAR(3)*ANGLE(1)
      RESULT(2) = -PAR(3)*ANGLE(2)
      RESULT(3) = -PAR(3)*ANGLE(3)
      IF (TIME .GT. 0.1D0) RESULT(2) = DBLE(IZERO)/DBLE(IZERO)
      END
