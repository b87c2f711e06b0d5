C     A part carried by a turntable turning at W = PAR(2) rad/s about
C     ground Z, at velocity level: component PAR(3) = 1 is
C     F = Xdot + W*Y, component 2 is F = Ydot - W*X. PAR(1): part id.
C     SLIPPED: dF/dY and dF/dX are returned as half their value (a
C     Coriolis factor 2 lost), F itself right.
      SUBROUTINE UCOSUB(ID, TIME, Q, PAR, NPAR, IDRSEL, IFLAG, SCALAR,
     &      ARRAY, XMATRX)
      IMPLICIT NONE
      INTEGER ID, NPAR, IDRSEL(3), IFLAG
      DOUBLE PRECISION TIME, Q(30), PAR(*), SCALAR, ARRAY(30),
     &      XMATRX(30, 30)
      INTEGER IPARTS(4), ICODES(4), K
      DOUBLE PRECISION W
      DATA ICODES /11, 12, 21, 22/
      IF (IFLAG .EQ. 3) THEN
         DO 10 K = 1, 4
            IPARTS(K) = NINT(PAR(1))
   10    CONTINUE
         CALL UCOVAR(ID, 4, IPARTS, 4, ICODES)
         RETURN
      END IF
      W = PAR(2)
      IF (NINT(PAR(3)) .EQ. 1) THEN
         IF (IDRSEL(1) .EQ. 1) SCALAR = Q(3) + W*Q(2)
         IF (IDRSEL(2) .EQ. 1) THEN
            ARRAY(2) = 0.5D0*W
            ARRAY(3) = 1.0D0
         END IF
      ELSE
         IF (IDRSEL(1) .EQ. 1) SCALAR = Q(4) - W*Q(1)
         IF (IDRSEL(2) .EQ. 1) THEN
            ARRAY(1) = -0.5D0*W
            ARRAY(4) = 1.0D0
         END IF
      END IF
      RETURN
      END
