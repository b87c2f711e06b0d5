! SPDX-License-Identifier: MIT
!> The Newton matrices of a model held by force statements written as expressions and by
!> user force routines (suite force-partials; src/mechanics/rollcon_force_partials.f90,
!> rollcon_user_force_partials.f90). Two parts in general position and motion under gravity:
!> a translational SFORCE between them reading DM, VR and a third marker's DX, a rotational
!> SFORCE reading AZ and WZ, a VFORCE between them in RM's axes on a moving part reading DX,
!> VX, VY and AX, a GFORCE to the ground reading VZ, WX, AY, PSI and an AKISPL of DZ, and a
!> VTORQUE reading WY and THETA. CVODE's d(q', u')/d(q, u) and IDA's dr/dy, dr/dy' against
!> central differences entry by entry; the coupling of the parts in IDA's sparse pattern and
!> CVODE's blocks. A spring-damper SFOSUB and a bushing GFOSUB written for the test (as
!> test/user_forces/'s, through rollcon_user_forces' SYSFNC and SYSARY) give the Newton
!> matrices of the same forces written as expressions, to the differences' error; a
!> routine that reads a marker its initialisation call did not name is noted, and that
!> partial left out. A force reading VARVAL of a VARSUB written for the test has the Newton
!> matrix of its twin reading an expression VARIABLE (the VARSUB's partials differenced over
!> its declared markers' parts, one of them a part the force does not join). A force reading
!> VARVAL of a VARSUB that reads a joint's reaction (SYSFNC('JOINT')) has IDA's dr/dy of
!> central differences, its columns in the multipliers included (the VARSUB's partials in
!> them differenced and chained through the expression), and CVODE's d(q', u')/d(q, u) of
!> them (the loop's partials in the multipliers chained through the saddle-point solve). A
!> DIFF whose DIFSUB integrates a joint's reaction has the DIFF's rows of IDA's and CVODE's
!> Newton matrices of central differences of the residual and of the right-hand side (its
!> partials in the multipliers differenced over the rows it declared: IDA's columns in
!> lambda, CVODE's chain through dlambda/d(q, u)).
module test_force_partials
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_problem, only : problem_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_force_routine_contract, only : routine_sfosub, routine_gfosub
    use rollcon_user_forces, only : register_force_routine, clear_force_routines, &
        & system_function, system_array, system_notes, clear_system_notes, &
        & register_variable_routine, register_diff_routine
    use rollcon_dae_form, only : dae_form_type
    use rollcon_newton_pattern, only : newton_pattern_type
    use adm_datasets, only : read_dataset
    use newton_checks, only : check_ode_matrix, check_dae_matrix
    use rollcon_testing, only : unittest_type, new_unittest, check
    use rollcon_momentum_partials, only : momentum_partials_type
    implicit none
    private

    public :: collect_force_partials

    !> Central differences of step h_fd: their truncation error h^2 f'''/6 and rounding
    !> eps f/h_fd are below 1e-8 of the matrix's largest entry here; tol_fd, 1e-6 of it,
    !> stands a hundred times above them, and a missing partial (stiffnesses of 30 to 400
    !> over masses of 1.5 to 2) is 1e-2 of it or more.
    real(wp), parameter :: tol_fd = 1.0e-6_wp, h_fd = 1.0e-6_wp
    !> A user routine's partials are central differences of step eps^(1/3) max(|y|, 1)
    !> (rollcon_user_force_partials): their error, h^2 v'''/6 + eps |v|/h, is near
    !> eps^(2/3) = 4e-11 of the values' scale (measured: 8e-13 of the matrix's largest entry);
    !> tol_user, 1e-10 of it, stands above the estimate, and a partial left out (a stiffness of
    !> 400 over a mass of 1) is 0.3 of it.
    real(wp), parameter :: tol_user = 1.0e-10_wp
    character(len=200), parameter :: lines(22) = [character(len=200) :: &
        & "expression forces", &
        & "UNITS/SYSTEM = SI", &
        & "PART/1, GROUND", &
        & "MARKER/10, PART = 1, QP = 0.1, 0.2, 0.3, REULER = 10D, 20D, 30D", &
        & "PART/2, MASS = 2, CM = 20, IP = 1, 2, 2.5, QG = 0.3, -0.2, 0.5, REULER = 40D, 70D, " &
        & // "-20D, VX = 0.2, VY = -0.1, VZ = 0.3, WX = 0.3, WY = -0.5, WZ = 0.7", &
        & "MARKER/20, PART = 2|MARKER/21, PART = 2, QP = 0.1, 0.05, -0.2, REULER = 15D, 35D, 5D", &
        & "PART/3, MASS = 1.5, CM = 30, IP = 0.8, 1.1, 1.3, QG = -0.4, 0.3, 0.1, REULER = " &
        & // "-30D, 50D, 60D, VX = -0.3, VZ = 0.1, WX = -0.4, WY = 0.2, WZ = 0.9", &
        & "MARKER/30, PART = 3|MARKER/31, PART = 3, QP = -0.1, 0.2, 0.1, REULER = 5D, 25D, 45D", &
        & "SFORCE/1, TRANSLATION, I = 21, J = 31, FUNCTION = -400*(DM(21, 31) - 0.3) " &
        & // "- 5*VR(21, 31) + 20*DX(20, 10)", &
        & "SFORCE/2, ROTATION, I = 20, J = 30, FUNCTION = -30*AZ(20, 30) - 0.8*WZ(20, 30)", &
        & "VFORCE/3, I = 21, JFLOAT = 30, RM = 31, FX = -50*DX(21, 31, 31) - 2*VX(21, 31, 31)" &
        & // ", FY = -60*DY(21, 31, 31) - VY(21, 31, 31, 30), FZ = -10*AX(21, 30)*DM(21, 30)", &
        & "GFORCE/4, I = 30, JFLOAT = 10, RM = 20, FX = -3*VZ(30, 10), FY = 0, " &
        & // "FZ = -80*AKISPL(DZ(30, 10), 0, 7), TX = -2*WX(30, 10, 20) - 5*AY(30, 10), " &
        & // "TY = 0, TZ = -4*SIN(PSI(30, 10))", &
        & "VTORQUE/5, I = 20, JFLOAT = 10, RM = 10, TX = -WY(20, 10, 10), TY = 0, " &
        & // "TZ = -6*THETA(20)", &
        & "SPLINE/7, X = -2, -1, 0, 1, 2, 3, Y = -3, -1.5, 0.2, 1, 2.5, 5", &
        & "ACCGRAV/KGRAV = -9.81", &
        & "INTEGRATOR/ERROR = 1e-8", &
        & "SIMULATE/DYNAMIC, END = 1, STEPS = 10", &
        & "END", "", "", "", ""]
    !> The twins: one part on a spring-damper SFORCE and a bushing GFORCE to the ground, the
    !> forces as expressions (expression_twin) and by the routines below (user_twin, whose
    !> PAR the routines read as test/user_forces/'s sforce_spring.f and gforce_bushing.f do)
    character(len=160), parameter :: twin_head(8) = [character(len=160) :: &
        & "twins", &
        & "UNITS/SYSTEM = SI", &
        & "PART/1, GROUND|MARKER/1, PART = 1|MARKER/2, PART = 1, QP = 0, 0, 2", &
        & "PART/2, MASS = 1, CM = 20, IP = 0.1, 0.12, 0.15, QG = 0.1, -0.2, 1, REULER = 30D, " &
        & // "40D, 50D, VX = 0.4, VZ = -0.3, WX = 1, WY = -0.4, WZ = 2", &
        & "MARKER/20, PART = 2, REULER = 0D, 90D, 0D", &
        & "MARKER/21, PART = 2, QP = 0.5, 0, 0", &
        & "PART/3, MASS = 1, CM = 30, IP = 0.1, 0.1, 0.1, QG = 1, 1, 1|MARKER/30, PART = 3", &
        & "ACCGRAV/KGRAV = -9.81"]
    character(len=200), parameter :: expression_twin(8) = [character(len=200) :: &
        & "GFORCE/1, I = 21, JFLOAT = 1, RM = 1,", &
        & ", FX = -400*(DX(21, 1, 1) - 0.5) - 4*VX(21, 1, 1, 1),", &
        & ", FY = -400*DY(21, 1, 1) - 4*VY(21, 1, 1, 1),", &
        & ", FZ = -400*(DZ(21, 1, 1) - 1) - 4*VZ(21, 1, 1, 1),", &
        & ", TX = -30*AX(21, 1) - 0.5*WX(21, 1, 1),", &
        & ", TY = -30*AY(21, 1) - 0.5*WY(21, 1, 1),", &
        & ", TZ = -30*AZ(21, 1) - 0.5*WZ(21, 1, 1)", &
        & "SFORCE/2, TRANSLATION, I = 20, J = 2, FUNCTION = -1000*(DM(20, 2) - 1) - 10*VR(20, 2)"]
    character(len=200), parameter :: user_twin(2) = [character(len=200) :: &
        & "GFORCE/1, I = 21, JFLOAT = 1, RM = 1, FUNCTION = USER(21, 1, 0.5, 0, 1, 400, 4, 30, " &
        & // "0.5)", &
        & "SFORCE/2, TRANSLATION, I = 20, J = 2, FUNCTION = USER(20, 2, 1000, 10, 1)"]
    character(len=80), parameter :: tail(3) = [character(len=80) :: &
        & "INTEGRATOR/ERROR = 1e-8", "SIMULATE/DYNAMIC, END = 1, STEPS = 10", "END"]
    !> The GFOSUB reads marker 30 (on the free part 3) without naming it in its
    !> initialisation call
    logical, save :: hide_a_read = .false.

contains

    subroutine collect_force_partials(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("expression-forces-ode-jacobian", test_ode), &
            & new_unittest("expression-forces-dae-jacobian-and-pattern", test_dae), &
            & new_unittest("user-routines-against-expressions", test_user_twins), &
            & new_unittest("user-routine-undeclared-read", test_undeclared), &
            & new_unittest("varsub-read-by-force-against-expression", test_varsub_twins), &
            & new_unittest("varsub-reading-reaction-dae-jacobian", test_varsub_reaction), &
            & new_unittest("varsub-reading-reaction-ode-jacobian", test_varsub_reaction_ode), &
            & new_unittest("difsub-reading-reaction-newton-matrices", test_difsub_reaction), &
            & new_unittest("momentum-partials-on-pairs-as-dense", test_pairs_as_dense)]
    end subroutine collect_force_partials

    !> A model built from a dataset's lines at its start (q0, u0).
    subroutine build(text, problem, q0, u0, error)
        character(len=*), intent(in) :: text(:)
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface), pointer :: routine
        type(adm_model_type) :: adm

        routine => rolling_disk_ucosub
        call read_dataset("force_partials.adm", text, adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, routine, problem, q0, u0, error)
        if (allocated(error)) return
        call problem%prepare(error)
    end subroutine build

    !> d(q', u')/d(q, u) of problem at its start.
    subroutine ode_matrix(problem, q0, u0, jac, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q0(:), u0(:)
        real(wp), allocatable, intent(out) :: jac(:, :)
        type(error_type), allocatable, intent(out) :: error

        allocate(jac(2*size(q0), 2*size(q0)))
        call problem%eq%ode_jacobian(0.0_wp, q0, u0, problem%settings%baumgarte(), jac, error)
    end subroutine ode_matrix

    !> d(q', u')/d(q, u) from the partials against central differences of (u, a(q, u)); the
    !> accelerations of part 2 depend on the coordinates and rates of part 3; parts 2 and 3
    !> share CVODE's block.
    subroutine test_ode(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:), jac(:, :)
        integer, allocatable :: blocks(:)
        integer :: n

        call build(lines, problem, q0, u0, error)
        if (allocated(error)) return
        call check_ode_matrix(problem, q0, u0, h_fd, tol_fd, jac, blocks, error)
        if (allocated(error)) return
        n = size(q0)
        ! the accelerations of part 2 (rows n + 1:n + 6) by the coordinates and rates of part 3
        call check(error, maxval(abs(jac(n + 1:n + 6, 7:12))) > 1.0_wp .and. &
            & maxval(abs(jac(n + 1:n + 6, n + 7:n + 12))) > 0.1_wp, "part 2's accelerations " &
            & // "depend on part 3's coordinates and rates: largest partials " &
            & // to_text(maxval(abs(jac(n + 1:n + 6, 7:12)))) // ", " &
            & // to_text(maxval(abs(jac(n + 1:n + 6, n + 7:n + 12)))))
        if (allocated(error)) return
        call check(error, all(blocks == blocks(1)), "parts 2 and 3 share CVODE's block")
        call problem%release()
    end subroutine test_ode

    !> dr/dy of the DAE residual (cj = 0) against central differences in y, and dr/dy' (cj = 1
    !> less cj = 0) against those in y'; every entry not zero is in the sparse pattern.
    subroutine test_dae(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:), jac(:, :)
        integer :: n

        call build(lines, problem, q0, u0, error)
        if (allocated(error)) return
        call check_dae_matrix(problem, q0, u0, h_fd, tol_fd, jac, error)
        if (allocated(error)) return
        n = size(q0)
        call check(error, maxval(abs(jac(n + 1:n + 6, 7:12))) > 1.0_wp, "part 2's momentum " &
            & // "rows depend on part 3's coordinates")
        call problem%release()
    end subroutine test_dae

    !> The twins' ODE Jacobians agree to tol_user of the largest entry: the user routines'
    !> partials (differences over the declared markers' parts) are the expressions' (exact);
    !> and without the routines' partials they would not (the part's accelerations depend on
    !> its coordinates through the forces' stiffness, entries of 400 and more).
    subroutine test_user_twins(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: exact(:, :), differenced(:, :)
        integer :: n, j

        hide_a_read = .false.
        call twin_matrices(exact, differenced, error)
        if (allocated(error)) return
        n = size(exact, 1)/2
        ! part 2's translational accelerations by its position: the forces' stiffness alone
        ! (the body's own partials have none there), 1000 + 400 over a mass of 1
        call check(error, minval([maxval(abs(exact(n + 1:n + 3, 1:3))), &
            & maxval(abs(differenced(n + 1:n + 3, 1:3)))]) > 100.0_wp, "the stiffness is in " &
            & // "both matrices: " // to_text(maxval(abs(exact(n + 1:n + 3, 1:3)))) // ", " &
            & // to_text(maxval(abs(differenced(n + 1:n + 3, 1:3)))))
        if (allocated(error)) return
        do j = 1, size(exact, 2)
            call check(error, differenced(:, j), exact(:, j), "the user routines' ODE " &
                & // "Jacobian, column " // to_text(j), abs_tol=tol_user*maxval(abs(exact)))
            if (allocated(error)) return
        end do
    end subroutine test_user_twins

    !> A GFOSUB that reads a marker of part 3 (SYSARY TDISP of marker 30) its initialisation
    !> call did not name: the read is noted (system_notes, as rollcon check reports it), and
    !> its partials are left out of the Newton matrix (ADAMS's rule: only the declared
    !> dependencies are differenced), where differences of the right-hand side find them
    !> (a stiffness of 500 on a mass of 1).
    subroutine test_undeclared(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        real(wp), allocatable :: q0(:), u0(:), y(:), yh(:), jac(:, :), fp(:), fm(:)
        real(wp) :: found, left
        integer :: j, n, ierr

        call clear_force_routines()
        call register_force_routine(routine_sfosub, "", "test_force_partials", spring_sfosub)
        call register_force_routine(routine_gfosub, "", "test_force_partials", bushing_gfosub)
        hide_a_read = .true.
        call clear_system_notes()
        call build([character(len=200) :: twin_head, user_twin, tail], problem, q0, u0, error)
        if (.not. allocated(error)) call ode_matrix(problem, q0, u0, jac, error)
        if (allocated(error)) then
            hide_a_read = .false.
            call clear_force_routines()
            return
        end if
        call ode%init(problem)
        n = size(q0)
        y = [q0, u0]
        allocate(fp(2*n), fm(2*n))
        found = 0.0_wp
        left = 0.0_wp
        ierr = 0
        ! part 2's accelerations (rows n + 1:n + 6) by part 3's coordinates (7:12)
        do j = 7, 12
            yh = y
            yh(j) = y(j) + h_fd
            ierr = ierr + ode%ode_rhs(0.0_wp, yh, fp)
            yh(j) = y(j) - h_fd
            ierr = ierr + ode%ode_rhs(0.0_wp, yh, fm)
            found = max(found, maxval(abs((fp(n + 1:n + 6) - fm(n + 1:n + 6))/(2.0_wp*h_fd))))
            left = max(left, maxval(abs(jac(n + 1:n + 6, j))))
        end do
        hide_a_read = .false.
        call clear_force_routines()
        call check(error, ierr == 0, "right-hand side failed")
        if (allocated(error)) return
        call check(error, index(system_notes(), "SYSARY('TDISP') named marker 30, which the " &
            & // "initialisation call (IFLAG = .TRUE.) did not name") > 0, "the undeclared " &
            & // "read is noted: " // system_notes())
        if (allocated(error)) return
        call check(error, maxval(abs(jac(n + 1:n + 3, 1:3))) > 100.0_wp, "the declared " &
            & // "reads' partials are there: " // to_text(maxval(abs(jac(n + 1:n + 3, 1:3)))))
        if (allocated(error)) return
        call check(error, found > 100.0_wp .and. left == 0.0_wp, "the undeclared read's " &
            & // "partials (" // to_text(found) // " by differences) are left out of the " &
            & // "Newton matrix: " // to_text(left))
        call problem%release()
    end subroutine test_undeclared

    !> SFORCE/2 of the twins reading VARVAL(3), VARIABLE/3 = DM(20, 2) - 1 + 0.2 DX(30) as an
    !> expression and as stretch_varsub's VALUE (the same, through SYSFNC): the ODE Jacobians
    !> agree to tol_user of the largest entry (the VARSUB's partials are differences of the
    !> same step and error as a force routine's, above), including part 2's accelerations by
    !> part 3's coordinates, which only the VARSUB's declared marker 30 brings in. With the
    !> VARSUB's partials taken as zero its stiffness (1000 over a mass of 1) would be missing.
    subroutine test_varsub_twins(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=200), parameter :: spring(1) = [character(len=200) :: &
            & "SFORCE/2, TRANSLATION, I = 20, J = 2, FUNCTION = -1000*VARVAL(3) - 10*VR(20, 2)"]
        character(len=200), parameter :: expression(1) = [character(len=200) :: &
            & "VARIABLE/3, FUNCTION = DM(20, 2) - 1 + 0.2*DX(30)"]
        character(len=200), parameter :: user(1) = [character(len=200) :: &
            & "VARIABLE/3, FUNCTION = USER(20, 2, 1, 30, 0.2)"]
        type(problem_type), target :: expressions, users
        real(wp), allocatable :: q0(:), u0(:), exact(:, :), differenced(:, :)
        integer :: n, j

        call clear_force_routines()
        call register_variable_routine("", "test_force_partials", stretch_varsub)
        call build([character(len=200) :: twin_head, expression, spring, tail], expressions, &
            & q0, u0, error)
        if (.not. allocated(error)) call ode_matrix(expressions, q0, u0, exact, error)
        if (.not. allocated(error)) call build([character(len=200) :: twin_head, user, spring, &
            & tail], users, q0, u0, error)
        if (.not. allocated(error)) call ode_matrix(users, q0, u0, differenced, error)
        call clear_force_routines()
        if (allocated(error)) return
        n = size(exact, 1)/2
        ! part 2's translational accelerations by its position, and by part 3's x
        call check(error, minval([maxval(abs(exact(n + 1:n + 3, 1:3))), &
            & maxval(abs(differenced(n + 1:n + 3, 1:3)))]) > 100.0_wp, "the stiffness is in " &
            & // "both matrices: " // to_text(maxval(abs(exact(n + 1:n + 3, 1:3)))) // ", " &
            & // to_text(maxval(abs(differenced(n + 1:n + 3, 1:3)))))
        if (allocated(error)) return
        call check(error, maxval(abs(differenced(n + 1:n + 3, 7))) > 10.0_wp, "part 3's x " &
            & // "moves part 2 through the VARSUB: " &
            & // to_text(maxval(abs(differenced(n + 1:n + 3, 7)))))
        if (allocated(error)) return
        do j = 1, size(exact, 2)
            call check(error, differenced(:, j), exact(:, j), "the VARSUB twin's ODE " &
                & // "Jacobian, column " // to_text(j), abs_tol=tol_user*maxval(abs(exact)))
            if (allocated(error)) return
        end do
        call expressions%release()
        call users%release()
    end subroutine test_varsub_twins

    !> A pendulum on a revolute joint whose axis is tilted in ground (its markers turned by
    !> 30, 40, 50 degrees), held by the rotational SFORCE/3 = -0.2 VARVAL(4) - 3 AZ(20, 10),
    !> VARIABLE/4 served by reaction_varsub: |F| of JOINT/1 at I, SYSFNC('JOINT', 1, 0, 1).
    !> IDA's dr/dy (cj = 0) at the start with the multipliers lambda_k = 2 + k (away from a
    !> zero reaction, where |F| has a kink) and mu = 0 against central differences of step
    !> h_fd in every unknown (newton_checks' check_dae_matrix, which checks dr/dy' and the
    !> sparse pattern too), to tol_fd of its largest entry (the VARSUB's partials are
    !> differences of error 4e-11 of their scale, above; measured 1.7e-9 for a largest entry
    !> of 6.9); and its columns in the multipliers differ from the same pendulum's without
    !> the VARIABLE (C^T alone) by the friction's partials, 0.2 d|F|/dlambda (measured 0.14),
    !> which the test requires to exceed 1e-2, over a thousand times tol_fd's bound here:
    !> left out, the columns would fail.
    subroutine test_varsub_reaction(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=200), parameter :: pendulum(8) = [character(len=200) :: &
            & "pendulum", "UNITS/SYSTEM = SI", &
            & "PART/1, GROUND|MARKER/10, PART = 1, REULER = 30D, 40D, 50D", &
            & "PART/2, MASS = 2, CM = 22, IP = 0.1, 0.12, 0.15, REULER = 30D, 40D, 50D", &
            & "MARKER/20, PART = 2|MARKER/22, PART = 2, QP = 0.8, -0.5, 0.3", &
            & "JOINT/1, REVOLUTE, I = 20, J = 10", "ACCGRAV/KGRAV = -9.81", &
            & "VARIABLE/4, FUNCTION = USER(1)"]
        character(len=200), parameter :: friction(1) = [character(len=200) :: &
            & "SFORCE/3, ROTATIONAL, I = 20, J = 10, FUNCTION = -0.2*VARVAL(4) - 3*AZ(20, 10)"]
        character(len=200), parameter :: bare(1) = [character(len=200) :: &
            & "SFORCE/3, ROTATIONAL, I = 20, J = 10, FUNCTION = -3*AZ(20, 10)"]
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:), with(:, :), without(:, :)
        real(wp) :: largest
        integer :: n

        call clear_force_routines()
        call register_variable_routine("", "test_force_partials", reaction_varsub)
        call build([character(len=200) :: pendulum, friction, tail], problem, q0, u0, error)
        if (.not. allocated(error)) call check_dae_matrix(problem, q0, u0, h_fd, tol_fd, with, &
            & error)
        if (allocated(error)) then
            call clear_force_routines()
            return
        end if
        call problem%release()
        call build([character(len=200) :: pendulum, bare, tail], problem, q0, u0, error)
        if (.not. allocated(error)) call check_dae_matrix(problem, q0, u0, h_fd, tol_fd, &
            & without, error)
        call clear_force_routines()
        if (allocated(error)) return
        n = size(q0)
        largest = maxval(abs(with(:, 2*n + 1:2*n + problem%eq%nc) &
            & - without(:, 2*n + 1:2*n + problem%eq%nc)))
        call check(error, largest > 1.0e-2_wp, "the friction's partials in the multipliers " &
            & // "are at most " // to_text(largest))
        call problem%release()
    end subroutine test_varsub_reaction

    !> test_varsub_reaction's pendulum (held by -0.2 VARVAL(4) - 3 AZ(20, 10), VARIABLE/4's
    !> VARSUB reading |F| of JOINT/1) at its start, at rest: CVODE's d(q', u')/d(q, u) against
    !> central differences of the right-hand side (which solves the loop in the accelerations
    !> and multipliers at each state), entry by entry, to tol_fd of its largest entry
    !> (newton_checks' check_ode_matrix; the VARSUB's partials are differences of error 4e-11
    !> of their scale). The chain through the VARIABLE runs from dlambda/d(q, u) (the loop's
    !> saddle-point matrix with the friction's partials in the multipliers) into the
    !> accelerations. At rest the terms the ODE form leaves out, the constraints' third
    !> partials in dgamma/dq (rollcon_equations' ode_jacobian), multiply u twice and vanish:
    !> the matrix is exact there, and so is the same pendulum's without the VARIABLE (-3 AZ
    !> alone), also checked. The friction's share, the difference of the two matrices
    !> (measured 1.3 of entries up to 8.5), must exceed a thousand times the tolerance's
    !> bound. The loop's matrix formed at its first iterate (multipliers 0 at the first call,
    !> where |F| has a kink) instead of at the solution misses 2e-2 in d(a_x)/d(q_4): 2e3
    !> times tol_fd's bound.
    subroutine test_varsub_reaction_ode(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=200), parameter :: pendulum(8) = [character(len=200) :: &
            & "pendulum", "UNITS/SYSTEM = SI", &
            & "PART/1, GROUND|MARKER/10, PART = 1, REULER = 30D, 40D, 50D", &
            & "PART/2, MASS = 2, CM = 22, IP = 0.1, 0.12, 0.15, REULER = 30D, 40D, 50D", &
            & "MARKER/20, PART = 2|MARKER/22, PART = 2, QP = 0.8, -0.5, 0.3", &
            & "JOINT/1, REVOLUTE, I = 20, J = 10", "ACCGRAV/KGRAV = -9.81", &
            & "VARIABLE/4, FUNCTION = USER(1)"]
        character(len=200), parameter :: friction(1) = [character(len=200) :: &
            & "SFORCE/3, ROTATIONAL, I = 20, J = 10, FUNCTION = -0.2*VARVAL(4) - 3*AZ(20, 10)"]
        character(len=200), parameter :: bare(1) = [character(len=200) :: &
            & "SFORCE/3, ROTATIONAL, I = 20, J = 10, FUNCTION = -3*AZ(20, 10)"]
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:), with(:, :), without(:, :)
        integer, allocatable :: blocks(:)
        real(wp) :: share

        call clear_force_routines()
        call register_variable_routine("", "test_force_partials", reaction_varsub)
        call build([character(len=200) :: pendulum, friction, tail], problem, q0, u0, error)
        if (.not. allocated(error)) call check(error, all(u0 == 0.0_wp), "the pendulum starts " &
            & // "at rest")
        if (.not. allocated(error)) call check_ode_matrix(problem, q0, u0, h_fd, tol_fd, with, &
            & blocks, error)
        if (allocated(error)) then
            call clear_force_routines()
            return
        end if
        call problem%release()
        call build([character(len=200) :: pendulum(:7), bare, tail], problem, q0, u0, error)
        if (.not. allocated(error)) call check_ode_matrix(problem, q0, u0, h_fd, tol_fd, &
            & without, blocks, error)
        call clear_force_routines()
        if (allocated(error)) return
        share = maxval(abs(with - without))
        call check(error, share > 1.0e3_wp*tol_fd*maxval(abs(with)), "the friction's share " &
            & // "of the ODE Jacobian is " // to_text(share) // " of entries up to " &
            & // to_text(maxval(abs(with))))
        call problem%release()
    end subroutine test_varsub_reaction_ode

    !> A pendulum on a revolute joint tilted in ground (as test_varsub_reaction's, no friction)
    !> with DIFF/9, whose DIFSUB (reaction_difsub) integrates |F| of JOINT/1 at I,
    !> SYSFNC('JOINT', 1, 0, 1), plus 0.3 DIF(9): the DIFF's row of IDA's Newton matrix dF/dy
    !> + cj dF/dy' (cj = 7) at the start, the multipliers solved there and moved by 0.5 + 0.25
    !> k (IDA's iterate need not be the solution), against central differences of the
    !> residual in every unknown (y and y' together, y' by cj h), and the sparse pattern keeps
    !> its entries in the multipliers; and the DIFF's row of CVODE's d(q', u', x')/d(q, u, x)
    !> at rest against central differences of the right-hand side (whose multipliers are
    !> solved at each state). The DIFSUB's partials are differences of error 4e-11 of their
    !> scale (|F| near 20 N); the residual's and right-hand side's differences of step 1e-6
    !> are within 1e-8 of the largest entry; tol_fd, 1e-6 of it, stands a hundred times above
    !> (measured: 1.6e-9 of entries up to 6.7 on IDA, 4.8e-9 of entries up to 11 on CVODE).
    !> The partials in the multipliers left out fail both: IDA's row then misses d|F|/dlambda
    !> (direction cosines of the reaction, up to 0.85; the test requires them above 1e-2),
    !> CVODE's d|F|/dlambda dlambda/d(q, u) (entries up to 5.5, where the row keeps 0.3).
    subroutine test_difsub_reaction(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: cj = 7.0_wp
        character(len=200), parameter :: pendulum(8) = [character(len=200) :: &
            & "pendulum", "UNITS/SYSTEM = SI", &
            & "PART/1, GROUND|MARKER/10, PART = 1, REULER = 30D, 40D, 50D", &
            & "PART/2, MASS = 2, CM = 22, IP = 0.1, 0.12, 0.15, REULER = 30D, 40D, 50D", &
            & "MARKER/20, PART = 2|MARKER/22, PART = 2, QP = 0.8, -0.5, 0.3", &
            & "JOINT/1, REVOLUTE, I = 20, J = 10", "ACCGRAV/KGRAV = -9.81", &
            & "DIFF/9, FUNCTION = USER(1), IC = 0.5"]
        type(problem_type), target :: problem
        type(dae_form_type) :: dae
        type(ode_form_type) :: ode
        type(newton_pattern_type) :: pattern
        real(wp), allocatable :: q0(:), u0(:), y(:), yp(:), matrix(:, :), plus(:), minus(:), &
            & yd(:), ypd(:), column(:)
        real(wp) :: worst, largest, in_lambda
        integer :: n, nc, ns, j, k, ierr
        logical :: kept

        call clear_force_routines()
        call register_diff_routine("", "test_force_partials", reaction_difsub)
        call build([character(len=200) :: pendulum, tail], problem, q0, u0, error)
        if (allocated(error)) then
            call clear_force_routines()
            return
        end if
        n = size(q0)
        nc = problem%eq%nc
        ! IDA: the DIFF's row (the last) by every unknown
        call dae%init(problem)
        call problem%accelerations(0.0_wp, q0, u0, error)
        if (allocated(error)) then
            call clear_force_routines()
            return
        end if
        ns = dae%state_size()
        allocate(y(ns), yp(ns), matrix(ns, ns), plus(ns), minus(ns))
        call dae%pack_state(q0, u0, y, yp)
        y(2*n + 1:2*n + nc) = y(2*n + 1:2*n + nc) + [(0.5_wp + 0.25_wp*k, k = 1, nc)]
        matrix = 0.0_wp
        ierr = dae%dae_jacobian(0.0_wp, cj, y, yp, matrix)
        worst = 0.0_wp
        do j = 1, ns
            yd = y
            ypd = yp
            yd(j) = y(j) + h_fd
            ypd(j) = yp(j) + cj*h_fd
            ierr = ierr + dae%dae_residual(0.0_wp, yd, ypd, plus)
            yd(j) = y(j) - h_fd
            ypd(j) = yp(j) - cj*h_fd
            ierr = ierr + dae%dae_residual(0.0_wp, yd, ypd, minus)
            worst = max(worst, abs(matrix(ns, j) - (plus(ns) - minus(ns))/(2.0_wp*h_fd)))
        end do
        largest = maxval(abs(matrix(ns, :)))
        in_lambda = maxval(abs(matrix(ns, 2*n + 1:2*n + nc)))
        call dae%dae_pattern(ns, pattern)
        kept = .true.
        do j = 2*n + 1, 2*n + nc
            if (matrix(ns, j) == 0.0_wp) cycle
            kept = kept .and. any(pattern%rows(pattern%starts(j) + 1:pattern%starts(j + 1)) &
                & == ns - 1)
        end do
        call check(error, ierr == 0 .and. in_lambda > 1.0e-2_wp .and. worst <= tol_fd*largest &
            & .and. kept, "IDA: the DIFF's row against differences of the residual: largest " &
            & // "difference " // to_text(worst) // " of entries up to " // to_text(largest) &
            & // ", in the multipliers up to " // to_text(in_lambda) // merge(" (kept)    ", &
            & " (not kept)", kept) // " (ierr " // to_text(ierr) // ")")
        if (allocated(error)) then
            call clear_force_routines()
            return
        end if
        ! CVODE: the DIFF's row (the last) by (q, u, x)
        call ode%init(problem)
        ns = ode%state_size()
        deallocate(y, yp, matrix, plus, minus)
        allocate(y(ns), yp(ns), matrix(ns, ns), plus(ns), minus(ns))
        call ode%pack_state(q0, u0, y, yp)
        ierr = ode%ode_jacobian(0.0_wp, y, matrix)
        worst = 0.0_wp
        do j = 1, ns
            yd = y
            yd(j) = y(j) + h_fd
            ierr = ierr + ode%ode_rhs(0.0_wp, yd, plus)
            yd(j) = y(j) - h_fd
            ierr = ierr + ode%ode_rhs(0.0_wp, yd, minus)
            column = (plus - minus)/(2.0_wp*h_fd)
            worst = max(worst, abs(matrix(ns, j) - column(ns)))
        end do
        largest = maxval(abs(matrix(ns, :)))
        call clear_force_routines()
        call check(error, ierr == 0 .and. largest > 1.0_wp .and. worst <= tol_fd*largest, &
            & "CVODE: the DIFF's row against differences of the right-hand side: largest " &
            & // "difference " // to_text(worst) // " of entries up to " // to_text(largest) &
            & // " (ierr " // to_text(ierr) // ")")
        call problem%release()
    end subroutine test_difsub_reaction

    !> A DIFSUB: |F| of JOINT/1 at its I, SYSFNC('JOINT', [1, 0, 1]), plus 0.3 DIF(9).
    subroutine reaction_difsub(id, time, par, npar, dflag, iflag, value)
        integer, intent(in) :: id
        real(wp), intent(in) :: time
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar
        logical, intent(in) :: dflag, iflag
        real(wp), intent(inout) :: value
        real(wp) :: state
        logical :: failed

        call system_function("JOINT", [1, 0, 1], value, failed)
        call system_function("DIF", [9], state, failed)
        value = value + 0.3_wp*state
    end subroutine reaction_difsub


    !> A VARSUB: |F| of JOINT/1 at its I, SYSFNC('JOINT', [1, 0, 1]).
    subroutine reaction_varsub(id, time, par, npar, dflag, iflag, value)
        integer, intent(in) :: id
        real(wp), intent(in) :: time
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar
        logical, intent(in) :: dflag, iflag
        real(wp), intent(inout) :: value
        logical :: failed

        call system_function("JOINT", [1, 0, 1], value, failed)
    end subroutine reaction_varsub

    !> A VARSUB: DM(PAR(1), PAR(2)) - PAR(3) + PAR(5) DX(PAR(4)) (SYSFNC), ADAMS's calling
    !> sequence (rollcon_system_routine_contract).
    subroutine stretch_varsub(id, time, par, npar, dflag, iflag, value)
        integer, intent(in) :: id
        real(wp), intent(in) :: time
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar
        logical, intent(in) :: dflag, iflag
        real(wp), intent(inout) :: value
        real(wp) :: dm, dx
        logical :: failed

        call system_function("DM", [nint(par(1)), nint(par(2))], dm, failed)
        call system_function("DX", [nint(par(4))], dx, failed)
        value = dm - par(3) + par(5)*dx
    end subroutine stretch_varsub

    !> The ODE Jacobians of the expression twin and the user twin at their start.
    subroutine twin_matrices(exact, differenced, error)
        real(wp), allocatable, intent(out) :: exact(:, :), differenced(:, :)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: expressions, users
        real(wp), allocatable :: q0(:), u0(:)

        call clear_force_routines()
        call register_force_routine(routine_sfosub, "", "test_force_partials", spring_sfosub)
        call register_force_routine(routine_gfosub, "", "test_force_partials", bushing_gfosub)
        call build([character(len=200) :: twin_head, expression_twin, tail], expressions, q0, &
            & u0, error)
        if (.not. allocated(error)) call ode_matrix(expressions, q0, u0, exact, error)
        if (allocated(error)) then
            call clear_force_routines()
            return
        end if
        call build([character(len=200) :: twin_head, user_twin, tail], users, q0, u0, error)
        if (.not. allocated(error)) call ode_matrix(users, q0, u0, differenced, error)
        call clear_force_routines()
        call expressions%release()
        call users%release()
    end subroutine twin_matrices

    !> sforce_spring.f as a module procedure: F = -PAR(3) (DM - PAR(5)) - PAR(4) VR of markers
    !> PAR(1), PAR(2), read with SYSFNC.
    subroutine spring_sfosub(id, time, par, npar, dflag, iflag, result)
        integer, intent(in) :: id
        real(wp), intent(in) :: time
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar
        logical, intent(in) :: dflag, iflag
        real(wp), intent(inout) :: result(*)
        real(wp) :: dm, vr
        logical :: failed

        call system_function("DM", [nint(par(1)), nint(par(2))], dm, failed)
        call system_function("VR", [nint(par(1)), nint(par(2))], vr, failed)
        result(1) = -par(3)*(dm - par(5)) - par(4)*vr
    end subroutine spring_sfosub

    !> gforce_bushing.f as a module procedure: marker PAR(1) held at (PAR(3), PAR(4), PAR(5))
    !> of marker PAR(2) by stiffness PAR(6) and damping PAR(7), its angles AX, AY, AZ by
    !> PAR(8) and PAR(9) (SYSARY TDISP, TVEL, RVEL; SYSFNC AX, AY, AZ). With hide_a_read it
    !> adds a force of marker 30's TDISP (part 3's), read in every call but the
    !> initialisation call.
    subroutine bushing_gfosub(id, time, par, npar, dflag, iflag, result)
        integer, intent(in) :: id
        real(wp), intent(in) :: time
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar
        logical, intent(in) :: dflag, iflag
        real(wp), intent(inout) :: result(*)
        character(len=2), parameter :: names(3) = ["AX", "AY", "AZ"]
        real(wp) :: displacement(3), velocity(3), omega(3), angle(3), hidden(3)
        integer :: ipar(4), states, k
        logical :: failed

        ipar = [nint(par(1)), nint(par(2)), nint(par(2)), nint(par(2))]
        call system_array("TDISP", ipar(:3), displacement, states, failed)
        call system_array("TVEL", ipar, velocity, states, failed)
        call system_array("RVEL", ipar(:3), omega, states, failed)
        do k = 1, 3
            call system_function(names(k), ipar(:2), angle(k), failed)
        end do
        do k = 1, 3
            result(k) = -par(6)*(displacement(k) - par(2 + k)) - par(7)*velocity(k)
            result(3 + k) = -par(8)*angle(k) - par(9)*omega(k)
        end do
        if (hide_a_read .and. .not. iflag) then
            call system_array("TDISP", [30, 1], hidden, states, failed)
            result(1:3) = result(1:3) - 500.0_wp*hidden
        end if
    end subroutine bushing_gfosub

    !> dm/dq and dm/du held on pairs of parts (rollcon_momentum_partials: the equations'
    !> storage, linear in the model) against the same writes into dense n x n matrices: every
    !> entry of a held pair equal bit for bit (the same operations), every other entry of the
    !> dense matrices an exact zero, scatter_negated the dense matrices negated, each pair's
    !> blocks read whole (q_block, u_block) the dense matrices' (a UCON's second partials
    !> written by pairs of parts, subtract_q_over, among the writes); a write to a pair not
    !> held is noted as missed (not lost silently; subtract_q_over's both ways round) and grow
    !> holds it from then on, keeping the pairs held before.
    subroutine test_pairs_as_dense(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: parts = 4, n = 6*parts
        type(momentum_partials_type) :: blocks, dense
        real(wp) :: x(n, 2*n), values(6), block(6, 6), second(4, 4), held(6, 6), full(6, 6), &
            & before
        integer :: i, j, k, a, b, step, at(4)

        call blocks%init_blocks(parts, reshape([1, 2, 3, 2, 2, 1, 0, 4], [2, 4]))
        call dense%init_dense(n)
        ! pairs held: each part with itself, (1, 2), (2, 3) both ways (repeats and ground
        ! dropped): 4 + 4 blocks
        call check(error, size(blocks%block_q, 3) == 8, "blocks held: " &
            & // to_text(size(blocks%block_q, 3)))
        if (allocated(error)) return
        do step = 1, 40
            ! a deterministic spread of writes over the held pairs
            a = mod(step, parts) + 1
            b = a
            if (mod(step, 3) == 1 .and. a <= 3) b = merge(2, a + 1, a == 3)
            if (mod(step, 3) == 2 .and. a == 2) b = 1
            k = mod(7*step, 6) + 1
            do i = 1, 6
                values(i) = sin(1.3_wp*step + 0.7_wp*i)
            end do
            block = reshape([(cos(0.1_wp*step*i), i = 1, 36)], [6, 6])
            select case (mod(step, 4))
            case (0)
                call blocks%subtract_q(a, b, k, 1, values(:3))
                call dense%subtract_q(a, b, k, 1, values(:3))
                call blocks%subtract_u(a, b, k, 4, values(4:))
                call dense%subtract_u(a, b, k, 4, values(4:))
            case (1)
                call blocks%subtract_q(a, b, k, 1, values)
                call dense%subtract_q(a, b, k, 1, values)
                call blocks%subtract_u(a, b, k, 1, values)
                call dense%subtract_u(a, b, k, 1, values)
            case (2)
                call blocks%subtract_q_entry(6*(a - 1) + k, 6*(b - 1) + 7 - k, values(2))
                call dense%subtract_q_entry(6*(a - 1) + k, 6*(b - 1) + 7 - k, values(2))
                ! a UCON's second partials over some coordinates of parts a and b, ascending
                ! (both of part a when b = a), straight and transposed
                at = [6*(min(a, b) - 1) + 2, 6*(min(a, b) - 1) + 5, 6*(max(a, b) - 1) + 1, &
                    & 6*(max(a, b) - 1) + 6]
                if (a == b) at = 6*(a - 1) + [1, 3, 4, 6]
                second = reshape([(sin(0.3_wp*step + 0.2_wp*i), i = 1, 16)], [4, 4])
                call blocks%subtract_q_over(at, values(3), second, mod(step, 8) == 6)
                call dense%subtract_q_over(at, values(3), second, mod(step, 8) == 6)
            case default
                if (step < 10) then
                    call blocks%set_part(a, block, -block)
                    call dense%set_part(a, block, -block)
                end if
            end select
        end do
        call check(error, blocks%missed_count == 0, "no write missed a held pair")
        if (allocated(error)) return
        do j = 1, n
            do i = 1, n
                a = (i - 1)/6 + 1
                b = (j - 1)/6 + 1
                if (blocks%pair(a, b) > 0) then
                    call check(error, blocks%q_at(i, j) == dense%dq(i, j) .and. &
                        & blocks%u_at(i, j) == dense%du(i, j), "entry (" // to_text(i) // ", " &
                        & // to_text(j) // ") as dense: " // to_text(blocks%q_at(i, j)) &
                        & // " against " // to_text(dense%dq(i, j)))
                else
                    call check(error, dense%dq(i, j) == 0.0_wp .and. dense%du(i, j) == 0.0_wp &
                        & .and. blocks%q_at(i, j) == 0.0_wp, "entry (" // to_text(i) // ", " &
                        & // to_text(j) // ") off the pairs is zero")
                end if
                if (allocated(error)) return
            end do
        end do
        call blocks%scatter_negated(x)
        call check(error, all(x(:, :n) == -dense%dq) .and. all(x(:, n + 1:) == -dense%du), &
            & "scatter_negated gives -dm/dq, -dm/du")
        if (allocated(error)) return
        ! each pair's blocks read whole (q_block, u_block) as the dense matrices hold them,
        ! zeros off the pairs
        do b = 1, parts
            do a = 1, parts
                call blocks%q_block(a, b, held)
                call dense%q_block(a, b, full)
                call check(error, all(held == dense%dq(6*a - 5:6*a, 6*b - 5:6*b)) .and. &
                    & all(full == held), "dm/dq's block (" // to_text(a) // ", " &
                    & // to_text(b) // ") as dense")
                if (allocated(error)) return
                call blocks%u_block(a, b, held)
                call dense%u_block(a, b, full)
                call check(error, all(held == dense%du(6*a - 5:6*a, 6*b - 5:6*b)) .and. &
                    & all(full == held), "dm/du's block (" // to_text(a) // ", " &
                    & // to_text(b) // ") as dense")
                if (allocated(error)) return
            end do
        end do
        ! part 4 joins no other part: a write to (1, 4) is missed, then held after grow (both
        ! ways round: 10 blocks)
        call blocks%subtract_q(1, 4, 2, 1, [1.0_wp])
        call check(error, blocks%missed_count == 1 .and. blocks%q_at(1, 20) == 0.0_wp, &
            & "a write outside the pairs is noted as missed")
        if (allocated(error)) return
        call blocks%grow()
        call blocks%subtract_q(1, 4, 2, 1, [1.0_wp])
        call check(error, blocks%missed_count == 0 .and. blocks%q_at(1, 20) == -1.0_wp .and. &
            & size(blocks%block_q, 3) == 10 .and. blocks%pair(2, 3) > 0, "grow holds the " &
            & // "missed pair and the pairs before")
        if (allocated(error)) return
        ! a UCON over parts 3 and 4, which no pair joins: both ways round noted as missed, each
        ! part's own entries written
        before = blocks%q_at(19, 19)
        call blocks%subtract_q_over([13, 19], 1.0_wp, reshape([1.0_wp, 2.0_wp, 3.0_wp, &
            & 4.0_wp], [2, 2]), .false.)
        call check(error, blocks%missed_count == 2 .and. blocks%q_at(19, 19) == before - 4.0_wp, &
            & "subtract_q_over notes the pairs not held: " // to_text(blocks%missed_count))
    end subroutine test_pairs_as_dense

end module test_force_partials
