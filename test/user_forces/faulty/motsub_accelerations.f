C     rollcon test data (suite user-forces): the MOTSUB of ../motsub_sine.f with one planted
C     fault, run on ../motion.adm (test/unit/job/test_user_forces.f90).
C     FAULT: it reads the pendulum's acceleration, SYSARY('TACC') of marker 31, which a
C     MOTSUB may not (ADAMS's rule: a MOTSUB calls no SYSFNC or SYSARY; a MOTION is a
C     function of TIME alone).
C     EXPECTED: refused before the run, MOTION/1 and its line named, with ADAMS's rule.
      SUBROUTINE MOTSUB(ID, TIME, PAR, NPAR, IORD, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR, IORD
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL IFLAG
      INTEGER IPAR(1), NSTATE
      DOUBLE PRECISION ACC(3)
      LOGICAL ERRFLG
      IPAR(1) = 31
      CALL SYSARY('TACC', IPAR, 1, ACC, NSTATE, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSARY TACC failed', ID, 'STOP')
      VALUE = PAR(1)*SIN(PAR(2)*TIME) + 0.0D0*ACC(1)
      END
