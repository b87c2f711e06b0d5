! SPDX-License-Identifier: MIT
!> An ADAMS dataset as a job's model source (rollcon_model_source): its parts, UCONs, forces and
!> run (rollcon_adm_build), with the dataset's INTEGRATOR and SIMULATE settings or those a
!> caller put in their place, and its start made consistent by the initial-conditions analysis
!> (docs/initial-conditions.md), as ADAMS does before a dynamic run, with the equations that
!> repeat others set aside there (rollcon_redundancy) named in its report. Its warning names the
!> statements of ADAMS's outputs and solver choices it read and does not use; its report
!> gives, before the analysis's, the principal moments and axes of every part whose IP has
!> products of inertia. Its notes (in the summary) give those and each REQUEST's COMMENT with
!> the columns that answer it (request_comments_text).
module rollcon_dataset_source
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_rotation, only : euler_angles
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_ucosub_catalog, only : find_builtin_ucosub
    use rollcon_model, only : served_by_model_ucosub
    use rollcon_problem, only : problem_type
    use rollcon_model_source, only : model_source_type
    use rollcon_initial_conditions, only : analyse_initial_conditions
    use rollcon_ic_report, only : ic_report_type, ic_report_text
    use rollcon_adm_model, only : adm_model_type, adm_request_type, request_displacement, &
        & request_velocity, request_acceleration, request_force, request_expressions, &
        & request_user
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_adm_initial, only : adm_ic_options
    implicit none
    private

    public :: dataset_source_type, new_dataset_source

    type, extends(model_source_type) :: dataset_source_type
        !> The dataset as read (its run settings are the source's `settings` from here on)
        type(adm_model_type) :: adm
        !> principal_axes_text of adm, made once for the notes and the report (its parts do not
        !> change after new_dataset_source)
        character(len=:), allocatable :: principal_axes
    contains
        procedure :: build
    end type dataset_source_type

contains

    !> The source of a dataset that was read and checked, read from path.
    function new_dataset_source(adm, path) result(source)
        type(adm_model_type), intent(in) :: adm
        character(len=*), intent(in) :: path
        type(dataset_source_type) :: source
        integer :: slash

        source%adm = adm
        source%path = path
        slash = index(path, "/", back=.true.)
        source%name = path(slash + 1:len_trim(path) - 4)
        source%kind = "dataset"
        source%settings = adm%run%settings
        source%warning = ""
        if (allocated(adm%warning)) source%warning = adm%warning
        source%principal_axes = principal_axes_text(adm)
        source%notes = source%principal_axes // request_comments_text(adm)
        source%own_routines = all_named(adm)
        source%no_ucons = .true.
        if (allocated(adm%ucons)) source%no_ucons = size(adm%ucons) == 0
    end function new_dataset_source

    !> The dataset's problem with the source's settings, and its start after the
    !> initial-conditions analysis (its report in report).
    subroutine build(self, ucosub, problem, q0, u0, report, error)
        class(dataset_source_type), intent(inout) :: self
        procedure(ucosub_interface), pointer, intent(in) :: ucosub
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        type(ic_report_type) :: analysis

        report = ""
        self%adm%run%settings = self%settings
        call build_adm_problem(self%adm, ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        ! as ADAMS before a dynamic run: the least change that meets every UCON
        call analyse_initial_conditions(problem, 0.0_wp, q0, u0, adm_ic_options(self%adm, &
            & problem), analysis, error)
        if (allocated(error)) then
            error%message = self%path // ": " // error%message
            return
        end if
        if (.not. allocated(self%principal_axes)) &
            & self%principal_axes = principal_axes_text(self%adm)
        report = self%principal_axes // ic_report_text(analysis)
        ! the equations the run sets aside as redundant, chosen at this start: said once here,
        ! before the run (a contradictory set is refused), and in the summary
        call problem%choose_rows(0.0_wp, q0, u0, error)
        if (allocated(error)) then
            error%message = self%path // ": initial conditions: " // error%message
            return
        end if
        if (len(problem%set_aside_text) > 0) report = report // new_line("a") &
            & // "  warning: redundant equations set aside (docs/design.md §4): " &
            & // problem%set_aside_text
    end subroutine build

    !> For each part whose IP has products of inertia, two lines: its principal moments and
    !> the principal axes in its CM marker's axes, with the 3-1-3 Euler angles of the turn
    !> from those axes onto them; "" when no part has products.
    function principal_axes_text(adm) result(text)
        type(adm_model_type), intent(in) :: adm
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a"), names = "xyz"
        real(wp) :: angles(3)
        integer :: i, k

        text = ""
        do i = 1, size(adm%parts)
            associate (part => adm%parts(i))
                if (part%ground .or. all(part%products == 0.0_wp)) cycle
                angles = euler_angles(part%principal)
                text = text // "principal axes of PART/" // to_text(part%id) // " (IP with " &
                    & // "products of inertia): moments " // to_text(part%ip(1)) // ", " &
                    & // to_text(part%ip(2)) // ", " // to_text(part%ip(3)) // " kg m^2 about " &
                    & // "x, y, z; turned from its CM marker's axes (MARKER/" &
                    & // to_text(part%cm) // ") by the 3-1-3 Euler angles " &
                    & // to_text(angles(1)) // ", " // to_text(angles(2)) // ", " &
                    & // to_text(angles(3)) // " rad" // nl // " "
                do k = 1, 3
                    text = text // " " // names(k:k) // " = (" // to_text(part%principal(1, k)) &
                        & // ", " // to_text(part%principal(2, k)) // ", " &
                        & // to_text(part%principal(3, k)) // ")"
                end do
                text = text // " in the CM marker's axes" // nl
            end associate
        end do
    end function principal_axes_text

    !> One line per REQUEST that has a COMMENT (`C=`), in the order of the file: the request,
    !> its line, the columns that answer it (docs/outputs.md) and the comment as written:
    !> "REQUEST/2 (line 13; req2_fx ... req2_tz): JOINT FORCE"; a request whose every
    !> expression is named in the warning, or a REQSUB's, says it has no column. "" when no
    !> request has a comment.
    function request_comments_text(adm) result(text)
        type(adm_model_type), intent(in) :: adm
        character(len=:), allocatable :: text
        type(adm_request_type), allocatable :: listed(:)
        logical, allocatable :: done(:)
        integer :: n, first

        text = ""
        allocate(listed(0))
        if (allocated(adm%requests)) listed = [listed, adm%requests]
        if (allocated(adm%force_requests)) listed = [listed, adm%force_requests]
        if (allocated(adm%other_requests)) listed = [listed, adm%other_requests]
        allocate(done(size(listed)), source=.false.)
        do n = 1, size(listed)
            if (allocated(listed(n)%comment)) done(n) = len(listed(n)%comment) == 0
            if (.not. allocated(listed(n)%comment)) done(n) = .true.
        end do
        do while (.not. all(done))
            first = minloc(listed%line, dim=1, mask=.not. done)
            done(first) = .true.
            associate (request => listed(first))
                text = text // "REQUEST/" // to_text(request%id) // " (line " &
                    & // to_text(request%line) // "; " // request_columns(request) // "): " &
                    & // request%comment // new_line("a")
            end associate
        end do
    end function request_comments_text

    !> The columns that answer a request, in words: "req2_fx ... req2_tz", "req3_f2, req3_f4",
    !> or "no column: see the warning".
    function request_columns(request) result(text)
        type(adm_request_type), intent(in) :: request
        character(len=:), allocatable :: text
        character(len=:), allocatable :: stem
        integer :: k

        stem = "req" // to_text(request%id)
        select case (request%kind)
        case (request_displacement)
            text = stem // "_x ... " // stem // "_phi"
        case (request_velocity)
            text = stem // "_vx ... " // stem // "_wz"
        case (request_acceleration)
            text = stem // "_accx ... " // stem // "_wdtz"
        case (request_force)
            text = stem // "_fx ... " // stem // "_tz"
        case (request_expressions)
            text = ""
            do k = 1, size(request%columns)
                if (len(request%columns(k)%text) == 0) cycle
                if (len(text) > 0) text = text // ", "
                text = text // stem // "_f" // to_text(k)
            end do
            if (len(text) == 0) text = "no column: see the warning"
        case default
            text = "no column: see the warning"
        end select
    end function request_columns

    !> The model's UCOSUB serves none of the dataset's UCONs (each names its ROUTINE; the
    !> joints' UCONs always have theirs): rollcon_model's served_by_model_ucosub.
    logical function all_named(adm)
        type(adm_model_type), intent(in) :: adm
        procedure(ucosub_interface), pointer :: builtin
        logical :: time_free, found
        integer :: k

        all_named = .true.
        ! a force served by the model's own SFOSUB, VFOSUB or GFOSUB needs the user's file
        if (allocated(adm%forces)) then
            do k = 1, size(adm%forces)
                if (adm%forces(k)%user) all_named = .false.
            end do
        end if
        ! so does a REQUEST served by a REQSUB, a VARIABLE by a VARSUB
        if (allocated(adm%other_requests)) then
            if (any(adm%other_requests%kind == request_user)) all_named = .false.
        end if
        if (allocated(adm%variables)) then
            if (any(adm%variables%user)) all_named = .false.
        end if
        ! and a MOTION by a MOTSUB
        if (allocated(adm%motions)) then
            if (any(adm%motions%user)) all_named = .false.
        end if
        ! and a DIFF by a DIFSUB
        if (allocated(adm%diffs)) then
            if (any(adm%diffs%user)) all_named = .false.
        end if
        if (.not. allocated(adm%ucons)) return
        do k = 1, size(adm%ucons)
            if (served_by_model_ucosub(adm%ucons(k)%routine)) all_named = .false.
            ! a routine of a user's file (ROUTINE=FILE::NAME) needs that file
            call find_builtin_ucosub(trim(adm%ucons(k)%routine), builtin, time_free, found)
            if (.not. found) all_named = .false.
        end do
    end function all_named

end module rollcon_dataset_source
