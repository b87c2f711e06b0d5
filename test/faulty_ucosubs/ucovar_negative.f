C rollcon test data: a one-variable UCOSUB, F = Z - PAR(2) for the
C part PAR(1) (code 13), with one planted mistake in its
C initialisation call. Checked as --ucon 1:3,0.25 (see
C test/unit/checker/test_check_reliability.f90).
C MISTAKE: UCOVAR is called with NPARTS = NVARS = -1.
C EXPECTED FINDING: [declaration] UCOVAR declares -1 variables
C (NVARS); no state is checked.
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
         CALL UCOVAR(ID, -1, LPARTS, -1, LVARS)
         RETURN
      END IF
      IF (IDRSEL(1) .EQ. 1) SCALAR = Q(1) - PAR(2)
      IF (IDRSEL(2) .EQ. 1) ARRAY(1) = 1.0D0
      RETURN
      END
