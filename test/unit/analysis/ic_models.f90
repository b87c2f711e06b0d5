! SPDX-License-Identifier: MIT
!> Models for the initial-conditions tests: the seed paper's coin (part 2, as in data/coin.adm)
!> with a chosen set of UCONs, and its exact upright start rolling along +X.
module ic_models
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_body, only : part_type
    use rollcon_model, only : model_type, setup_model
    use rollcon_problem, only : problem_type
    use rollcon_disk_par, only : disk_par
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_gen_disk_height, only : disk_height_ucosub, disk_height_par
    implicit none
    private

    public :: coin_problem, coin_start, ucon_noslip, ucon_height, coin_radius, coin_rho
    public :: coin_part

    !> The coin's part id (data/coin.adm's)
    integer, parameter :: coin_part = 2
    !> Radius [m] and thickness [m] of the paper's steel disk, density [kg/m^3]
    real(wp), parameter :: coin_radius = 0.1_wp, coin_thickness = 0.003_wp, &
        & coin_density = 7800.0_wp
    !> Speed of the exact start along +X [m/s]
    real(wp), parameter :: coin_speed = 0.1_wp
    !> Kinds of UCON a test asks for
    integer, parameter :: ucon_noslip = 1, ucon_height = 2

contains

    !> The coin with UCONs of the given kinds: a no-slip one takes `parameter` as its component
    !> (1, 2, 3: F1, F2, F3), a height one as its radius [m]; ids are 1, 2, ... in order.
    subroutine coin_problem(kinds, parameters, problem, error)
        integer, intent(in) :: kinds(:)
        real(wp), intent(in) :: parameters(:)
        type(problem_type), intent(inout), target :: problem
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(part_type) :: disk
        integer :: k

        disk%id = coin_part
        disk%mass = coin_density*pi*coin_radius**2*coin_thickness
        disk%inertia(1:2) = disk%mass*(3.0_wp*coin_radius**2 + coin_thickness**2)/12.0_wp
        disk%inertia(3) = 0.5_wp*disk%mass*coin_radius**2
        call model%add_part(disk)
        model%ucosub => rolling_disk_ucosub
        do k = 1, size(kinds)
            if (kinds(k) == ucon_noslip) then
                call model%add_ucon(k, disk_par(coin_part, coin_radius, nint(parameters(k))))
            else
                call model%add_ucon(k, disk_height_par(coin_part, parameters(k)), &
                    & disk_height_ucosub)
            end if
        end do
        call setup_model(model, error)
        if (allocated(error)) return
        call problem%init(model)
    end subroutine coin_problem

    !> The exact start: upright (psi = 0, theta = pi/2), centre at (0, 0, R), rolling along +X
    !> at coin_speed with phidot = -v/R (docs/design.md §5).
    pure subroutine coin_start(q, u)
        real(wp), intent(out) :: q(6), u(6)

        q = [0.0_wp, 0.0_wp, coin_radius, 0.0_wp, 0.5_wp*pi, 0.0_wp]
        u = [coin_speed, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -coin_speed/coin_radius]
    end subroutine coin_start

    !> The coin's rho, the RMS distance of its mass from its centre: sqrt((2 A + C)/(2 m)) =
    !> sqrt(R^2/2 + h^2/12) [m], from the disk's formulas (docs/initial-conditions.md).
    pure real(wp) function coin_rho()
        coin_rho = sqrt(0.5_wp*coin_radius**2 + coin_thickness**2/12.0_wp)
    end function coin_rho

end module ic_models
