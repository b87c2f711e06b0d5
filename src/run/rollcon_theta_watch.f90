! SPDX-License-Identifier: MIT
!> Every part's Euler-angle limit: its 3-1-3 angles are singular where theta is 0 or pi (the
!> principal z-axis along ground Z). One event function per part, sin(theta) - sin(theta_min),
!> guards both sides of flat. When it fires the run either stops (a limit the input sets) or
!> re-bases the part's principal axes and goes on (docs/rebasing.md); a watch that re-bases
!> adds a column `basis_<id>` per part (the number of the basis its coordinates are in) and a
!> summary line of the re-basings, and gives the model back its own axes before the next run.
module rollcon_theta_watch
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_body, only : part_type
    use rollcon_force, only : applied_force_type
    use rollcon_model, only : ucon_statement_type, statement_type
    use rollcon_equations, only : equations_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_output_layout, only : name_length
    use rollcon_watch, only : watch_type, watch_event_type, action_stop, action_rebase
    use rollcon_rebasing, only : turn_about_y, next_basis
    implicit none
    private

    public :: theta_watch_type, new_theta_watch

    type, extends(watch_type) :: theta_watch_type
        !> The limit [rad]: how near 0 or pi theta may come (< 0: not watched)
        real(wp) :: theta_min = 0.05_wp
        !> Re-base at the limit and go on (true), or stop there (false)
        logical :: rebase = .false.
        !> For each part (model order), the words of a stop at its limit in place of "its
        !> principal z-axis is nearly along ground Z" ("" for those): what the part is
        !> ("the coin lies nearly flat")
        character(len=:), allocatable :: flat_words
        !> The part whose stop uses flat_words (0: none)
        integer :: worded_part = 0
        !> For each part (model order), its re-basings in the run so far
        integer, allocatable :: bases(:)
        !> For each part (model order), its re-basings about body y in the run so far
        integer, allocatable :: turns_about_y(:)
        !> For each part (model order), the number of the basis its coordinates are in
        !> (rollcon_rebasing's basis_axes: 0 for its own principal axes)
        integer, allocatable :: basis_numbers(:)
        !> The parts, forces, UCONs (a joint's geometry in PAR) and statements (a joint's marker
        !> I) in the parts' own principal axes, as prepare found them: a run that re-based parts
        !> leaves the model turned; the next prepare gives it back its own axes
        type(part_type), allocatable :: own_parts(:)
        type(applied_force_type), allocatable :: own_forces(:)
        type(ucon_statement_type), allocatable :: own_ucons(:)
        type(statement_type), allocatable :: own_statements(:)
    contains
        procedure :: prepare
        procedure :: root_count
        procedure :: roots
        procedure :: fired
        procedure :: part_rebased
        procedure :: parts_to_rebase
        procedure :: column_names
        procedure :: fill_columns
        procedure :: summary_lines
    end type theta_watch_type

contains

    !> A watch of every part's theta limit [rad], re-basing there or stopping.
    function new_theta_watch(theta_min, rebase) result(watch)
        real(wp), intent(in) :: theta_min
        logical, intent(in) :: rebase
        type(theta_watch_type) :: watch

        watch%theta_min = theta_min
        watch%rebase = rebase
    end function new_theta_watch

    !> Give the model back its parts' own axes after a run that re-based them; no re-basing yet.
    subroutine prepare(self, eq, settings, error)
        class(theta_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error

        if (allocated(self%bases) .and. allocated(self%own_parts)) then
            if (any(self%bases /= 0)) then
                eq%model%parts = self%own_parts
                eq%model%forces = self%own_forces
                if (allocated(self%own_ucons)) eq%model%ucons = self%own_ucons
                if (allocated(self%own_statements)) eq%model%statements = self%own_statements
            end if
        end if
        if (self%rebase) then
            self%own_parts = eq%model%parts
            self%own_forces = eq%model%forces
            if (allocated(eq%model%ucons)) self%own_ucons = eq%model%ucons
            if (allocated(eq%model%statements)) self%own_statements = eq%model%statements
        end if
        if (allocated(self%bases)) deallocate(self%bases)
        allocate(self%bases(size(eq%model%parts)), source=0)
        self%turns_about_y = self%bases
        self%basis_numbers = self%bases
    end subroutine prepare

    !> One per part (none when theta_min < 0: the limit is off).
    pure integer function root_count(self, eq)
        class(theta_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        root_count = 0
        if (self%theta_min >= 0.0_wp) root_count = size(eq%model%parts)
    end function root_count

    !> sin(theta_p) - sin(theta_min) for every part p.
    subroutine roots(self, eq, settings, time, q, u, g, error, lambda, a)
        class(theta_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: g(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in), optional :: lambda(:), a(:)
        integer :: p

        do p = 1, size(g)
            g(p) = sin(q(6*(p - 1) + 5)) - sin(self%theta_min)
        end do
    end subroutine roots

    !> Part k reached its limit: re-base it, or stop with the singularity it came near (body
    !> z-axis along ground +Z at theta = 0, along -Z at theta = pi).
    function fired(self, eq, k, time, q, u) result(event)
        class(theta_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        type(watch_event_type) :: event

        event%part = k
        event%limit = "theta_limit"
        if (self%rebase) then
            event%action = action_rebase
            event%message = ""
            return
        end if
        event%action = action_stop
        associate (psi => q(6*k - 2), theta => q(6*k - 1), psidot => u(6*k - 2))
            if (k == self%worded_part) then
                event%message = limit_words(self%theta_min, theta) // to_text(time) // " s: " &
                    & // self%flat_words // ", where the 3-1-3 Euler angles become singular " &
                    & // "(psi = " // to_text(psi) // " rad, psidot = " // to_text(psidot) &
                    & // " rad/s)"
                return
            end if
            event%message = "part " // to_text(eq%model%parts(k)%id) // ": " &
                & // limit_words(self%theta_min, theta) // to_text(time) // " s: its principal " &
                & // "z-axis is nearly along ground " // trim(merge("+Z (theta = 0) ", &
                & "-Z (theta = pi)", cos(theta) >= 0.0_wp)) // ", the singularity of the 3-1-3 " &
                & // "Euler angles, where psi and phi are no longer defined apart (psi = " &
                & // to_text(psi) // " rad, psidot = " // to_text(psidot) // " rad/s)"
        end associate
    end function fired

    !> "theta fell to the limit theta_min = ... rad at t = " on the theta = 0 side, "theta rose
    !> to pi - theta_min = ... rad (the limit ...) at t = " on the other.
    function limit_words(theta_min, theta) result(words)
        real(wp), intent(in) :: theta_min, theta
        character(len=:), allocatable :: words

        if (cos(theta) >= 0.0_wp) then
            words = "theta fell to the limit theta_min = " // to_text(theta_min) // " rad at t = "
        else
            words = "theta rose to pi - theta_min = " // to_text(pi - theta_min) &
                & // " rad (the limit theta_min = " // to_text(theta_min) &
                & // " rad from flat on the theta = pi side) at t = "
        end if
    end function limit_words

    subroutine part_rebased(self, p, turn)
        class(theta_watch_type), intent(inout) :: self
        !> The part (model order) and the re-basing's turn (rollcon_rebasing)
        integer, intent(in) :: p, turn

        self%bases(p) = self%bases(p) + 1
        if (turn == turn_about_y) self%turns_about_y(p) = self%turns_about_y(p) + 1
        self%basis_numbers(p) = next_basis(self%basis_numbers(p), turn)
    end subroutine part_rebased

    !> With re-basing, every part whose sin(theta) is at or below sin(theta_min) at the start.
    function parts_to_rebase(self, eq, q) result(parts)
        class(theta_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: q(:)
        integer, allocatable :: parts(:)
        integer :: p

        allocate(parts(0))
        if (.not. self%rebase .or. self%theta_min < 0.0_wp) return
        parts = pack([(p, p = 1, size(eq%model%parts))], &
            & [(sin(q(6*p - 1)) <= sin(self%theta_min), p = 1, size(eq%model%parts))])
    end function parts_to_rebase

    !> basis_<id> for every part, when the watch re-bases.
    subroutine column_names(self, eq, names)
        class(theta_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)
        integer :: p

        allocate(names(0))
        if (.not. self%rebase) return
        deallocate(names)
        allocate(names(size(eq%model%parts)))
        do p = 1, size(names)
            names(p) = "basis_" // to_text(eq%model%parts(p)%id)
        end do
    end subroutine column_names

    !> Each part's basis number (rollcon_rebasing's basis_axes).
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(theta_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)

        if (size(values) > 0) values = real(self%basis_numbers, wp)
    end subroutine fill_columns

    !> "re-basings of the principal axes (docs/rebasing.md): part 1: 0, part 2: 104 (100
    !> about x, 4 about y)".
    function summary_lines(self, eq) result(text)
        class(theta_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=:), allocatable :: text
        integer :: p

        text = ""
        if (.not. self%rebase .or. .not. allocated(self%bases)) return
        text = "re-basings of the principal axes (docs/rebasing.md):"
        do p = 1, size(self%bases)
            if (p > 1) text = text // ","
            text = text // " part " // to_text(eq%model%parts(p)%id) // ": " &
                & // to_text(self%bases(p))
            if (self%bases(p) > 0) text = text // " (" &
                & // to_text(self%bases(p) - self%turns_about_y(p)) // " about x, " &
                & // to_text(self%turns_about_y(p)) // " about y)"
        end do
        text = text // new_line("a")
    end function summary_lines

end module rollcon_theta_watch
