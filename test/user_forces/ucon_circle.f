C     A part's centre held on a circle of radius R = PAR(2) about ground
C     Z, at position level: F = X**2 + Y**2 - R**2 = 0 (PAR(1): the
C     part's id). Named by ROUTINE=ucon_circle::CIRCLE; UCOSUB's calling
C     sequence.
      SUBROUTINE CIRCLE(ID, TIME, Q, PAR, NPAR, IDRSEL, IFLAG, SCALAR,
     &      ARRAY, XMATRX)
      IMPLICIT NONE
      INTEGER ID, NPAR, IDRSEL(3), IFLAG
      DOUBLE PRECISION TIME, Q(30), PAR(*), SCALAR, ARRAY(30),
     &      XMATRX(30, 30)
      INTEGER IPARTS(2), ICODES(2)
      DATA ICODES /11, 12/
      IF (IFLAG .EQ. 3) THEN
         IPARTS(1) = NINT(PAR(1))
         IPARTS(2) = NINT(PAR(1))
         CALL UCOVAR(ID, 2, IPARTS, 2, ICODES)
         RETURN
      END IF
      IF (IDRSEL(1) .EQ. 1) SCALAR = Q(1)**2 + Q(2)**2 - PAR(2)**2
      IF (IDRSEL(2) .EQ. 1) THEN
         ARRAY(1) = 2.0D0*Q(1)
         ARRAY(2) = 2.0D0*Q(2)
      END IF
      IF (IDRSEL(3) .EQ. 1) THEN
         XMATRX(1, 1) = 2.0D0
         XMATRX(2, 2) = 2.0D0
      END IF
      RETURN
      END
