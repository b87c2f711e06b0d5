C SPDX-License-Identifier: MIT
C     Runs a generated ucosub.f on cases read from standard input and
C     prints every output at full precision, for the "fixed-form" test
C     of test/unit/ucosubs/generated/test_generated.f90 to compare with
C     the module.
C
C     Input (list-directed): NCASE, then for each case
C       ID IFLAG NPAR NQ
C       IDRSEL(1) IDRSEL(2) IDRSEL(3)
C       TIME
C       PAR(1) ... PAR(NPAR)
C       Q(1) ... Q(NQ)
C     Output, for each case, one record each:
C       NERR IDERR NDECL IDDECL NOUT   (ERRMES calls and the ID given
C                                       to the first; variables UCOVAR
C                                       declared and the ID given;
C                                       outputs written outside the
C                                       NQ x NQ block)
C       the first ERRMES message (blank when none)
C       LPARTS(1..NDECL)
C       LVARS(1..NDECL)
C       SCALAR, ARRAY(1..NQ), XMATRX(1..NQ, 1..NQ) column by column,
C       one per record.
C     Every output starts as SENTIN, so an entry the routine leaves
C     untouched prints as SENTIN.
      PROGRAM DRIVER
      IMPLICIT NONE
      INTEGER NCASE, K, ID, IFLAG, NPAR, NQ, IDRSEL(3), I, J, NOUT
      DOUBLE PRECISION TIME, PAR(30), Q(30), SCALAR, ARRAY(30)
      DOUBLE PRECISION XMATRX(30, 30), SENTIN
      PARAMETER (SENTIN = 12345.0D0)
      INTEGER NERR, IDERR, NDECL, IDDECL, LP(30), LV(30)
      COMMON /STUBI/ NERR, IDERR, NDECL, IDDECL, LP, LV
      CHARACTER*240 ERRTXT
      COMMON /STUBC/ ERRTXT
C
      READ (5, *) NCASE
      DO 100 K = 1, NCASE
         READ (5, *) ID, IFLAG, NPAR, NQ
         READ (5, *) (IDRSEL(I), I = 1, 3)
         READ (5, *) TIME
         DO 10 I = 1, 30
            PAR(I) = 0.0D0
            Q(I) = 0.0D0
   10    CONTINUE
         READ (5, *) (PAR(I), I = 1, NPAR)
         READ (5, *) (Q(I), I = 1, NQ)
         NERR = 0
         IDERR = 0
         NDECL = 0
         IDDECL = 0
         ERRTXT = ' '
         SCALAR = SENTIN
         DO 30 J = 1, 30
            ARRAY(J) = SENTIN
            DO 20 I = 1, 30
               XMATRX(I, J) = SENTIN
   20       CONTINUE
   30    CONTINUE
         CALL UCOSUB(ID, TIME, Q, PAR, NPAR, IDRSEL, IFLAG, SCALAR,
     &               ARRAY, XMATRX)
         NOUT = 0
         DO 50 J = 1, 30
            IF (J .GT. NQ .AND. ARRAY(J) .NE. SENTIN) NOUT = NOUT + 1
            DO 40 I = 1, 30
               IF ((I .GT. NQ .OR. J .GT. NQ)
     &             .AND. XMATRX(I, J) .NE. SENTIN) NOUT = NOUT + 1
   40       CONTINUE
   50    CONTINUE
         WRITE (6, '(5I8)') NERR, IDERR, NDECL, IDDECL, NOUT
         WRITE (6, '(A)') ERRTXT
         WRITE (6, '(30I4)') (LP(I), I = 1, NDECL)
         WRITE (6, '(30I4)') (LV(I), I = 1, NDECL)
         WRITE (6, '(ES25.17)') SCALAR
         WRITE (6, '(ES25.17)') (ARRAY(I), I = 1, NQ)
         WRITE (6, '(ES25.17)') ((XMATRX(I, J), I = 1, NQ), J = 1, NQ)
  100 CONTINUE
      END
