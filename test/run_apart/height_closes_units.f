C rollcon test data (the test suite run-apart): F = Z - PAR(2)
C for the part PAR(1) (code 13), the height of a ball of radius PAR(2)
C resting on the ground, correct in every call; in its initialisation
C call it also closes the units 0, 5 and 6 (stderr, stdin, stdout).
C The run computes in a child process and rollcon itself writes every
C output: the run completes, its outputs where they were asked for.
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
         CLOSE(6)
         CLOSE(0)
         CLOSE(5)
         RETURN
      END IF
      IF (IDRSEL(1) .EQ. 1) SCALAR = Q(1) - PAR(2)
      IF (IDRSEL(1) .EQ. 2) SCALAR = -PAR(2)
      IF (IDRSEL(2) .EQ. 1) ARRAY(1) = 1.0D0
      RETURN
      END
