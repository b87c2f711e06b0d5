C     rollcon test routines (suite force-measures): joint_friction.f's friction with the
C     joint's reaction in closed form. The centre of mass is at R = DX, DY(22, 10) from the
C     pivot, turning at W = WZ(20, 10); with the friction torque T about the pivot, Euler's
C     law there gives the angular acceleration A = ((R x M G)_Z + T)/(IZZ + M |R|^2), and
C     Newton's law the reaction F = M (A Z x R - W^2 R - G), G = (0, -PAR(4), 0). T =
C     -PAR(1) |F| W is solved by fixed-point iteration (a contraction: dT/dT = PAR(1) W M |R|
C     /(IZZ + M |R|^2) is about 0.1 here) to the last bits (REACTS).
C     SFOSUB: the friction torque T. DIFSUB: the reaction |F|, the rate of a DIFF
C     integrating it (variable_friction_twin.adm).
      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT(1)
      LOGICAL DFLAG, IFLAG
      DOUBLE PRECISION T, F
      CALL REACTS(ID, PAR, T, F)
      RESULT(1) = T
      END

      SUBROUTINE DIFSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL DFLAG, IFLAG
      DOUBLE PRECISION T
      CALL REACTS(ID, PAR, T, VALUE)
      END

C     The friction torque T and the reaction |F| at the state of the call (above).
      SUBROUTINE REACTS(ID, PAR, T, F)
      IMPLICIT NONE
      INTEGER ID
      DOUBLE PRECISION PAR(*), T, F
      INTEGER IPAR(2), K
      DOUBLE PRECISION RX, RY, W, M, IZZ, G, A, FX, FY, LAST
      LOGICAL ERRFLG
      IPAR(1) = 22
      IPAR(2) = 10
      CALL SYSFNC('DX', IPAR, 2, RX, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC DX failed', ID, 'STOP')
      CALL SYSFNC('DY', IPAR, 2, RY, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC DY failed', ID, 'STOP')
      IPAR(1) = 20
      CALL SYSFNC('WZ', IPAR, 2, W, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC WZ failed', ID, 'STOP')
      M = PAR(2)
      IZZ = PAR(3)
      G = PAR(4)
      T = 0.0D0
      DO 10 K = 1, 200
         LAST = T
         A = (-RX*M*G + T)/(IZZ + M*(RX**2 + RY**2))
         FX = M*(-A*RY - W**2*RX)
         FY = M*(A*RX - W**2*RY + G)
         T = -PAR(1)*SQRT(FX**2 + FY**2)*W
         IF (ABS(T - LAST) .LE. 1.0D-16*ABS(T)) GO TO 20
   10 CONTINUE
   20 A = (-RX*M*G + T)/(IZZ + M*(RX**2 + RY**2))
      FX = M*(-A*RY - W**2*RX)
      FY = M*(A*RX - W**2*RY + G)
      F = SQRT(FX**2 + FY**2)
      END
