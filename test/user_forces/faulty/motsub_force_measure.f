C     rollcon test data (suite force-measures): the MOTSUB of ../motsub_sine.f with one
C     planted fault, run on ../motion.adm (test/unit/job/test_user_force_measures.f90).
C     FAULT: it reads the reaction of the pendulum's hinge, SYSFNC('FM') of markers 31 and
C     21, which a MOTSUB may not (ADAMS's rule: a MOTION is a function of TIME alone).
C     EXPECTED: refused before the run, MOTION/1 and its line named, with the call and the
C     rule.
      SUBROUTINE MOTSUB(ID, TIME, PAR, NPAR, IORD, IFLAG, VALUE)
      IMPLICIT NONE
      INTEGER ID, NPAR, IORD
      DOUBLE PRECISION TIME, PAR(*), VALUE
      LOGICAL IFLAG
      INTEGER IPAR(2)
      DOUBLE PRECISION REACTION
      LOGICAL ERRFLG
      IPAR(1) = 31
      IPAR(2) = 21
      CALL SYSFNC('FM', IPAR, 2, REACTION, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC FM failed', ID, 'STOP')
      VALUE = PAR(1)*SIN(PAR(2)*TIME) + 0.0D0*REACTION
      END
