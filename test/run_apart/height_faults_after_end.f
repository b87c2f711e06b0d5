C rollcon test data (the test suite run-apart): F = Z - PAR(2) for
C the part PAR(1) (code 13), the height of a ball of radius PAR(2)
C resting on the ground, correct at every time of the run; called at
C TIME > 0.5 s (after resting_ball.adm's END) it faults: an integer
C division by zero (SIGFPE). A run calls a user's routine only at its
C own states and times: the run completes.
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
C     Q(2:30) hold zeros: a divisor the compiler cannot see.
      IZERO = NINT(Q(30))
      IF (IDRSEL(1) .EQ. 1) SCALAR = Q(1) - PAR(2)
      IF (TIME .GT. 0.5D0) SCALAR = SCALAR + DBLE(NPAR / IZERO)
      IF (IDRSEL(1) .EQ. 2) SCALAR = -PAR(2)
      IF (IDRSEL(2) .EQ. 1) ARRAY(1) = 1.0D0
      RETURN
      END
