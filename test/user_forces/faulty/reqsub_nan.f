C     rollcon test data (suite user-forces): the REQSUB of ../request_measures.f cut to its
C     displacement, with one planted fault, run on ../request.adm
C     (test/unit/job/test_user_forces.f90).
C     FAULT: a NaN returned in RESULT(3) once the run is under way (0/0 at TIME > 0.1).
C     EXPECTED: the error: REQUEST/7's REQSUB returned RESULT = (..., NaN, ...) at TIME = ...
      SUBROUTINE REQSUB(ID, TIME, PAR, NPAR, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(8)
      LOGICAL IFLAG
      INTEGER IPAR(3), NSTATE, IZERO
      DOUBLE PRECISION DISP(3)
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      IPAR(3) = NINT(PAR(2))
      CALL SYSARY('TDISP', IPAR, 3, DISP, NSTATE, ERRFLG)
C     PAR(2) - 2 is zero: a divisor the compiler cannot see
      IZERO = NINT(PAR(2)) - 2
      RESULT(2) = DISP(1)
      RESULT(3) = DISP(2)
      RESULT(4) = DISP(3)
      IF (TIME .GT. 0.1D0) RESULT(3) = DBLE(IZERO)/DBLE(IZERO)
      END
