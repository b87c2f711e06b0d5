! SPDX-License-Identifier: MIT
!> The layout suite's model of two independent parts, built in code, and a reader of the CSV a
!> run writes (any layout): part 2 is the paper's disk, rolling straight and upright at
!> 1 m/s under three no-slip UCONs (11, 12, 13); part 5 is a free body with no UCON, thrown up
!> and sideways while spinning about its principal z-axis, which lies horizontal.
module layout_models
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    use rollcon_kinds, only : wp
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_body, only : part_type
    use rollcon_model, only : model_type, setup_model
    use rollcon_problem, only : problem_type
    use rollcon_theta_watch, only : new_theta_watch
    use rollcon_disk_par, only : disk_par
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_simulation, only : history_type
    use rollcon_output_layout, only : name_length
    implicit none
    private

    public :: two_part_model, two_part_problem, read_csv, failing_disk_ucosub

    !> Part ids
    integer, parameter, public :: disk_id = 2, free_id = 5
    !> The paper's disk: radius and thickness [m], density [kg/m^3]
    real(wp), parameter, public :: disk_radius = 0.1_wp
    real(wp), parameter :: disk_thickness = 0.003_wp, density = 7800.0_wp
    !> The disk's speed [m/s]: above the paper's disk's critical 0.572 m/s, so upright rolling
    !> is stable (docs/design.md §5)
    real(wp), parameter, public :: disk_speed = 1.0_wp
    !> The free body: mass [kg], principal moments [kg m^2] (z the largest: a stable spin)
    real(wp), parameter :: free_mass = 2.0_wp, free_inertia(3) = [0.1_wp, 0.2_wp, 0.3_wp]
    !> Its start (X, Y, Z [m], psi, theta, phi [rad]), velocity [m/s] and spin [rad/s]
    real(wp), parameter, public :: free_start(6) = [1.0_wp, 0.0_wp, 2.0_wp, 0.3_wp, &
        & 0.5_wp*pi, 0.0_wp]
    real(wp), parameter, public :: free_velocity(3) = [0.5_wp, 0.0_wp, 1.0_wp]
    real(wp), parameter, public :: free_spin = 3.0_wp
    !> Gravity along -Z [m/s^2]
    real(wp), parameter, public :: gravity = 9.81_wp

contains

    !> The two-part model set up in problem (IDA, default tolerances, a theta limit of 0.05 rad
    !> that neither part reaches), and its start (two_part_model).
    subroutine two_part_problem(problem, q0, u0, error, ucosub, ucon_parts)
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        !> The routine serving the UCONs (default: the hand-checked disk routine)
        procedure(ucosub_interface), optional :: ucosub
        !> The part id each UCON's PAR names (default: the disk's)
        integer, intent(in), optional :: ucon_parts(3)
        type(model_type), target :: model

        call two_part_model(model, q0, u0, error, ucosub, ucon_parts)
        if (allocated(error)) return
        call problem%init(model)
        call problem%add_watch(new_theta_watch(0.05_wp, rebase=.false.))
    end subroutine two_part_problem

    !> The two-part model, set up (setup_model), and its start: the disk upright at (0, 0, R)
    !> rolling along +X (phidot = -v/R, docs/design.md §5), the free body at free_start with
    !> free_velocity and phidot = free_spin (theta = pi/2: the spin is about the body z-axis).
    subroutine two_part_model(model, q0, u0, error, ucosub, ucon_parts)
        type(model_type), intent(out) :: model
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        !> The routine serving the UCONs (default: the hand-checked disk routine)
        procedure(ucosub_interface), optional :: ucosub
        !> The part id each UCON's PAR names (default: the disk's)
        integer, intent(in), optional :: ucon_parts(3)
        type(part_type) :: disk, free
        integer :: k, parts(3)

        disk%id = disk_id
        disk%mass = density*pi*disk_radius**2*disk_thickness
        disk%inertia(1:2) = disk%mass*(3.0_wp*disk_radius**2 + disk_thickness**2)/12.0_wp
        disk%inertia(3) = 0.5_wp*disk%mass*disk_radius**2
        free%id = free_id
        free%mass = free_mass
        free%inertia = free_inertia
        call model%add_part(disk)
        call model%add_part(free)
        model%gravity = [0.0_wp, 0.0_wp, -gravity]
        parts = disk_id
        if (present(ucon_parts)) parts = ucon_parts
        do k = 1, 3
            if (present(ucosub)) then
                call model%add_ucon(10 + k, disk_par(parts(k), disk_radius, k), ucosub, &
                    & time_free=.true.)
            else
                call model%add_ucon(10 + k, disk_par(parts(k), disk_radius, k), &
                    & rolling_disk_ucosub, time_free=.true.)
            end if
        end do
        call setup_model(model, error)
        if (allocated(error)) return
        q0 = [0.0_wp, 0.0_wp, disk_radius, 0.0_wp, 0.5_wp*pi, 0.0_wp, free_start]
        u0 = [disk_speed, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -disk_speed/disk_radius, &
            & free_velocity, 0.0_wp, 0.0_wp, free_spin]
    end subroutine two_part_model

    !> The disk routine, except that UCON 13 returns F = NaN after t = 0.25 s.
    subroutine failing_disk_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id
        real(wp), intent(in) :: time
        real(wp), intent(in) :: q(30)
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar
        integer, intent(in) :: idrsel(3)
        integer, intent(in) :: iflag
        real(wp), intent(inout) :: scalar
        real(wp), intent(inout) :: array(30)
        real(wp), intent(inout) :: xmatrx(30, 30)

        call rolling_disk_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        if (iflag == 0 .and. id == 13 .and. time > 0.25_wp .and. idrsel(1) == 1) &
            & scalar = ieee_value(scalar, ieee_quiet_nan)
    end subroutine failing_disk_ucosub

    !> Read a CSV written by a run: its header names and its rows; the file is deleted.
    subroutine read_csv(path, names, history, error)
        character(len=*), intent(in) :: path
        character(len=name_length), allocatable, intent(out) :: names(:)
        type(history_type), intent(out) :: history
        type(error_type), allocatable, intent(out) :: error
        character(len=4096) :: line
        real(wp), allocatable :: row(:)
        integer :: unit, stat, i

        open(newunit=unit, file=path, status="old", action="read", iostat=stat)
        if (stat == 0) read(unit, '(a)', iostat=stat) line
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot read the header", stat_io)
            return
        end if
        allocate(names(count([(line(i:i) == ",", i = 1, len_trim(line))]) + 1))
        read(line, *) names
        allocate(row(size(names)))
        do
            read(unit, *, iostat=stat) row
            if (stat /= 0) exit
            call history%add(row)
        end do
        close(unit, status="delete")
    end subroutine read_csv

end module layout_models
