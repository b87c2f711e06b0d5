C     rollcon test routine (suite user-forces): an SFOSUB between markers PAR(1) and PAR(2)
C     calling the utilities AKISPL, CUBSPL, STEP and RCNVRT: the spring force of SPLINE/PAR(3)
C     at the stretch DM - PAR(5) (Akima's fit, its slope from CUBSPL's curve times PAR(8)),
C     brought in by STEP(TIME, 0, 0, PAR(6), 1), damping PAR(4) on VR, and PAR(7) times the
C     square of the first Euler parameter of PAR(1)'s axes in PAR(2)'s (RDISP through
C     RCNVRT from EULER to EULPAR). utilities_expressions.adm writes the same force.
      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2), NSTATE, ISTAT
      DOUBLE PRECISION DM, VR, ANGLES(3), E(4), SPRING(3), SLOPE(3)
      DOUBLE PRECISION RAMP
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSFNC('DM', IPAR, 2, DM, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC DM failed', ID, 'STOP')
      CALL SYSFNC('VR', IPAR, 2, VR, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC VR failed', ID, 'STOP')
      CALL SYSARY('RDISP', IPAR, 2, ANGLES, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY RDISP failed', ID, 'STOP')
      CALL RCNVRT('EULER', ANGLES, 'EULPAR', E, ISTAT)
      CALL ERRMES(ISTAT .NE. 0, 'RCNVRT failed', ID, 'STOP')
      CALL AKISPL(DM - PAR(5), 0.0D0, NINT(PAR(3)), 0, SPRING, ERRFLG)
      CALL ERRMES(ERRFLG, 'AKISPL failed', ID, 'STOP')
      CALL CUBSPL(DM - PAR(5), 0.0D0, NINT(PAR(3)), 1, SLOPE, ERRFLG)
      CALL ERRMES(ERRFLG, 'CUBSPL failed', ID, 'STOP')
      CALL STEP(TIME, 0.0D0, 0.0D0, PAR(6), 1.0D0, 0, RAMP, ERRFLG)
      CALL ERRMES(ERRFLG, 'STEP failed', ID, 'STOP')
      RESULT = -SPRING(1)*RAMP - PAR(8)*SLOPE(1) - PAR(4)*VR
     &         + PAR(7)*E(1)**2
      END
