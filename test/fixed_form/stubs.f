C SPDX-License-Identifier: MIT
C     Stand-ins for the ADAMS utilities UCOVAR and ERRMES: they record
C     what a UCOSUB tells them in COMMON for driver.f to print.
C
C     UCOVAR: keep the declared parts and codes and the ID given.
      SUBROUTINE UCOVAR(ID, NPARTS, LPARTS, NVARS, LVARS)
      IMPLICIT NONE
      INTEGER ID, NPARTS, LPARTS(*), NVARS, LVARS(*)
      INTEGER NERR, IDERR, NDECL, IDDECL, LP(30), LV(30), I
      COMMON /STUBI/ NERR, IDERR, NDECL, IDDECL, LP, LV
      NDECL = MAX(0, MIN(NVARS, NPARTS, 30))
      IF (NPARTS .NE. NVARS) NDECL = -1
      IDDECL = ID
      DO 10 I = 1, MAX(NDECL, 0)
         LP(I) = LPARTS(I)
         LV(I) = LVARS(I)
   10 CONTINUE
      END
C
C     ERRMES: count the reports, keep the first message and its ID.
C     Like the library's ERRMES, it never stops the program.
      SUBROUTINE ERRMES(ERRFLG, MESAGE, ID, ENDFLG)
      IMPLICIT NONE
      LOGICAL ERRFLG
      CHARACTER*(*) MESAGE, ENDFLG
      INTEGER ID
      INTEGER NERR, IDERR, NDECL, IDDECL, LP(30), LV(30)
      COMMON /STUBI/ NERR, IDERR, NDECL, IDDECL, LP, LV
      CHARACTER*240 ERRTXT
      COMMON /STUBC/ ERRTXT
      IF (.NOT. ERRFLG) RETURN
      NERR = NERR + 1
      IF (NERR .EQ. 1) THEN
         IDERR = ID
         ERRTXT = MESAGE
         IF (ENDFLG .NE. 'STOP') ERRTXT = 'ENDFLG is not STOP: '
     &                                    // MESAGE
      END IF
      END
