! SPDX-License-Identifier: MIT
!> Every statement's reaction as output columns (docs/outputs.md, "Reactions";
!> rollcon_reactions): `joint<id>_fx, _fy, _fz, _tx, _ty, _tz` the force and torque a JOINT
!> exerts on the part of its marker I, at marker I, in ground axes [N, N m] (`jprim<id>_...`
!> a JPRIM's), `ucon<id>_...` the force and torque a UCON exerts on its part at the part's
!> centre of mass (`ucon<id>_part<part id>_...` for each of several parts); and the summary's
!> largest force and torque of each. A dataset's REQUEST/id, FORCE between a JOINT's or
!> JPRIM's two markers (model%force_requests) is answered by `req<id>_fx ... _tz`: the same
!> reaction on the part of the request's marker I, at I (ADAMS's force request, in ground axes):
!> the statement's own when the markers are in its order, else the reaction on J's part, equal
!> and opposite, its moment taken about J. Where equations are redundant (rollcon_redundancy) the
!> reactions of the statements in a dependency are not unique: the split of least norm is
!> reported, and the summary says so.
module rollcon_reaction_watch
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_equations, only : equations_type
    use rollcon_reactions, only : reaction_site_type, reaction_sites, site_wrench, &
        & swapped_wrench, part_attitude_type, part_attitude
    use rollcon_run_settings, only : run_settings_type
    use rollcon_output_layout, only : name_length
    use rollcon_watch_columns, only : suffixes => reaction_suffixes
    use rollcon_watch, only : watch_type
    implicit none
    private

    public :: reaction_watch_type

    type, extends(watch_type) :: reaction_watch_type
        !> Where each statement's reaction is reported (rollcon_reactions)
        type(reaction_site_type), allocatable :: sites(:)
        !> The largest |force| [N] and |torque| [N m] of each site over the output rows
        real(wp), allocatable :: largest(:, :)
        !> For each of the model's force requests, the site of its statement
        integer, allocatable :: request_sites(:)
        !> The parts the sites are on (model order, each once), their attitudes at the row
        !> (made once a row for all the sites on a part), and each site's entry in them
        integer, allocatable :: parts(:), site_part(:)
        type(part_attitude_type), allocatable :: attitudes(:)
    contains
        procedure :: prepare
        procedure :: column_names
        procedure :: fill_columns
        procedure :: summary_lines
    end type reaction_watch_type

contains

    !> The model's sites; no row yet.
    subroutine prepare(self, eq, settings, error)
        class(reaction_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error

        integer :: r, i, p
        logical :: used(size(eq%model%parts))

        self%sites = reaction_sites(eq%model)
        if (allocated(self%largest)) deallocate(self%largest)
        allocate(self%largest(2, size(self%sites)), source=0.0_wp)
        used = .false.
        do i = 1, size(self%sites)
            p = self%sites(i)%part
            if (p >= 1 .and. p <= size(used)) used(p) = .true.
        end do
        self%parts = pack([(p, p = 1, size(used))], used)
        ! each site's entry in parts; 0 for a site on no part (site_wrench then makes its own)
        self%site_part = [(findloc(self%parts, self%sites(i)%part, dim=1), &
            & i = 1, size(self%sites))]
        if (allocated(self%attitudes)) deallocate(self%attitudes)
        allocate(self%attitudes(size(self%parts)))
        ! a second prepare (the bench prepares one problem twice) starts again from none
        if (allocated(self%request_sites)) deallocate(self%request_sites)
        allocate(self%request_sites(0))
        if (.not. allocated(eq%model%force_requests)) return
        do r = 1, size(eq%model%force_requests)
            i = findloc(self%sites%statement, eq%model%force_requests(r)%statement, dim=1)
            self%request_sites = [self%request_sites, i]
        end do
    end subroutine prepare

    !> Six per site: `<stem>_fx ... <stem>_tz`; then six per force request, `req<id>_fx ...`.
    subroutine column_names(self, eq, names)
        class(reaction_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)
        integer :: i, c, n

        ! no sites before prepare (a watch before it refused the model)
        if (.not. allocated(self%sites)) then
            allocate(names(0))
            return
        end if
        allocate(names(6*(size(self%sites) + size(self%request_sites))))
        do i = 1, size(self%sites)
            do c = 1, 6
                names(6*(i - 1) + c) = self%sites(i)%stem // trim(suffixes(c))
            end do
        end do
        n = 6*size(self%sites)
        do i = 1, size(self%request_sites)
            do c = 1, 6
                names(n + 6*(i - 1) + c) = "req" // to_text(eq%model%force_requests(i)%id) &
                    & // trim(suffixes(c))
            end do
        end do
    end subroutine column_names

    !> Each site's force and torque at the row, from the rows of C as the run's last evaluation
    !> at this state left them and the multipliers reported (the least-norm split where rows are
    !> set aside); the largest kept.
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(reaction_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)
        integer :: i, n

        do i = 1, size(self%parts)
            self%attitudes(i) = part_attitude(q, self%parts(i))
        end do
        do i = 1, size(self%sites)
            associate (wrench => values(6*i - 5:6*i))
                if (self%site_part(i) > 0) then
                    wrench = site_wrench(eq%model, self%sites(i), eq%c, lambda, q, &
                        & self%attitudes(self%site_part(i)))
                else
                    wrench = site_wrench(eq%model, self%sites(i), eq%c, lambda, q)
                end if
                self%largest(1, i) = max(self%largest(1, i), norm2(wrench(1:3)))
                self%largest(2, i) = max(self%largest(2, i), norm2(wrench(4:6)))
            end associate
        end do
        n = 6*size(self%sites)
        do i = 1, size(self%request_sites)
            associate (wrench => values(n + 6*i - 5:n + 6*i), &
                    & site => values(6*self%request_sites(i) - 5:6*self%request_sites(i)))
                wrench = site
                if (eq%model%force_requests(i)%swapped) wrench = swapped_wrench(eq%model, &
                    & self%sites(self%request_sites(i)), site, q)
            end associate
        end do
    end subroutine fill_columns

    !> "largest reactions (...): JOINT/1 (line 14): 24.5 N, 0 N m; ..." and, where equations
    !> are redundant, which statements' reactions are the least-norm split.
    function summary_lines(self, eq) result(text)
        class(reaction_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=:), allocatable :: text, shared
        logical, allocatable :: split(:)
        integer :: i, s

        text = ""
        if (.not. allocated(self%sites)) return
        if (size(self%sites) == 0) return
        text = "largest reactions (docs/outputs.md: a JOINT's or JPRIM's force and torque on " &
            & // "the part of its marker I, at I; a UCON's on each part it holds, at its " &
            & // "centre of mass):"
        do i = 1, size(self%sites)
            if (i > 1) text = text // ";"
            text = text // " " // eq%model%statement_name(self%sites(i)%statement)
            if (index(self%sites(i)%stem, "_part") > 0) text = text // " on PART/" &
                & // to_text(eq%model%parts(self%sites(i)%part)%id)
            text = text // " " // short(self%largest(1, i)) // " N, " &
                & // short(self%largest(2, i)) // " N m"
        end do
        text = text // new_line("a")
        if (.not. allocated(eq%redundancy%involved)) return
        if (.not. any(eq%redundancy%involved)) return
        allocate(split(size(eq%model%statements)), source=.false.)
        do i = 1, eq%nc
            if (eq%redundancy%involved(i)) split(eq%model%ucons(i)%statement) = .true.
        end do
        shared = ""
        do s = 1, size(split)
            if (.not. split(s)) cycle
            if (len(shared) > 0) shared = shared // ", "
            shared = shared // eq%model%statement_name(s)
        end do
        text = text // "reactions not unique (redundant equations): " // shared &
            & // " share forces that any split of theirs balances; the split reported is " &
            & // "the least-norm one (docs/design.md §4)" // new_line("a")
    end function summary_lines

    !> A magnitude in 4 significant digits.
    function short(x) result(text)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=32) :: value

        write(value, '(es11.4e2)') x
        text = trim(adjustl(value))
    end function short

end module rollcon_reaction_watch
