C     rollcon test routine (suite user-forces): a MOTSUB, the displacement PAR(1) SIN(PAR(2)
C     TIME) and its first and second TIME derivatives (IORD = 0, 1, 2).
      SUBROUTINE MOTSUB(ID, TIME, PAR, NPAR, IORD, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR, IORD
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL IFLAG
      IF (IFLAG) RETURN
      IF (IORD .EQ. 0) THEN
         VALUE = PAR(1)*SIN(PAR(2)*TIME)
      ELSE IF (IORD .EQ. 1) THEN
         VALUE = PAR(1)*(COS(PAR(2)*TIME)*PAR(2))
      ELSE
         VALUE = PAR(1)*(-SIN(PAR(2)*TIME)*PAR(2)*PAR(2))
      END IF
      END
