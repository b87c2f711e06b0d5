C rollcon test data: the generated rolling-disk UCOSUB
C (ucon/adams/rolling_disk/ucosub.f) with one planted mistake.
C MISTAKE: every evaluation call writes PAR(10), an argument the
C routine may only read (ADAMS may pass it in read-only memory).
C EXPECTED FINDING: check: every UCON: [changed-argument] PAR(10)
C in every state; run (rollcon tipping_coin --ucosub): an error
C naming UCON/1 and 'the routine changed PAR(10) from 0.1 to 0.2'.
C
C     Rolling disk as an ADAMS UCOSUB. No slip, no penetration: the
C     disk's material point at the contact has zero velocity.
C
C     PAR(1): part id
C     PAR(2:9): codes 21 22 23 14 15 24 25 26
C     PAR(10): disk radius R [m], > 0
C     PAR(11): no-slip component: 1, 2 or 3
C     F1: X velocity of the disk's material point at the contact [m/s]
C     F2: Y velocity of the disk's material point at the contact [m/s]
C     F3: Z velocity of the disk's material point at the contact [m/s]
C
C     IFLAG = 3: declare the variables with UCOVAR. IFLAG = 0: evaluate
C     what IDRSEL selects. IDRSEL(1) = 0/1/2/3/4: nothing, F, f(t),
C     dF/dt, d2F/dt2 in SCALAR. IDRSEL(2) = 0/1/2: nothing, dF/dq,
C     d2F/dt dq in ARRAY. IDRSEL(3) = 0/1: nothing, d2F/dq dq (both
C     triangles) in XMATRX. Entries that are zero are left untouched:
C     the caller zeroes the outputs. Errors go to ERRMES.
C
      SUBROUTINE UCOSUB(ID, TIME, Q, PAR, NPAR, IDRSEL, IFLAG, SCALAR,
     &      ARRAY, XMATRX)
      IMPLICIT NONE
      INTEGER ID, NPAR, IDRSEL(3), IFLAG
      DOUBLE PRECISION TIME, Q(30), PAR(*), SCALAR, ARRAY(30),
     &      XMATRX(30, 30)
      INTEGER NVARS, NPARS
      PARAMETER (NVARS = 8, NPARS = 11)
      DOUBLE PRECISION BIG
      PARAMETER (BIG = 1.7976931348623157D308)
      INTEGER LPARTS(NVARS), LVARS(NVARS), IPART, I, ICOMP
      DOUBLE PRECISION XDOT, YDOT, ZDOT, PSI, THETA, PSIDOT, THETADOT,
     &      PHIDOT, RADIUS
      DOUBLE PRECISION CSE0, CSE1, CSE2, CSE3, CSE4, CSE5, CSE6, CSE7,
     &      CSE8, CSE9, CSE10, CSE11, CSE12, CSE13, CSE14, CSE15, CSE16,
     &      CSE17, CSE18, CSE19, CSE20, CSE21, CSE22, CSE23, CSE24,
     &      CSE25
      CHARACTER*120 MESAGE
      DATA LVARS /21, 22, 23, 14, 15, 24, 25, 26/
C
C     Check PAR: a bad entry is reported through ERRMES; outputs stay
C     untouched.
      IF (NPAR .LT. NPARS) THEN
         WRITE (MESAGE, '(A, I4)')
     &         'rolling disk needs NPAR >= 11 (part id, 8 '
     &         // 'codes, disk radius R, no-slip component), got '
     &         // 'NPAR =', NPAR
         GO TO 900
      END IF
      IF (PAR(1) .LT. 1.0D0 .OR. PAR(1) .GE. 2147483647.0D0
     &      .OR. PAR(1) .NE. AINT(PAR(1))) THEN
         WRITE (MESAGE, '(A, 1PE24.16)')
     &         'PAR(1) (part id) must be a positive whole '
     &         // 'number, got', PAR(1)
         GO TO 900
      END IF
      IPART = NINT(PAR(1))
      IF (PAR(2) .NE. 21.0D0) THEN
         WRITE (MESAGE, '(A, 1PE24.16)')
     &         'PAR(2) must be code 21 (codes 21 22 23 14 15 24 '
     &         // '25 26 in PAR(2:9)), got', PAR(2)
         GO TO 900
      END IF
      IF (PAR(3) .NE. 22.0D0) THEN
         WRITE (MESAGE, '(A, 1PE24.16)')
     &         'PAR(3) must be code 22 (codes 21 22 23 14 15 24 '
     &         // '25 26 in PAR(2:9)), got', PAR(3)
         GO TO 900
      END IF
      IF (PAR(4) .NE. 23.0D0) THEN
         WRITE (MESAGE, '(A, 1PE24.16)')
     &         'PAR(4) must be code 23 (codes 21 22 23 14 15 24 '
     &         // '25 26 in PAR(2:9)), got', PAR(4)
         GO TO 900
      END IF
      IF (PAR(5) .NE. 14.0D0) THEN
         WRITE (MESAGE, '(A, 1PE24.16)')
     &         'PAR(5) must be code 14 (codes 21 22 23 14 15 24 '
     &         // '25 26 in PAR(2:9)), got', PAR(5)
         GO TO 900
      END IF
      IF (PAR(6) .NE. 15.0D0) THEN
         WRITE (MESAGE, '(A, 1PE24.16)')
     &         'PAR(6) must be code 15 (codes 21 22 23 14 15 24 '
     &         // '25 26 in PAR(2:9)), got', PAR(6)
         GO TO 900
      END IF
      IF (PAR(7) .NE. 24.0D0) THEN
         WRITE (MESAGE, '(A, 1PE24.16)')
     &         'PAR(7) must be code 24 (codes 21 22 23 14 15 24 '
     &         // '25 26 in PAR(2:9)), got', PAR(7)
         GO TO 900
      END IF
      IF (PAR(8) .NE. 25.0D0) THEN
         WRITE (MESAGE, '(A, 1PE24.16)')
     &         'PAR(8) must be code 25 (codes 21 22 23 14 15 24 '
     &         // '25 26 in PAR(2:9)), got', PAR(8)
         GO TO 900
      END IF
      IF (PAR(9) .NE. 26.0D0) THEN
         WRITE (MESAGE, '(A, 1PE24.16)')
     &         'PAR(9) must be code 26 (codes 21 22 23 14 15 24 '
     &         // '25 26 in PAR(2:9)), got', PAR(9)
         GO TO 900
      END IF
      IF (.NOT. (PAR(10) .GT. 0.0D0 .AND. PAR(10) .LE. BIG)) THEN
         WRITE (MESAGE, '(A, 1PE24.16)')
     &         'PAR(10) (disk radius R [m]) must be positive '
     &         // 'and finite, got', PAR(10)
         GO TO 900
      END IF
      IF (PAR(11) .NE. 1.0D0 .AND. PAR(11) .NE. 2.0D0
     &      .AND. PAR(11) .NE. 3.0D0) THEN
         WRITE (MESAGE, '(A, 1PE24.16)')
     &         'PAR(11) (no-slip component) must be 1, 2 or 3, '
     &         // 'got', PAR(11)
         GO TO 900
      END IF
      ICOMP = NINT(PAR(11))
C
      IF (IFLAG .EQ. 3) THEN
         DO 10 I = 1, NVARS
            LPARTS(I) = IPART
   10    CONTINUE
         CALL UCOVAR(ID, NVARS, LPARTS, NVARS, LVARS)
         RETURN
      END IF
      IF (IFLAG .NE. 0) THEN
         MESAGE = 'IFLAG must be 3 (initialise) or 0 (evaluate)'
         GO TO 900
      END IF
      IF (IDRSEL(1) .LT. 0 .OR. IDRSEL(1) .GT. 4 .OR. IDRSEL(2) .LT. 0
     &      .OR. IDRSEL(2) .GT. 2 .OR. IDRSEL(3) .LT. 0
     &      .OR. IDRSEL(3) .GT. 1) THEN
         MESAGE = 'IDRSEL must be (0..4, 0..2, 0..1)'
         GO TO 900
      END IF
C
C     Common subexpressions of every output of every component.
      XDOT = Q(1)
      YDOT = Q(2)
      ZDOT = Q(3)
      PSI = Q(4)
      THETA = Q(5)
      PSIDOT = Q(6)
      THETADOT = Q(7)
      PHIDOT = Q(8)
      RADIUS = PAR(10)
      PAR(10) = 2.0D0*RADIUS
      CSE0 = COS(PSI)
      CSE1 = CSE0*RADIUS
      CSE2 = COS(THETA)
      CSE3 = CSE1*CSE2
      CSE4 = SIN(THETA)
      CSE5 = SIN(PSI)
      CSE6 = CSE5*RADIUS
      CSE7 = CSE4*CSE6
      CSE8 = CSE5*PHIDOT
      CSE9 = CSE2*CSE5
      CSE10 = CSE0*CSE4
      CSE11 = CSE10*THETADOT + CSE9*PSIDOT
      CSE12 = -RADIUS*(CSE11 + CSE8)
      CSE13 = -RADIUS*(CSE10*PSIDOT + CSE9*THETADOT)
      CSE14 = -CSE7
      CSE15 = CSE0*CSE2
      CSE16 = CSE15*PSIDOT - CSE4*CSE5*THETADOT
      CSE17 = CSE0*PHIDOT + CSE16
      CSE18 = -CSE15*THETADOT + CSE4*CSE5*PSIDOT
      CSE19 = CSE2*CSE6
      CSE20 = -CSE19
      CSE21 = CSE1*CSE4
      CSE22 = -CSE21
      CSE23 = CSE2*RADIUS
      CSE24 = CSE23*THETADOT
      CSE25 = CSE4*RADIUS
C
      IF (ICOMP .EQ. 1) THEN
         IF (IDRSEL(1) .EQ. 1) THEN
            SCALAR = CSE1*PHIDOT + CSE3*PSIDOT - CSE7*THETADOT + XDOT
         ELSE IF (IDRSEL(1) .EQ. 2 .OR. IDRSEL(1) .EQ. 3
     &         .OR. IDRSEL(1) .EQ. 4) THEN
            SCALAR = 0.0D0
         END IF
         IF (IDRSEL(2) .EQ. 1) THEN
            ARRAY(1) = 1.0D0
            ARRAY(4) = CSE12
            ARRAY(5) = CSE13
            ARRAY(6) = CSE3
            ARRAY(7) = CSE14
            ARRAY(8) = CSE1
         END IF
         IF (IDRSEL(3) .EQ. 1) THEN
            XMATRX(4, 4) = -CSE17*RADIUS
            XMATRX(4, 5) = CSE18*RADIUS
            XMATRX(5, 4) = XMATRX(4, 5)
            XMATRX(4, 6) = CSE20
            XMATRX(6, 4) = XMATRX(4, 6)
            XMATRX(4, 7) = CSE22
            XMATRX(7, 4) = XMATRX(4, 7)
            XMATRX(4, 8) = -CSE6
            XMATRX(8, 4) = XMATRX(4, 8)
            XMATRX(5, 5) = -CSE16*RADIUS
            XMATRX(5, 6) = CSE22
            XMATRX(6, 5) = XMATRX(5, 6)
            XMATRX(5, 7) = CSE20
            XMATRX(7, 5) = XMATRX(5, 7)
         END IF
C
      ELSE IF (ICOMP .EQ. 2) THEN
         IF (IDRSEL(1) .EQ. 1) THEN
            SCALAR = CSE19*PSIDOT + CSE21*THETADOT + CSE8*RADIUS + YDOT
         ELSE IF (IDRSEL(1) .EQ. 2 .OR. IDRSEL(1) .EQ. 3
     &         .OR. IDRSEL(1) .EQ. 4) THEN
            SCALAR = 0.0D0
         END IF
         IF (IDRSEL(2) .EQ. 1) THEN
            ARRAY(2) = 1.0D0
            ARRAY(4) = CSE17*RADIUS
            ARRAY(5) = -CSE18*RADIUS
            ARRAY(6) = CSE19
            ARRAY(7) = CSE21
            ARRAY(8) = CSE6
         END IF
         IF (IDRSEL(3) .EQ. 1) THEN
            XMATRX(4, 4) = CSE12
            XMATRX(4, 5) = CSE13
            XMATRX(5, 4) = XMATRX(4, 5)
            XMATRX(4, 6) = CSE3
            XMATRX(6, 4) = XMATRX(4, 6)
            XMATRX(4, 7) = CSE14
            XMATRX(7, 4) = XMATRX(4, 7)
            XMATRX(4, 8) = CSE1
            XMATRX(8, 4) = XMATRX(4, 8)
            XMATRX(5, 5) = -CSE11*RADIUS
            XMATRX(5, 6) = CSE14
            XMATRX(6, 5) = XMATRX(5, 6)
            XMATRX(5, 7) = CSE3
            XMATRX(7, 5) = XMATRX(5, 7)
         END IF
C
      ELSE IF (ICOMP .EQ. 3) THEN
         IF (IDRSEL(1) .EQ. 1) THEN
            SCALAR = -CSE24 + ZDOT
         ELSE IF (IDRSEL(1) .EQ. 2 .OR. IDRSEL(1) .EQ. 3
     &         .OR. IDRSEL(1) .EQ. 4) THEN
            SCALAR = 0.0D0
         END IF
         IF (IDRSEL(2) .EQ. 1) THEN
            ARRAY(3) = 1.0D0
            ARRAY(5) = CSE25*THETADOT
            ARRAY(7) = -CSE23
         END IF
         IF (IDRSEL(3) .EQ. 1) THEN
            XMATRX(5, 5) = CSE24
            XMATRX(5, 7) = CSE25
            XMATRX(7, 5) = XMATRX(5, 7)
         END IF
      END IF
      RETURN
C
  900 CALL ERRMES(.TRUE., MESAGE, ID, 'STOP')
      RETURN
      END
