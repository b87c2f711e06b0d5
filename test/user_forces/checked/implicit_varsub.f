C     rollcon test data (suite user-routine-check): a VARSUB written without IMPLICIT NONE, the
C     stretch of a spring from marker PAR(2) to PAR(1) of free length PAR(3), with a slip of
C     implicit typing `rollcon check` must report: LFREE (a name from I to N: INTEGER)
C     receives the free length PAR(3) and is truncated (../variable.adm: 1.0 stays 1, so a run
C     cannot tell; 1.5 would be 1).
C     EXPECTED: one [typing] finding, naming line 15 and SUBROUTINE VARSUB
      SUBROUTINE VARSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), VALUE, D(3)
      LOGICAL DFLAG, IFLAG, ERRFLG
      INTEGER MARKS(2), NSTATE
      MARKS(1) = NINT(PAR(1))
      MARKS(2) = NINT(PAR(2))
      CALL SYSARY('TDISP', MARKS, 2, D, NSTATE, ERRFLG)
      LFREE = PAR(3)
      VALUE = SQRT(D(1)**2 + D(2)**2 + D(3)**2) - LFREE
      END
