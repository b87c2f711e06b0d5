C     rollcon test data (suite user-forces): the lag DIFSUB of ../diff_lag.f (explicit form)
C     with one planted fault, run on a lag dataset (test/unit/job/test_user_forces.f90).
C     FAULT: a write through a wild index of PAR after the initialisation
C     call.
C     EXPECTED: killed by SIGSEGV inside a DIFSUB call, the run stopped, the DIFF named.
      SUBROUTINE DIFSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(1), IZERO
      DOUBLE PRECISION DX, DIF
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      CALL SYSFNC('DX', IPAR, 1, DX, ERRFLG)
      IPAR(1) = ID
      CALL SYSFNC('DIF', IPAR, 1, DIF, ERRFLG)
C     PAR(1) - 20 is zero: an index the compiler cannot see
      IZERO = NINT(PAR(1)) - 20
      VALUE = (DX - DIF)/PAR(2)
      IF (.NOT. IFLAG) PAR(200000000 + IZERO) = VALUE
      END
