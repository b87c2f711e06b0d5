C rollcon test data: a one-variable UCOSUB, F = Z - PAR(2) for the
C part PAR(1) (code 13), with one planted fault. Checked as
C --ucon 1:3,0.25 (see test/unit/isolation/test_isolation.f90).
C FAULT: an endless loop in the evaluation call.
C EXPECTED FINDING: UCON/1 [timeout] inside the call IFLAG = 0,
C IDRSEL = (1, 1, 1) at state 1, after the time limit.
C
      SUBROUTINE UCOSUB(ID, TIME, Q, PAR, NPAR, IDRSEL, IFLAG, SCALAR,
     &      ARRAY, XMATRX)
      IMPLICIT NONE
      INTEGER ID, NPAR, IDRSEL(3), IFLAG
      DOUBLE PRECISION TIME, Q(30), PAR(*), SCALAR, ARRAY(30),
     &      XMATRX(30, 30)
      INTEGER LPARTS(1), LVARS(1), IZERO
      IF (IFLAG .EQ. 3) THEN
         LPARTS(1) = NINT(PAR(1))
         LVARS(1) = 13
         CALL UCOVAR(ID, 1, LPARTS, 1, LVARS)
         RETURN
      END IF
C     Q(2:30) hold zeros: an index or divisor the compiler cannot see.
      IZERO = NINT(Q(30))
      IF (IDRSEL(1) .EQ. 1) SCALAR = Q(1) - PAR(2)
      IF (IDRSEL(2) .EQ. 1) ARRAY(1) = 1.0D0
   20 IF (Q(1) .EQ. Q(1)) GO TO 20
      RETURN
      END
