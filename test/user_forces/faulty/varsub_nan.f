C     rollcon test data (suite user-forces): the VARSUB of ../variable_stretch.f with one
C     planted fault, run on ../variable.adm (test/unit/job/test_user_forces.f90).
C     FAULT: a NaN returned once the run is under way (0/0 at TIME > 0.1).
C     EXPECTED: the error: VARIABLE/3's VARSUB returned VALUE = NaN at TIME = ...
      SUBROUTINE VARSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2), IZERO
      DOUBLE PRECISION DM
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSFNC('DM', IPAR, 2, DM, ERRFLG)
C     PAR(2) - 2 is zero: a divisor the compiler cannot see
      IZERO = NINT(PAR(2)) - 2
      VALUE = DM - PAR(3)
      IF (TIME .GT. 0.1D0) VALUE = DBLE(IZERO)/DBLE(IZERO)
      END
