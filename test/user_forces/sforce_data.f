C     rollcon test routine (suite user-forces): an SFOSUB between markers PAR(1) and PAR(2)
C     whose stiffness, damping and free length are ARRAY/PAR(3)'s NUMBERS (GTARAY) and whose
C     sense is STRING/PAR(4) (GTSTRG: 'pull' a spring that pulls the markers together when
C     stretched, 'push' the opposite). It checks the data utilities as it goes: a wrong
C     answer stops the run through ERRMES. data_expressions.adm writes the same force.
      SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
      IMPLICIT NONE
      INTEGER ID, NPAR
      DOUBLE PRECISION TIME, PAR(*), RESULT
      LOGICAL DFLAG, IFLAG
      INTEGER IPAR(2), NUMBER, NCHARS, ISTAT, LENGTH
      DOUBLE PRECISION DM, VR, CONSTS(3), SENSE, SPARE(1)
      CHARACTER*16 WORD
      CHARACTER*2 SHORT
      CHARACTER*32 TEXT
      LOGICAL ERRFLG
      IPAR(1) = NINT(PAR(1))
      IPAR(2) = NINT(PAR(2))
      CALL SYSFNC('DM', IPAR, 2, DM, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC DM failed', ID, 'STOP')
      CALL SYSFNC('VR', IPAR, 2, VR, ERRFLG)
      CALL ERRMES(ERRFLG, 'SYSFNC VR failed', ID, 'STOP')
      CALL GTARAY(NINT(PAR(3)), CONSTS, NUMBER, ISTAT)
      CALL ERRMES(ISTAT .NE. 0 .OR. NUMBER .NE. 3, 'GTARAY failed',
     &            ID, 'STOP')
      CALL GTSTRG(NINT(PAR(4)), WORD, NCHARS, ISTAT)
      CALL ERRMES(ISTAT .NE. 0 .OR. NCHARS .NE. 4, 'GTSTRG failed',
     &            ID, 'STOP')
      IF (WORD .EQ. 'pull') THEN
          SENSE = 1.0D0
      ELSE IF (WORD .EQ. 'push') THEN
          SENSE = -1.0D0
      ELSE
          CALL ERRMES(.TRUE., 'STRING is neither pull nor push', ID,
     &                'STOP')
      END IF
C     what the model lacks, and a STRING argument too short for the text
      CALL GTARAY(999, SPARE, NUMBER, ISTAT)
      CALL ERRMES(ISTAT .NE. -2 .OR. NUMBER .NE. 0,
     &            'GTARAY of a missing ARRAY said nothing', ID, 'STOP')
      CALL GTSTRG(999, WORD, NCHARS, ISTAT)
      CALL ERRMES(ISTAT .NE. -2,
     &            'GTSTRG of a missing STRING said nothing', ID, 'STOP')
      CALL GTSTRG(NINT(PAR(4)), SHORT, NCHARS, ISTAT)
      CALL ERRMES(ISTAT .EQ. 0 .OR. SHORT .NE. 'pu'
     &            .OR. NCHARS .NE. 4,
     &            'GTSTRG into a short STRING said nothing', ID, 'STOP')
C     the conversions to text
      CALL ISTRNG(-ID*1001, TEXT, LENGTH, ISTAT)
      CALL ERRMES(ISTAT .NE. 0 .OR. TEXT .NE. '-2002'
     &            .OR. LENGTH .NE. 5, 'ISTRNG failed', ID, 'STOP')
      CALL RSTRNG(-0.15D0, TEXT, LENGTH, ISTAT)
      CALL ERRMES(ISTAT .NE. 0
     &            .OR. TEXT .NE. '-1.4999999999999999E-001'
     &            .OR. LENGTH .NE. 24, 'RSTRNG failed', ID, 'STOP')
      RESULT = SENSE*(-CONSTS(1)*(DM - CONSTS(3)) - CONSTS(2)*VR)
      END
