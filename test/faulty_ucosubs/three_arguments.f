C rollcon test data: a UCOSUB written with three arguments, as if
C for another ADAMS interface. Checked as --ucon 1:3,0.25 (see
C test/unit/checker/test_check_reliability.f90).
C MISTAKE: SUBROUTINE UCOSUB(ID, TIME, Q): rollcon passes ten
C arguments, the routine sees three, never calls UCOVAR and writes
C nothing.
C EXPECTED FINDING: [declaration] the initialisation call made no
C UCOVAR call; no state is checked.
C
      SUBROUTINE UCOSUB(ID, TIME, Q)
      IMPLICIT NONE
      INTEGER ID
      DOUBLE PRECISION TIME, Q(30)
      RETURN
      END
