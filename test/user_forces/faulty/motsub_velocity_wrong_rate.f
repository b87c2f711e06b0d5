C     rollcon test routine (suite user-forces): motsub_rates.f's VELOCITY MOTSUB with its
C     IORD = 1 value off by 1: not the TIME derivative of its IORD = 0 value, which the
C     run's start check must find.
      SUBROUTINE MOTSUB(ID, TIME, PAR, NPAR, IORD, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR, IORD
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL IFLAG
      IF (IFLAG) RETURN
      VALUE = 0.0D0
      IF (IORD .EQ. 0) THEN
         VALUE = PAR(1)*COS(PAR(2)*TIME)
      ELSE IF (IORD .EQ. 1) THEN
         VALUE = PAR(1)*(-SIN(PAR(2)*TIME)*PAR(2)) + 1.0D0
      ELSE
         CALL ERRMES(.TRUE., 'IORD not asked of this motion', ID,
     &               'STOP')
      END IF
      END
