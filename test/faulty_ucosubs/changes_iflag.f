C rollcon test data: a one-variable UCOSUB, F = Z - PAR(2) for the
C part PAR(1) (code 13), with one planted fault. Checked as
C --ucon 1:3,0.25 (see test/unit/checker/test_check_findings.f90).
C FAULT: every evaluation call sets IFLAG to 5, an argument the
C routine may only read (rollcon passed it as a constant: the
C routine crashed with SIGSEGV).
C EXPECTED FINDING: UCON/1 [changed-argument] IFLAG, from 0 to 5.
C
      SUBROUTINE UCOSUB(ID, TIME, Q, PAR, NPAR, IDRSEL, IFLAG, SCALAR,
     &      ARRAY, XMATRX)
      IMPLICIT NONE
      INTEGER ID, NPAR, IDRSEL(3), IFLAG
      DOUBLE PRECISION TIME, Q(30), PAR(*), SCALAR, ARRAY(30),
     &      XMATRX(30, 30)
      INTEGER LPARTS(1), LVARS(1)
      IF (IFLAG .EQ. 3) THEN
         LPARTS(1) = NINT(PAR(1))
         LVARS(1) = 13
         CALL UCOVAR(ID, 1, LPARTS, 1, LVARS)
         RETURN
      END IF
      IF (IDRSEL(1) .EQ. 1) SCALAR = Q(1) - PAR(2)
      IF (IDRSEL(2) .EQ. 1) ARRAY(1) = 1.0D0
      IFLAG = 5
      RETURN
      END
