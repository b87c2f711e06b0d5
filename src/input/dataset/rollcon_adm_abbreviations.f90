! SPDX-License-Identifier: MIT
!> ADAMS's minimum abbreviations of the statement names, command names and argument keywords
!> rollcon reads (docs/datasets.md, "Abbreviations"). ADAMS does not take any unique
!> beginning of a name: each name has its own shortest form, fixed when the name entered the
!> language, so that a name added later never changes what an older abbreviation means
!> (REQUEST's `C` is COMMENT although CNAMES, CUNITS and CLABELS begin with C; its `F` is
!> FORCE although F1 ... F8 and FUNCTION begin with F). A written word stands for a name
!> when it is a beginning of the name at least as long as that name's shortest form.
!>
!> The table writes each name with its shortest form in capitals and the rest in lower case
!> (`REQuest`: REQ, REQU, ..., REQUEST), as ADAMS's reference marks them. Each place is the
!> statements of a dataset (`statement`), the commands of a command file (`command`), or a
!> statement's (or command's) arguments; a place lists every name rollcon knows there: those
!> it reads, those it reads and does not use, and those it refuses with a reason, so that no
!> abbreviation of one is taken for another. The names of ADAMS that rollcon does not know
!> shaped the shortest forms too: within a place, the shortest form of a name is the
!> shortest beginning that no other name of ADAMS at that place shares, save where an older
!> name keeps a shorter one (REQUEST and MREQUEST `C`, REQUEST `F`). rollcon's own INTEGRATOR
!> keywords (RTOL, ATOL, MAXSTEPS, ...) take forms that no ADAMS keyword's form begins.
module rollcon_adm_abbreviations
    implicit none
    private

    public :: minimum_abbreviation, abbreviated_form, abbreviation_places, place_names

    !> One place and its names, separated by blanks, each with its shortest form in capitals
    type :: place_type
        character(len=12) :: place
        character(len=640) :: names
    end type place_type

    !> The table (docs/datasets.md repeats it)
    type(place_type), parameter :: table(*) = [ &
        & place_type("statement", "ACcgrav ARray CONtact COUpler DIff END GCon GEar GForce " &
        & // "INtegrator JOint JPrim " &
        & // "MARker MOtion Output BUshing SPRingdamper VTorque " &
        & // "PArt PInput POUtput SForce SImulate SPLine STring UCon UNits VAriable VForce DEbug " &
        & // "EQuilibrium GRaphics IC " &
        & // "Kinematics LIst MRequest NOlist PReferences REQuest RESults"), &
        & place_type("command", "SImulate INTegrator Output STOp DEBug PReferences " &
        & // "EQuilibrium IC Kinematics"), &
        & place_type("PART", "Ground Mass Cm IP Qg Reuler VX VY VZ WX WY WZ Exact"), &
        & place_type("MARKER", "PArt Qp Reuler"), &
        & place_type("VARIABLE", "Function Ic Routine"), &
        & place_type("DIFF", "Function IC IMplicit Static_hold Routine"), &
        & place_type("SPLINE", "X Y Z Linear_extrapolate"), &
        & place_type("STRING", "String"), &
        & place_type("ARRAY", "X Y U IC Size Numbers Variables"), &
        & place_type("PINPUT", "Variables"), &
        & place_type("POUTPUT", "Variables"), &
        & place_type("UCON", "Function Routine"), &
        & place_type("ACCGRAV", "Igrav Jgrav Kgrav"), &
        & place_type("UNITS", "Force Mass Length Time System"), &
        & place_type("SFORCE", "I J Translation ROTation Actiononly Function TRANSLATIONAl " &
        & // "ROTATIONAl ROUtine"), &
        & place_type("VFORCE", "I Jfloat RM FX FY FZ FUnction ROutine"), &
        & place_type("GFORCE", "I Jfloat RM FX FY FZ TX TY TZ FUnction ROutine"), &
        & place_type("VTORQUE", "I Jfloat RM TX TY TZ Function ROutine"), &
        & place_type("SPRINGDAMPER", "I J TRanslational Rotational K C Length Force KT CT " &
        & // "Angle TOrque"), &
        & place_type("BUSHING", "I J K C KT CT Force Torque"), &
        & place_type("JOINT", "COnvel CYlindrical Fixed Hooke REvolute SPherical " &
        & // "Translational Universal I J IC ICTran ICRot Delta_v Maximum_deformation " &
        & // "RAckpin SCrew PLanar PD PItch"), &
        & place_type("MOTION", "JOint I J Translation ROTation TRANSLATIONAl ROTATIONAl X Y Z " &
        & // "B1 B2 B3 Displacement Velocity Acceleration Function ICDisp ICVel ROUtine"), &
        & place_type("JPRIM", "Atpoint INLine INPlane PArallel_axes PErpendicular " &
        & // "Orientation I J"), &
        & place_type("GCON", "I Function"), &
        & place_type("COUPLER", "Joints Type Scales Function Routine"), &
        & place_type("GEAR", "Joints Cv"), &
        & place_type("CONTACT", "IGeom JGeom IFlip_geometry JFlip_geometry IMpact POisson " &
        & // "STIFfness DAmping DMax Exponent PEnalty Restitution_coefficient NORMAL_Function " &
        & // "NORMAL_Routine Coulomb_friction MU_Static MU_Dynamic " &
        & // "STICtion_transition_velocity FRICTION_Transition_velocity FRICTION_Function " &
        & // "FRICTION_Routine Augmented_lagrangian_formulation ROlling_resistance " &
        & // "AIr_viscosity"), &
        & place_type("SIMULATE", "DYnamic End STEps DTout DUration STAtic Kinematic " &
        & // "Transient Initial_conditions"), &
        & place_type("INTEGRATOR", "Error RTol ATol MAXSteps BAumgarte Formulation MEthod " &
        & // "DRift Jacobian Solver GStiff Wstiff Dstiff CONstant_bdf HAstiff HHt Newmark " &
        & // "Rkf45 ABam I3 SI2 SI1 HMAx HMIn HInit ALpha Beta GAmma ADaptivity Kmax Maxit " &
        & // "CORrector INterpolate Pattern"), &
        & place_type("OUTPUT", "Dacsave Grsave NOPrint NOSeparator Reqsave Separator " &
        & // "Teletype Ypr"), &
        & place_type("REQUEST", "Displacement Velocity Acceleration Force I J RM F1 F2 F3 F4 " &
        & // "F5 F6 F7 F8 FUnction ROutine Comment Title CNames CUnits CLabels REsults_name"), &
        & place_type("MREQUEST", "Displacement Velocity ACceleration Force Parts JOints " &
        & // "JPrims APpfors Comment"), &
        & place_type("GRAPHICS", "Arc BOX CIRcle CUrve CYlinder ELLipsoid EXternal FOrce " &
        & // "FRustum PLane POint SPdp TORus Outline CM CORner RM EMarker I J RADius LEngth " &
        & // "TOP BOTtom X Y Z XScale YScale ZScale XMIn XMAx YMIn YMAx MAjor_radius " &
        & // "MInor_radius CRatio DA DB DC DD LA LB LC LD RANgle SIdes SEg COIls CID EId " &
        & // "EType FIle ELEment FAceting_tolerance"), &
        & place_type("RESULTS", "Formatted Xrf NOACcelerations NOAPpliedforces NOContacts " &
        & // "NODatastructures NOFloatingmarkers NOLinear NOREActionforces NOREQuests " &
        & // "NOSystemelements NOTires NOVelocities Roundoff Trailingzeros Sigfigs " &
        & // "Zerothreshold Comment"), &
        & place_type("DEBUG", "DOf DUmp Eprint Jmdump REqdump RHsdump Topology Verbose"), &
        & place_type("PREFERENCES", "CONTACT_Faceting_tolerance Nthreads " &
        & // "CONTACT_Geometry_library FLEX_LIMIT_CHECK FLEX_LIMIT_CHECK_action " &
        & // "Library_search_path SImfail SOlverbias STatus_message"), &
        & place_type("EQUILIBRIUM", "STATic Dynamic Error Imbalance STABility Tlimit " &
        & // "SEttling_time Global_damping Alimit MAxit Pattern MEthod"), &
        & place_type("KINEMATICS", "Error AError Hmax Tlimit ALimit Maxit AMaxit Pattern " &
        & // "APattern"), &
        & place_type("IC", "Error AError Verror Tlimit ALimit Maxit AMaxit Pattern APattern")]

contains

    !> The length of the shortest form of `name` (upper case, in full) at `place`; -1 when
    !> the table has no such name there.
    pure integer function minimum_abbreviation(place, name) result(minimum)
        character(len=*), intent(in) :: place, name
        character(len=:), allocatable :: word
        integer :: i

        minimum = -1
        word = abbreviated_form(place, name)
        if (len(word) == 0) return
        minimum = len(word)
        do i = 1, len(word)
            if (is_lower(word(i:i))) then
                minimum = i - 1
                return
            end if
        end do
    end function minimum_abbreviation

    !> `name` as the table writes it at `place`, its shortest form in capitals (REQuest);
    !> "" when the table has no such name there.
    pure function abbreviated_form(place, name) result(word)
        character(len=*), intent(in) :: place, name
        character(len=:), allocatable :: word
        character(len=:), allocatable :: names
        integer :: p, start, blank

        word = ""
        p = place_index(place)
        if (p == 0) return
        names = trim(table(p)%names) // " "
        start = 1
        do while (start < len(names))
            blank = start + index(names(start:), " ") - 1
            if (upper(names(start:blank - 1)) == trim(name)) then
                word = names(start:blank - 1)
                return
            end if
            start = blank + 1
        end do
    end function abbreviated_form

    !> The places of the table, in its order.
    pure function abbreviation_places() result(places)
        character(len=12) :: places(size(table))

        places = table%place
    end function abbreviation_places

    !> The names at `place`, upper case, in the table's order (none for a place not in it).
    pure function place_names(place) result(names)
        character(len=*), intent(in) :: place
        character(len=32), allocatable :: names(:)
        character(len=:), allocatable :: words
        integer :: p, start, blank

        allocate(names(0))
        p = place_index(place)
        if (p == 0) return
        words = trim(table(p)%names) // " "
        start = 1
        do while (start < len(words))
            blank = start + index(words(start:), " ") - 1
            names = [character(len=32) :: names, upper(words(start:blank - 1))]
            start = blank + 1
        end do
    end function place_names

    !> Position of `place` in the table (0: absent).
    pure integer function place_index(place) result(p)
        character(len=*), intent(in) :: place

        do p = 1, size(table)
            if (trim(table(p)%place) == trim(place)) return
        end do
        p = 0
    end function place_index

    pure logical function is_lower(c)
        character, intent(in) :: c

        is_lower = c >= "a" .and. c <= "z"
    end function is_lower

    !> The word in capitals.
    pure function upper(word) result(text)
        character(len=*), intent(in) :: word
        character(len=len(word)) :: text
        integer :: i

        text = word
        do i = 1, len(word)
            if (is_lower(word(i:i))) text(i:i) = achar(iachar(word(i:i)) - 32)
        end do
    end function upper

end module rollcon_adm_abbreviations
