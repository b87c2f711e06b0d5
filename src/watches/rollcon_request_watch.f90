! SPDX-License-Identifier: MIT
!> Displacement requests (a dataset's REQUEST/id, DISPLACEMENT, I=i, J=j, RM=rm): each adds six
!> columns to every output row, the displacement of marker I from marker J as ADAMS measures it:
!>
!> - `req<id>_x`, `req<id>_y`, `req<id>_z` [m]: the vector from J's origin to I's origin
!>   (from the ground origin without J), in the axes of RM (ground axes without RM);
!> - `req<id>_psi`, `req<id>_theta`, `req<id>_phi` [rad]: the body-fixed 3-1-3 Euler angles
!>   of I's axes in J's axes (in ground axes without J), whatever RM.
!>
!> The markers are body-fixed (rollcon_marker): a re-basing of a part's principal axes
!> (docs/rebasing.md) turns the watch's markers on it as it turns the model's, so the columns
!> are those of the same physical markers in any basis.
module rollcon_request_watch
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_rotation, only : euler_angles, transpose_times
    use rollcon_marker, only : marker_type, marker_motion, turn_marker
    use rollcon_equations, only : equations_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_output_layout, only : name_length
    use rollcon_watch_columns, only : request_column_patterns
    use rollcon_watch, only : watch_type
    implicit none
    private

    public :: request_watch_type, displacement_request_type, new_request_watch
    public :: request_column_name

    !> What each request's columns hold, in order (the column req<id>_<suffix>)
    character(len=*), parameter :: suffixes(6) = [character(len=5) :: "x", "y", "z", "psi", &
        & "theta", "phi"]

    !> One request: its id and its markers as the model holds them (rollcon_marker)
    type :: displacement_request_type
        integer :: id = 0
        !> The marker measured
        type(marker_type) :: i
        !> The marker it is measured from, and the one whose axes resolve x, y, z; a marker on
        !> ground at the origin with ground axes when the request names none
        type(marker_type) :: j, rm
    end type displacement_request_type

    type, extends(watch_type) :: request_watch_type
        !> The requests in the model's current axes
        type(displacement_request_type), allocatable :: requests(:)
        !> The requests as given, in each part's own principal axes (basis 0)
        type(displacement_request_type), allocatable :: own(:)
    contains
        procedure :: prepare
        procedure :: part_rebased
        procedure :: column_names
        procedure :: fill_columns
    end type request_watch_type

contains

    !> A watch of these requests, their markers in their parts' own principal axes.
    function new_request_watch(requests) result(watch)
        type(displacement_request_type), intent(in) :: requests(:)
        type(request_watch_type) :: watch

        watch%own = requests
        watch%requests = requests
    end function new_request_watch

    !> The column name of quantity k (1..6: x, y, z, psi, theta, phi) of request id.
    pure function request_column_name(id, k) result(name)
        integer, intent(in) :: id, k
        character(len=name_length) :: name

        name = "req" // to_text(id) // "_" // trim(suffixes(k))
    end function request_column_name

    !> Every marker on a part of the model; the markers as given (a run that re-based parts
    !> left them turned).
    subroutine prepare(self, eq, settings, error)
        class(request_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error
        integer :: k

        self%requests = self%own
        do k = 1, size(self%requests)
            associate (r => self%requests(k))
                if (any([r%i%part, r%j%part, r%rm%part] < 0 .or. [r%i%part, r%j%part, &
                    & r%rm%part] > size(eq%model%parts))) then
                    call fatal_error(error, "request " // to_text(r%id) // ": a marker is on " &
                        & // "part number " // to_text(maxval([r%i%part, r%j%part, &
                        & r%rm%part])) // " in model order; the model has " &
                        & // to_text(size(eq%model%parts)) // " parts", stat_input)
                    return
                end if
            end associate
        end do
    end subroutine prepare

    !> Part p's principal axes were turned: its markers in the new axes, as the model's.
    subroutine part_rebased(self, p, turn)
        class(request_watch_type), intent(inout) :: self
        !> The part (model order) and the re-basing's turn (rollcon_rebasing)
        integer, intent(in) :: p, turn
        integer :: k

        do k = 1, size(self%requests)
            call turn_marker(self%requests(k)%i, p, turn)
            call turn_marker(self%requests(k)%j, p, turn)
            call turn_marker(self%requests(k)%rm, p, turn)
        end do
    end subroutine part_rebased

    !> req<id>_x ... req<id>_phi for every request.
    subroutine column_names(self, eq, names)
        class(request_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)
        integer :: r, k

        allocate(names(size(suffixes)*size(self%requests)))
        do r = 1, size(self%requests)
            do k = 1, size(suffixes)
                names(size(suffixes)*(r - 1) + k) = request_column_name(self%requests(r)%id, k)
            end do
        end do
    end subroutine column_names

    !> The displacement of each request's I marker from its J marker (module header).
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(request_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)
        real(wp) :: point_i(3), point_j(3), point_rm(3), velocity(3), omega(3)
        real(wp) :: axes_i(3, 3), axes_j(3, 3), axes_rm(3, 3), relative(3, 3)
        integer :: r, first, a, b

        do r = 1, size(self%requests)
            associate (request => self%requests(r))
                call marker_motion(request%i, q, u, point_i, velocity, axes_i, omega)
                call marker_motion(request%j, q, u, point_j, velocity, axes_j, omega)
                call marker_motion(request%rm, q, u, point_rm, velocity, axes_rm, omega)
            end associate
            first = size(suffixes)*(r - 1)
            values(first + 1:first + 3) = transpose_times(axes_rm, point_i - point_j)
            ! I's axes in J's: entry by entry (the hot path allocates nothing)
            do b = 1, 3
                do a = 1, 3
                    relative(a, b) = dot_product(axes_j(:, a), axes_i(:, b))
                end do
            end do
            values(first + 4:first + 6) = euler_angles(relative)
        end do
    end subroutine fill_columns

end module rollcon_request_watch
