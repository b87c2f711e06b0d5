C     rollcon test routine (suite user-routine-check): diff_lag.f's DIFSUB (explicit) with
C     hidden state, as `rollcon check` must report it: a SAVEd call counter adds +-1e-3 to
C     the rate at each call, so the same state gives another VALUE each time.
      SUBROUTINE DIFSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR, CALLS
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(1)
      DOUBLE PRECISION DX, DIF
      LOGICAL ERRFLG
      SAVE CALLS
      DATA CALLS /0/
      IPAR(1) = NINT(PAR(1))
      CALL SYSFNC('DX', IPAR, 1, DX, ERRFLG)
      IPAR(1) = ID
      CALL SYSFNC('DIF', IPAR, 1, DIF, ERRFLG)
      CALLS = CALLS + 1
      VALUE = (DX - DIF)/PAR(2) + 1.0D-3*(-1)**CALLS
      END
