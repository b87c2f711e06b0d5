C     rollcon test routine (suite user-forces): a linear bushing GFOSUB holding marker
C     I = PAR(1) at the point (PAR(3), PAR(4), PAR(5)) of marker J = PAR(2), stiffness PAR(6),
C     damping PAR(7), and its axes along J's with rotational stiffness PAR(8) and damping
C     PAR(9) on the angles AX, AY, AZ: SYSARY's TDISP, TVEL and RVEL, SYSFNC's AX, AY, AZ.
      SUBROUTINE GFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(6)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(4), NSTATE, K
      DOUBLE PRECISION DISP(3), VEL(3), OMEGA(3), ANGLE(3)
      CHARACTER*2 ANAME(3)
      LOGICAL ERRFLG
      DATA ANAME /'AX', 'AY', 'AZ'/
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      IPAR(3) = NINT(PAR(2))
      IPAR(4) = NINT(PAR(2))
      CALL SYSARY('TDISP', IPAR, 3, DISP, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY TDISP failed', ID, 'STOP')
      CALL SYSARY('TVEL', IPAR, 4, VEL, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY TVEL failed', ID, 'STOP')
      CALL SYSARY('RVEL', IPAR, 3, OMEGA, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY RVEL failed', ID, 'STOP')
      DO 10 K = 1, 3
         CALL SYSFNC(ANAME(K), IPAR, 2, ANGLE(K), ERRFLG)
         CALL ERRMES(ERRFLG, 'SYSFNC A failed', ID, 'STOP')
   10 CONTINUE
      DO 20 K = 1, 3
         RESULT(K) = -PAR(6)*(DISP(K) - PAR(2 + K)) - PAR(7)*VEL(K)
         RESULT(3 + K) = -PAR(8)*ANGLE(K) - PAR(9)*OMEGA(K)
   20 CONTINUE
      END
