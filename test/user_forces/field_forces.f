C     rollcon test routines (suite user-forces): the SFOSUB and GFOSUB of
C     field_forces.adm, reading the PAR lists that dataset gives them.
C
C     SFOSUB, SFORCE/2, TRANSLATION, FUNCTION = USER(I, J, K, C, L0):
C     a spring-damper along the line from marker J to marker I,
C     F = -K*(L - L0) - C*LDOT, L the distance, LDOT its rate, computed
C     from the displacement D and velocity V of I relative to J
C     (SYSARY TDISP, TVEL; ground axes): L = |D|, LDOT = D.V/L.
      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2), NSTATE
      DOUBLE PRECISION D(3), V(3), L, LDOT
      LOGICAL ERRFLG
      IF (NPAR .LT. 5) THEN
         CALL ERRMES(.TRUE., 'SFOSUB takes I, J, K, C, L0', ID, 'STOP')
      END IF
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSARY('TDISP', IPAR, 2, D, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY TDISP failed', ID, 'STOP')
      CALL SYSARY('TVEL', IPAR, 2, V, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY TVEL failed', ID, 'STOP')
      L = SQRT(D(1)**2 + D(2)**2 + D(3)**2)
      LDOT = (D(1)*V(1) + D(2)*V(2) + D(3)*V(3))/L
      RESULT = -PAR(3)*(L - PAR(5)) - PAR(4)*LDOT
      END
C
C     GFOSUB, GFORCE/1 (RM a ground marker), FUNCTION = USER(I, J, IR,
C     JR, X0, Y0, KX, CX, KY, CY, KZ, CZ, CR): a bushing that holds
C     the offset D of marker I from marker J, in ground axes, at
C     (X0, Y0, 0): force component k = -K_k*(D_k - D0_k) - C_k*V_k,
C     V the velocity of I relative to J (SYSARY TDISP, TVEL), with
C     (K, C) = (KX, CX), (KY, CY), (KZ, CZ) along ground X, Y, Z; and
C     a rotational damper on marker IR: torque -CR*W, W its angular
C     velocity in ground axes (SYSFNC WX, WY, WZ). JR, the rotational
C     pair's other marker, is not read: the torque's reaction lands on
C     JFLOAT (ground), so the damper acts on IR's rotation relative to
C     ground.
      SUBROUTINE GFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(6)
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2), IROT(1), NSTATE, K
      DOUBLE PRECISION D(3), V(3), W(3), D0(3)
      CHARACTER*2 WNAME(3)
      LOGICAL ERRFLG
      DATA WNAME /'WX', 'WY', 'WZ'/
      IF (NPAR .LT. 13) THEN
         CALL ERRMES(.TRUE., 'GFOSUB takes 13 constants', ID, 'STOP')
      END IF
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      IROT(1) = NINT(PAR(3))
      CALL SYSARY('TDISP', IPAR, 2, D, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY TDISP failed', ID, 'STOP')
      CALL SYSARY('TVEL', IPAR, 2, V, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY TVEL failed', ID, 'STOP')
      DO 10 K = 1, 3
         CALL SYSFNC(WNAME(K), IROT, 1, W(K), ERRFLG)
         CALL ERRMES(ERRFLG, 'SYSFNC W failed', ID, 'STOP')
   10 CONTINUE
      D0(1) = PAR(5)
      D0(2) = PAR(6)
      D0(3) = 0.0D0
      DO 20 K = 1, 3
         RESULT(K) = -PAR(5 + 2*K)*(D(K) - D0(K)) - PAR(6 + 2*K)*V(K)
         RESULT(3 + K) = -PAR(13)*W(K)
   20 CONTINUE
      END
