C     A part carried round ground Z at W = PAR(2) rad/s, the velocity
C     half of it: F = Xdot + W*Y = 0 (PAR(1): the part's id). Its name
C     is its own (TURNVEL), named by ROUTINE=ucon_turn_velocity::TURNVEL,
C     with UCOSUB's calling sequence; the file defines no UCOSUB, so only
C     that ROUTINE= can use it.
      SUBROUTINE TURNVEL(ID, TIME, Q, PAR, NPAR, IDRSEL, IFLAG, SCALAR,
     &      ARRAY, XMATRX)
      IMPLICIT NONE
      INTEGER ID, NPAR, IDRSEL(3), IFLAG
      DOUBLE PRECISION TIME, Q(30), PAR(*), SCALAR, ARRAY(30),
     &      XMATRX(30, 30)
      INTEGER IPARTS(2), ICODES(2)
      DATA ICODES /12, 21/
      IF (IFLAG .EQ. 3) THEN
         IPARTS(1) = NINT(PAR(1))
         IPARTS(2) = NINT(PAR(1))
         CALL UCOVAR(ID, 2, IPARTS, 2, ICODES)
         RETURN
      END IF
C     Q(1) = Y, Q(2) = Xdot
      IF (IDRSEL(1) .EQ. 1) SCALAR = Q(2) + PAR(2)*Q(1)
      IF (IDRSEL(2) .EQ. 1) THEN
         ARRAY(1) = PAR(2)
         ARRAY(2) = 1.0D0
      END IF
      RETURN
      END
