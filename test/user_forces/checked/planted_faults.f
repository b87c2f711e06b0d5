C     rollcon test data (suite user-routine-check): a VARSUB and a REQSUB with one planted
C     fault each, chosen by PAR(4), for `rollcon check FILE --model` on ../variable.adm and
C     ../request.adm with a fourth constant (test/unit/checker/test_user_routine_check.f90).
C     VALUE, and the REQSUB's RESULT(2:4), are marker PAR(1)'s displacement from marker
C     PAR(2) (SYSARY's TDISP; VALUE its magnitude less PAR(3)), plus what FAULTS adds:
C     PAR(4) = 1: a SAVEd call counter, 1e-3 a call     EXPECTED: [hidden state], each state
C     PAR(4) = 2: 0/0 once TIME > 0.1                   EXPECTED: [finite], once
C     PAR(4) = 3: SIGN(0.1, VZ), Coulomb's friction      EXPECTED: [jump] of 0.2
C     PAR(4) = 4: SYSARY('TVEL') read outside the initialisation call, 0 times its value
C                                                       EXPECTED: [declaration], once
      SUBROUTINE VARSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL DFLAG, IFLAG
      DOUBLE PRECISION D(3), EXTRA
      CALL FAULTS(TIME, PAR, IFLAG, D, EXTRA)
      VALUE = SQRT(D(1)**2 + D(2)**2 + D(3)**2) - PAR(3) + EXTRA
      END

      SUBROUTINE REQSUB(ID, TIME, PAR, NPAR, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(8)
      LOGICAL IFLAG
      DOUBLE PRECISION EXTRA
      CALL FAULTS(TIME, PAR, IFLAG, RESULT(2), EXTRA)
      RESULT(4) = RESULT(4) + EXTRA
      END

C     DISP(3): TDISP of markers PAR(1), PAR(2); EXTRA: the fault PAR(4) plants
      SUBROUTINE FAULTS(TIME, PAR, IFLAG, DISP, EXTRA)
      IMPLICIT NONE
      DOUBLE PRECISION TIME, PAR(*), DISP(3), EXTRA
      LOGICAL IFLAG
      INTEGER IPAR(2), NSTATE, CALLS, IZERO, FAULT
      DOUBLE PRECISION VZ, VELOCITY(3)
      LOGICAL ERRFLG
      SAVE CALLS
      DATA CALLS /0/
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSARY('TDISP', IPAR, 2, DISP, NSTATE, ERRFLG)
      FAULT = NINT(PAR(4))
      EXTRA = 0.0D0
      IF (FAULT .EQ. 1) THEN
          CALLS = CALLS + 1
          EXTRA = 1.0D-3*CALLS
      ELSE IF (FAULT .EQ. 2) THEN
C         PAR(2) - 2 is zero: a divisor the compiler cannot see
          IZERO = NINT(PAR(2)) - 2
          IF (TIME .GT. 0.1D0) EXTRA = DBLE(IZERO)/DBLE(IZERO)
      ELSE IF (FAULT .EQ. 3) THEN
          CALL SYSFNC('VZ', IPAR, 2, VZ, ERRFLG)
          EXTRA = SIGN(0.1D0, VZ)
      ELSE IF (FAULT .EQ. 4 .AND. .NOT. IFLAG) THEN
          CALL SYSARY('TVEL', IPAR, 2, VELOCITY, NSTATE, ERRFLG)
          EXTRA = 0.0D0*VELOCITY(1)
      END IF
      END
