C     rollcon test routine (suite user-forces): a MOTSUB for a VELOCITY MOTION (PAR(3) = 1:
C     f = PAR(1) COS(PAR(2) TIME), IORD = 0, and its TIME derivative, IORD = 1) or an
C     ACCELERATION MOTION (PAR(3) = 2: f = -PAR(1) SIN(PAR(2) TIME), IORD = 0). ADAMS asks
C     no other IORD of these motions: any other stops the run.
      SUBROUTINE MOTSUB(ID, TIME, PAR, NPAR, IORD, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR, IORD
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL IFLAG
      IF (IFLAG) RETURN
      VALUE = 0.0D0
      IF (NINT(PAR(3)) .EQ. 1 .AND. IORD .EQ. 0) THEN
         VALUE = PAR(1)*COS(PAR(2)*TIME)
      ELSE IF (NINT(PAR(3)) .EQ. 1 .AND. IORD .EQ. 1) THEN
         VALUE = PAR(1)*(-SIN(PAR(2)*TIME)*PAR(2))
      ELSE IF (NINT(PAR(3)) .EQ. 2 .AND. IORD .EQ. 0) THEN
         VALUE = -PAR(1)*SIN(PAR(2)*TIME)
      ELSE
         CALL ERRMES(.TRUE., 'IORD not asked of this motion', ID,
     &               'STOP')
      END IF
      END
