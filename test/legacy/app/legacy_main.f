C     SPDX-License-Identifier: MIT
C     A FORTRAN 77 host program: implicit typing, no modules, the ADAMS
C     argument list. It links the hand-checked UCOSUB of the rollcon
C     library, supplies its own UCOVAR (as a host solver does) and reads
C     the library's error channel with UCOERR. Prints N passed, N failed.
      PROGRAM LEGACY
      IMPLICIT DOUBLE PRECISION (A-H, O-Z)
      IMPLICIT INTEGER (I-N)
      DIMENSION Q(30), PAR(11), ARRAY(30), XMATRX(30,30), IDRSEL(3)
      DIMENSION LWANT(8)
      CHARACTER*200 MESAGE
      COMMON /HOSTDC/ NCALLS, IDDECL, NDECL, LPDECL(30), LVDECL(30)
      DATA PAR /5.0D0, 21.0D0, 22.0D0, 23.0D0, 14.0D0, 15.0D0, 24.0D0,
     &          25.0D0, 26.0D0, 0.1D0, 1.0D0/
      DATA LWANT /21, 22, 23, 14, 15, 24, 25, 26/
      NPASS = 0
      NFAIL = 0
      NCALLS = 0
      DO 10 I = 1, 30
         Q(I) = 0.0D0
   10 CONTINUE
C
C     1. Initialisation call: UCOVAR (ours, below) gets the 8 variables
C        of part 5 under UCON id 2.
      CALL UCOSUB(2, 0.0D0, Q, PAR, 11, IDRSEL, 3, SCALAR, ARRAY,
     &            XMATRX)
      IOK = 1
      IF (NCALLS .NE. 1 .OR. IDDECL .NE. 2 .OR. NDECL .NE. 8) IOK = 0
      DO 20 I = 1, 8
         IF (LPDECL(I) .NE. 5 .OR. LVDECL(I) .NE. LWANT(I)) IOK = 0
   20 CONTINUE
      CALL REPORT('initialisation declares 8 variables', IOK,
     &            NPASS, NFAIL)
C
C     2. Evaluation at psi = 0: F1 = XDOT + R*(PHIDOT + PSIDOT*COS(TH)),
C        dF1/dXDOT = 1, dF1/dPHIDOT = R.
      Q(1) = 0.3D0
      Q(5) = 1.1D0
      Q(6) = 2.0D0
      Q(7) = -0.7D0
      Q(8) = -3.0D0
      SCALAR = 0.0D0
      DO 30 I = 1, 30
         ARRAY(I) = 0.0D0
   30 CONTINUE
      IDRSEL(1) = 1
      IDRSEL(2) = 1
      IDRSEL(3) = 0
      CALL UCOSUB(2, 0.0D0, Q, PAR, 11, IDRSEL, 0, SCALAR, ARRAY,
     &            XMATRX)
      FWANT = Q(1) + PAR(10)*(Q(8) + Q(6)*COS(Q(5)))
      IOK = 1
      IF (ABS(SCALAR - FWANT) .GT. 1.0D-15) IOK = 0
      IF (ARRAY(1) .NE. 1.0D0 .OR. ARRAY(8) .NE. PAR(10)) IOK = 0
      CALL REPORT('F1 and its partials at psi = 0', IOK, NPASS, NFAIL)
C
C     3. A negative radius comes back through UCOERR, not as a crash.
      PAR(10) = -1.0D0
      CALL UCOSUB(2, 0.0D0, Q, PAR, 11, IDRSEL, 0, SCALAR, ARRAY,
     &            XMATRX)
      CALL UCOERR(IERR, MESAGE)
      IOK = 1
      IF (IERR .EQ. 0 .OR. INDEX(MESAGE, 'PAR(10)') .EQ. 0) IOK = 0
      CALL REPORT('bad PAR reported through UCOERR', IOK, NPASS, NFAIL)
      CALL UCOERR(IERR, MESAGE)
      IOK = 1
      IF (IERR .NE. 0) IOK = 0
      CALL REPORT('UCOERR clears the error', IOK, NPASS, NFAIL)
C
      WRITE (*, '(I0, A, I0, A)') NPASS, ' passed, ', NFAIL, ' failed'
      IF (NFAIL .GT. 0) STOP 1
      END
C
C     The host's UCOVAR: records the declaration in COMMON.
      SUBROUTINE UCOVAR(ID, NPARTS, LPARTS, NVARS, LVARS)
      IMPLICIT INTEGER (A-Z)
      DIMENSION LPARTS(*), LVARS(*)
      COMMON /HOSTDC/ NCALLS, IDDECL, NDECL, LPDECL(30), LVDECL(30)
      NCALLS = NCALLS + 1
      IDDECL = ID
      NDECL = MIN(NVARS, NPARTS, 30)
      DO 10 I = 1, NDECL
         LPDECL(I) = LPARTS(I)
         LVDECL(I) = LVARS(I)
   10 CONTINUE
      RETURN
      END
C
      SUBROUTINE REPORT(NAME, IOK, NPASS, NFAIL)
      CHARACTER*(*) NAME
      INTEGER IOK, NPASS, NFAIL
      IF (IOK .EQ. 1) THEN
         NPASS = NPASS + 1
         WRITE (*, '(2A)') '  PASS legacy/', NAME
      ELSE
         NFAIL = NFAIL + 1
         WRITE (*, '(2A)') '  FAIL legacy/', NAME
      END IF
      RETURN
      END
