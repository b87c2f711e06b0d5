! SPDX-License-Identifier: MIT
!> The generated UCOSUBs as a list, with seeded random states and PAR lists for each.
!>
!> Not a suite: test_generated runs its tests over this list, so a new spec needs one entry
!> here (its routine, codes and parameter ranges) to be covered by every generic test.
module generated_specs_list
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_gen_chaplygin_sled, only : chaplygin_sled_ucosub, chaplygin_sled_codes, &
        & chaplygin_sled_npar, chaplygin_sled_ncomponents, chaplygin_sled_time_free, &
        & chaplygin_sled_component_time_free, chaplygin_sled_holonomic, &
        & chaplygin_sled_component_holonomic
    use rollcon_gen_disk_height, only : disk_height_ucosub, disk_height_codes, &
        & disk_height_npar, disk_height_ncomponents, disk_height_time_free, &
        & disk_height_component_time_free, disk_height_holonomic, &
        & disk_height_component_holonomic
    use rollcon_gen_gnd_atpoint, only : gnd_atpoint_ucosub, gnd_atpoint_codes, &
        & gnd_atpoint_npar, gnd_atpoint_ncomponents, gnd_atpoint_time_free, &
        & gnd_atpoint_component_time_free, gnd_atpoint_holonomic, &
        & gnd_atpoint_component_holonomic
    use rollcon_gen_gnd_homokinetic, only : gnd_homokinetic_ucosub, gnd_homokinetic_codes, &
        & gnd_homokinetic_npar, gnd_homokinetic_ncomponents, gnd_homokinetic_time_free, &
        & gnd_homokinetic_component_time_free, gnd_homokinetic_holonomic, &
        & gnd_homokinetic_component_holonomic
    use rollcon_gen_gnd_inline, only : gnd_inline_ucosub, gnd_inline_codes, &
        & gnd_inline_npar, gnd_inline_ncomponents, gnd_inline_time_free, &
        & gnd_inline_component_time_free, gnd_inline_holonomic, &
        & gnd_inline_component_holonomic
    use rollcon_gen_gnd_inplane, only : gnd_inplane_ucosub, gnd_inplane_codes, &
        & gnd_inplane_npar, gnd_inplane_ncomponents, gnd_inplane_time_free, &
        & gnd_inplane_component_time_free, gnd_inplane_holonomic, &
        & gnd_inplane_component_holonomic
    use rollcon_gen_gnd_motion_angle, only : gnd_motion_angle_ucosub, gnd_motion_angle_codes, &
        & gnd_motion_angle_npar, gnd_motion_angle_ncomponents, gnd_motion_angle_time_free, &
        & gnd_motion_angle_component_time_free, gnd_motion_angle_holonomic, &
        & gnd_motion_angle_component_holonomic
    use rollcon_gen_gnd_orientation, only : gnd_orientation_ucosub, gnd_orientation_codes, &
        & gnd_orientation_npar, gnd_orientation_ncomponents, gnd_orientation_time_free, &
        & gnd_orientation_component_time_free, gnd_orientation_holonomic, &
        & gnd_orientation_component_holonomic
    use rollcon_gen_gnd_parallel_axes, only : gnd_parallel_axes_ucosub, gnd_parallel_axes_codes, &
        & gnd_parallel_axes_npar, gnd_parallel_axes_ncomponents, gnd_parallel_axes_time_free, &
        & gnd_parallel_axes_component_time_free, gnd_parallel_axes_holonomic, &
        & gnd_parallel_axes_component_holonomic
    use rollcon_gen_gnd_perpendicular, only : gnd_perpendicular_ucosub, gnd_perpendicular_codes, &
        & gnd_perpendicular_npar, gnd_perpendicular_ncomponents, gnd_perpendicular_time_free, &
        & gnd_perpendicular_component_time_free, gnd_perpendicular_holonomic, &
        & gnd_perpendicular_component_holonomic
    use rollcon_gen_jp_atpoint, only : jp_atpoint_ucosub, jp_atpoint_codes, &
        & jp_atpoint_npar, jp_atpoint_ncomponents, jp_atpoint_time_free, &
        & jp_atpoint_component_time_free, jp_atpoint_holonomic, &
        & jp_atpoint_component_holonomic
    use rollcon_gen_jp_homokinetic, only : jp_homokinetic_ucosub, jp_homokinetic_codes, &
        & jp_homokinetic_npar, jp_homokinetic_ncomponents, jp_homokinetic_time_free, &
        & jp_homokinetic_component_time_free, jp_homokinetic_holonomic, &
        & jp_homokinetic_component_holonomic
    use rollcon_gen_jp_inline, only : jp_inline_ucosub, jp_inline_codes, &
        & jp_inline_npar, jp_inline_ncomponents, jp_inline_time_free, &
        & jp_inline_component_time_free, jp_inline_holonomic, &
        & jp_inline_component_holonomic
    use rollcon_gen_jp_inplane, only : jp_inplane_ucosub, jp_inplane_codes, &
        & jp_inplane_npar, jp_inplane_ncomponents, jp_inplane_time_free, &
        & jp_inplane_component_time_free, jp_inplane_holonomic, &
        & jp_inplane_component_holonomic
    use rollcon_gen_jp_motion_angle, only : jp_motion_angle_ucosub, jp_motion_angle_codes, &
        & jp_motion_angle_npar, jp_motion_angle_ncomponents, jp_motion_angle_time_free, &
        & jp_motion_angle_component_time_free, jp_motion_angle_holonomic, &
        & jp_motion_angle_component_holonomic
    use rollcon_gen_jp_orientation, only : jp_orientation_ucosub, jp_orientation_codes, &
        & jp_orientation_npar, jp_orientation_ncomponents, jp_orientation_time_free, &
        & jp_orientation_component_time_free, jp_orientation_holonomic, &
        & jp_orientation_component_holonomic
    use rollcon_gen_jp_parallel_axes, only : jp_parallel_axes_ucosub, jp_parallel_axes_codes, &
        & jp_parallel_axes_npar, jp_parallel_axes_ncomponents, jp_parallel_axes_time_free, &
        & jp_parallel_axes_component_time_free, jp_parallel_axes_holonomic, &
        & jp_parallel_axes_component_holonomic
    use rollcon_gen_jp_perpendicular, only : jp_perpendicular_ucosub, jp_perpendicular_codes, &
        & jp_perpendicular_npar, jp_perpendicular_ncomponents, jp_perpendicular_time_free, &
        & jp_perpendicular_component_time_free, jp_perpendicular_holonomic, &
        & jp_perpendicular_component_holonomic
    use rollcon_gen_knife_edge, only : knife_edge_ucosub, knife_edge_codes, &
        & knife_edge_npar, knife_edge_ncomponents, knife_edge_time_free, &
        & knife_edge_component_time_free, knife_edge_holonomic, &
        & knife_edge_component_holonomic
    use rollcon_gen_planar_hold, only : planar_hold_ucosub, planar_hold_codes, &
        & planar_hold_npar, planar_hold_ncomponents, planar_hold_time_free, &
        & planar_hold_component_time_free, planar_hold_holonomic, &
        & planar_hold_component_holonomic
    use rollcon_gen_rolling_disk, only : rolling_disk_ucosub, rolling_disk_codes, &
        & rolling_disk_npar, rolling_disk_ncomponents, rolling_disk_time_free, &
        & rolling_disk_component_time_free, rolling_disk_holonomic, &
        & rolling_disk_component_holonomic
    use rollcon_gen_rolling_sphere, only : rolling_sphere_ucosub, rolling_sphere_codes, &
        & rolling_sphere_npar, rolling_sphere_ncomponents, rolling_sphere_time_free, &
        & rolling_sphere_component_time_free, rolling_sphere_holonomic, &
        & rolling_sphere_component_holonomic
    use rollcon_gen_turntable_ball, only : turntable_ball_ucosub, turntable_ball_codes, &
        & turntable_ball_npar, turntable_ball_ncomponents, turntable_ball_time_free, &
        & turntable_ball_component_time_free, turntable_ball_holonomic, &
        & turntable_ball_component_holonomic
    use rollcon_gen_turntable_disk, only : turntable_disk_ucosub, turntable_disk_codes, &
        & turntable_disk_npar, turntable_disk_ncomponents, turntable_disk_time_free, &
        & turntable_disk_component_time_free, turntable_disk_holonomic, &
        & turntable_disk_component_holonomic
    implicit none
    private

    public :: generated_spec_type, generated_specs, random_state, random_parameters, spec_par

    !> One generated routine and what a test needs to call it
    type :: generated_spec_type
        !> Spec name (the file stem in ucon/specs/)
        character(len=:), allocatable :: name
        !> The generated routine
        procedure(ucosub_interface), pointer, nopass :: ucosub => null()
        !> Codes it declares, in UCOVAR order
        integer, allocatable :: codes(:)
        !> Number of PAR entries it needs
        integer :: npar = 0
        !> A spec of two parts (a joint primitive between two parts): the number of variables
        !> of the part in PAR(1), the rest being the second part's (ucon/spec.py); 0 for a
        !> spec of one part
        integer :: first_part_nvars = 0
        !> Number of components (PAR picks one when more than 1)
        integer :: ncomponents = 1
        !> Kind of each physical parameter, in PAR order: "length" (log-uniform in
        !> [1e-3, 10] m), "offset" (uniform in [-1, 1] m), "rate" (uniform in [-5, 5] rad/s)
        character(len=6), allocatable :: parameter_kinds(:)
        !> What PAR's last entry picks, as the routine's messages name it
        character(len=:), allocatable :: component_meaning
        !> <spec>_time_free: no component has an explicit time
        logical :: time_free = .false.
        !> <spec>_component_time_free: the same, per component
        logical, allocatable :: component_time_free(:)
        !> <spec>_holonomic: no component depends on a velocity
        logical :: holonomic = .false.
        !> <spec>_component_holonomic: the same, per component
        logical, allocatable :: component_holonomic(:)
        !> F has no pole near the random states: false for an angle atan2(y, x), whose
        !> derivatives grow as 1/r^k near x = y = 0, where a random state comes (r = 0.09 at
        !> state 55 of test_derivatives) and sixth-order differences with h = 1e-3 rad lose
        !> more than 1e-8 of the entry; such a spec's partials are checked at states away from
        !> its pole by the suite of its driver (motion-partials)
        logical :: pole_free = .true.
    end type generated_spec_type


contains

    !> Every generated routine, in spec-name order.
    subroutine generated_specs(specs)
        !> The list
        type(generated_spec_type), allocatable, intent(out) :: specs(:)
        integer :: i

        allocate(specs(24))
        do i = 1, size(specs)
            specs(i)%component_meaning = "no-slip component"
        end do
        specs(12)%component_meaning = "hold component"
        do i = 17, 24
            specs(i)%component_meaning = "primitive component"
        end do
        do i = 3, 10
            specs(i)%component_meaning = "primitive component"
        end do
        specs(1)%name = "chaplygin_sled"
        specs(1)%ucosub => chaplygin_sled_ucosub
        specs(1)%codes = chaplygin_sled_codes
        specs(1)%npar = chaplygin_sled_npar
        specs(1)%ncomponents = chaplygin_sled_ncomponents
        specs(1)%time_free = chaplygin_sled_time_free
        specs(1)%component_time_free = chaplygin_sled_component_time_free
        specs(1)%holonomic = chaplygin_sled_holonomic
        specs(1)%component_holonomic = chaplygin_sled_component_holonomic
        specs(1)%parameter_kinds = [character(len=6) :: "offset"]
        specs(2)%name = "disk_height"
        specs(2)%ucosub => disk_height_ucosub
        specs(2)%codes = disk_height_codes
        specs(2)%npar = disk_height_npar
        specs(2)%ncomponents = disk_height_ncomponents
        specs(2)%time_free = disk_height_time_free
        specs(2)%component_time_free = disk_height_component_time_free
        specs(2)%holonomic = disk_height_holonomic
        specs(2)%component_holonomic = disk_height_component_holonomic
        specs(2)%parameter_kinds = [character(len=6) :: "length"]
        specs(11)%name = "knife_edge"
        specs(11)%ucosub => knife_edge_ucosub
        specs(11)%codes = knife_edge_codes
        specs(11)%npar = knife_edge_npar
        specs(11)%ncomponents = knife_edge_ncomponents
        specs(11)%time_free = knife_edge_time_free
        specs(11)%component_time_free = knife_edge_component_time_free
        specs(11)%holonomic = knife_edge_holonomic
        specs(11)%component_holonomic = knife_edge_component_holonomic
        allocate(specs(11)%parameter_kinds(0))
        specs(12)%name = "planar_hold"
        specs(12)%ucosub => planar_hold_ucosub
        specs(12)%codes = planar_hold_codes
        specs(12)%npar = planar_hold_npar
        specs(12)%ncomponents = planar_hold_ncomponents
        specs(12)%time_free = planar_hold_time_free
        specs(12)%component_time_free = planar_hold_component_time_free
        specs(12)%holonomic = planar_hold_holonomic
        specs(12)%component_holonomic = planar_hold_component_holonomic
        specs(12)%parameter_kinds = [character(len=6) :: "offset"]
        specs(13)%name = "rolling_disk"
        specs(13)%ucosub => rolling_disk_ucosub
        specs(13)%codes = rolling_disk_codes
        specs(13)%npar = rolling_disk_npar
        specs(13)%ncomponents = rolling_disk_ncomponents
        specs(13)%time_free = rolling_disk_time_free
        specs(13)%component_time_free = rolling_disk_component_time_free
        specs(13)%holonomic = rolling_disk_holonomic
        specs(13)%component_holonomic = rolling_disk_component_holonomic
        specs(13)%parameter_kinds = [character(len=6) :: "length"]
        specs(14)%name = "rolling_sphere"
        specs(14)%ucosub => rolling_sphere_ucosub
        specs(14)%codes = rolling_sphere_codes
        specs(14)%npar = rolling_sphere_npar
        specs(14)%ncomponents = rolling_sphere_ncomponents
        specs(14)%time_free = rolling_sphere_time_free
        specs(14)%component_time_free = rolling_sphere_component_time_free
        specs(14)%holonomic = rolling_sphere_holonomic
        specs(14)%component_holonomic = rolling_sphere_component_holonomic
        specs(14)%parameter_kinds = [character(len=6) :: "length"]
        specs(15)%name = "turntable_ball"
        specs(15)%ucosub => turntable_ball_ucosub
        specs(15)%codes = turntable_ball_codes
        specs(15)%npar = turntable_ball_npar
        specs(15)%ncomponents = turntable_ball_ncomponents
        specs(15)%time_free = turntable_ball_time_free
        specs(15)%component_time_free = turntable_ball_component_time_free
        specs(15)%holonomic = turntable_ball_holonomic
        specs(15)%component_holonomic = turntable_ball_component_holonomic
        specs(15)%parameter_kinds = [character(len=6) :: "length", "rate", "offset", "offset"]
        specs(16)%name = "turntable_disk"
        specs(16)%ucosub => turntable_disk_ucosub
        specs(16)%codes = turntable_disk_codes
        specs(16)%npar = turntable_disk_npar
        specs(16)%ncomponents = turntable_disk_ncomponents
        specs(16)%time_free = turntable_disk_time_free
        specs(16)%component_time_free = turntable_disk_component_time_free
        specs(16)%holonomic = turntable_disk_holonomic
        specs(16)%component_holonomic = turntable_disk_component_holonomic
        specs(16)%parameter_kinds = [character(len=6) :: "length", "offset", "offset", "rate", &
            & "rate", "rate"]
        specs(3)%name = "gnd_atpoint"
        specs(3)%ucosub => gnd_atpoint_ucosub
        specs(3)%codes = gnd_atpoint_codes
        specs(3)%npar = gnd_atpoint_npar
        specs(3)%ncomponents = gnd_atpoint_ncomponents
        specs(3)%time_free = gnd_atpoint_time_free
        specs(3)%component_time_free = gnd_atpoint_component_time_free
        specs(3)%holonomic = gnd_atpoint_holonomic
        specs(3)%component_holonomic = gnd_atpoint_component_holonomic
        ! marker origins and axes: any finite numbers (the routine assumes no unit axes)
        specs(3)%parameter_kinds = spread("offset", 1, 6)
        specs(4)%name = "gnd_homokinetic"
        specs(4)%ucosub => gnd_homokinetic_ucosub
        specs(4)%codes = gnd_homokinetic_codes
        specs(4)%npar = gnd_homokinetic_npar
        specs(4)%ncomponents = gnd_homokinetic_ncomponents
        specs(4)%time_free = gnd_homokinetic_time_free
        specs(4)%component_time_free = gnd_homokinetic_component_time_free
        specs(4)%holonomic = gnd_homokinetic_holonomic
        specs(4)%component_holonomic = gnd_homokinetic_component_holonomic
        ! marker axes: any finite numbers (the routine assumes no unit axes)
        specs(4)%parameter_kinds = spread("offset", 1, 12)
        specs(5)%name = "gnd_inline"
        specs(5)%ucosub => gnd_inline_ucosub
        specs(5)%codes = gnd_inline_codes
        specs(5)%npar = gnd_inline_npar
        specs(5)%ncomponents = gnd_inline_ncomponents
        specs(5)%time_free = gnd_inline_time_free
        specs(5)%component_time_free = gnd_inline_component_time_free
        specs(5)%holonomic = gnd_inline_holonomic
        specs(5)%component_holonomic = gnd_inline_component_holonomic
        ! marker origins and axes: any finite numbers (the routine assumes no unit axes)
        specs(5)%parameter_kinds = spread("offset", 1, 12)
        specs(6)%name = "gnd_inplane"
        specs(6)%ucosub => gnd_inplane_ucosub
        specs(6)%codes = gnd_inplane_codes
        specs(6)%npar = gnd_inplane_npar
        specs(6)%ncomponents = gnd_inplane_ncomponents
        specs(6)%time_free = gnd_inplane_time_free
        specs(6)%component_time_free = gnd_inplane_component_time_free
        specs(6)%holonomic = gnd_inplane_holonomic
        specs(6)%component_holonomic = gnd_inplane_component_holonomic
        ! marker origins and axes: any finite numbers (the routine assumes no unit axes)
        specs(6)%parameter_kinds = spread("offset", 1, 9)
        specs(7)%name = "gnd_motion_angle"
        specs(7)%ucosub => gnd_motion_angle_ucosub
        specs(7)%codes = gnd_motion_angle_codes
        specs(7)%npar = gnd_motion_angle_npar
        specs(7)%ncomponents = gnd_motion_angle_ncomponents
        specs(7)%time_free = gnd_motion_angle_time_free
        specs(7)%component_time_free = gnd_motion_angle_component_time_free
        specs(7)%holonomic = gnd_motion_angle_holonomic
        specs(7)%component_holonomic = gnd_motion_angle_component_holonomic
        ! five vectors: any finite numbers (the routine assumes no unit vectors)
        specs(7)%parameter_kinds = spread("offset", 1, 15)
        specs(7)%component_meaning = "angle"
        specs(7)%pole_free = .false.
        specs(8)%name = "gnd_orientation"
        specs(8)%ucosub => gnd_orientation_ucosub
        specs(8)%codes = gnd_orientation_codes
        specs(8)%npar = gnd_orientation_npar
        specs(8)%ncomponents = gnd_orientation_ncomponents
        specs(8)%time_free = gnd_orientation_time_free
        specs(8)%component_time_free = gnd_orientation_component_time_free
        specs(8)%holonomic = gnd_orientation_holonomic
        specs(8)%component_holonomic = gnd_orientation_component_holonomic
        ! marker origins and axes: any finite numbers (the routine assumes no unit axes)
        specs(8)%parameter_kinds = spread("offset", 1, 12)
        specs(9)%name = "gnd_parallel_axes"
        specs(9)%ucosub => gnd_parallel_axes_ucosub
        specs(9)%codes = gnd_parallel_axes_codes
        specs(9)%npar = gnd_parallel_axes_npar
        specs(9)%ncomponents = gnd_parallel_axes_ncomponents
        specs(9)%time_free = gnd_parallel_axes_time_free
        specs(9)%component_time_free = gnd_parallel_axes_component_time_free
        specs(9)%holonomic = gnd_parallel_axes_holonomic
        specs(9)%component_holonomic = gnd_parallel_axes_component_holonomic
        ! marker origins and axes: any finite numbers (the routine assumes no unit axes)
        specs(9)%parameter_kinds = spread("offset", 1, 9)
        specs(10)%name = "gnd_perpendicular"
        specs(10)%ucosub => gnd_perpendicular_ucosub
        specs(10)%codes = gnd_perpendicular_codes
        specs(10)%npar = gnd_perpendicular_npar
        specs(10)%ncomponents = gnd_perpendicular_ncomponents
        specs(10)%time_free = gnd_perpendicular_time_free
        specs(10)%component_time_free = gnd_perpendicular_component_time_free
        specs(10)%holonomic = gnd_perpendicular_holonomic
        specs(10)%component_holonomic = gnd_perpendicular_component_holonomic
        ! marker origins and axes: any finite numbers (the routine assumes no unit axes)
        specs(10)%parameter_kinds = spread("offset", 1, 6)
        specs(17)%name = "jp_atpoint"
        specs(17)%ucosub => jp_atpoint_ucosub
        specs(17)%codes = jp_atpoint_codes
        specs(17)%npar = jp_atpoint_npar
        specs(17)%first_part_nvars = 6
        specs(17)%ncomponents = jp_atpoint_ncomponents
        specs(17)%time_free = jp_atpoint_time_free
        specs(17)%component_time_free = jp_atpoint_component_time_free
        specs(17)%holonomic = jp_atpoint_holonomic
        specs(17)%component_holonomic = jp_atpoint_component_holonomic
        specs(17)%parameter_kinds = spread("offset", 1, 6)
        specs(18)%name = "jp_homokinetic"
        specs(18)%ucosub => jp_homokinetic_ucosub
        specs(18)%codes = jp_homokinetic_codes
        specs(18)%npar = jp_homokinetic_npar
        specs(18)%first_part_nvars = 3
        specs(18)%ncomponents = jp_homokinetic_ncomponents
        specs(18)%time_free = jp_homokinetic_time_free
        specs(18)%component_time_free = jp_homokinetic_component_time_free
        specs(18)%holonomic = jp_homokinetic_holonomic
        specs(18)%component_holonomic = jp_homokinetic_component_holonomic
        specs(18)%parameter_kinds = spread("offset", 1, 12)
        specs(19)%name = "jp_inline"
        specs(19)%ucosub => jp_inline_ucosub
        specs(19)%codes = jp_inline_codes
        specs(19)%npar = jp_inline_npar
        specs(19)%first_part_nvars = 6
        specs(19)%ncomponents = jp_inline_ncomponents
        specs(19)%time_free = jp_inline_time_free
        specs(19)%component_time_free = jp_inline_component_time_free
        specs(19)%holonomic = jp_inline_holonomic
        specs(19)%component_holonomic = jp_inline_component_holonomic
        specs(19)%parameter_kinds = spread("offset", 1, 12)
        specs(20)%name = "jp_inplane"
        specs(20)%ucosub => jp_inplane_ucosub
        specs(20)%codes = jp_inplane_codes
        specs(20)%npar = jp_inplane_npar
        specs(20)%first_part_nvars = 6
        specs(20)%ncomponents = jp_inplane_ncomponents
        specs(20)%time_free = jp_inplane_time_free
        specs(20)%component_time_free = jp_inplane_component_time_free
        specs(20)%holonomic = jp_inplane_holonomic
        specs(20)%component_holonomic = jp_inplane_component_holonomic
        specs(20)%parameter_kinds = spread("offset", 1, 9)
        specs(21)%name = "jp_motion_angle"
        specs(21)%ucosub => jp_motion_angle_ucosub
        specs(21)%codes = jp_motion_angle_codes
        specs(21)%npar = jp_motion_angle_npar
        specs(21)%first_part_nvars = 3
        specs(21)%ncomponents = jp_motion_angle_ncomponents
        specs(21)%time_free = jp_motion_angle_time_free
        specs(21)%component_time_free = jp_motion_angle_component_time_free
        specs(21)%holonomic = jp_motion_angle_holonomic
        specs(21)%component_holonomic = jp_motion_angle_component_holonomic
        ! five vectors: any finite numbers (the routine assumes no unit vectors)
        specs(21)%parameter_kinds = spread("offset", 1, 15)
        specs(21)%component_meaning = "angle"
        specs(21)%pole_free = .false.
        specs(22)%name = "jp_orientation"
        specs(22)%ucosub => jp_orientation_ucosub
        specs(22)%codes = jp_orientation_codes
        specs(22)%npar = jp_orientation_npar
        specs(22)%first_part_nvars = 3
        specs(22)%ncomponents = jp_orientation_ncomponents
        specs(22)%time_free = jp_orientation_time_free
        specs(22)%component_time_free = jp_orientation_component_time_free
        specs(22)%holonomic = jp_orientation_holonomic
        specs(22)%component_holonomic = jp_orientation_component_holonomic
        specs(22)%parameter_kinds = spread("offset", 1, 12)
        specs(23)%name = "jp_parallel_axes"
        specs(23)%ucosub => jp_parallel_axes_ucosub
        specs(23)%codes = jp_parallel_axes_codes
        specs(23)%npar = jp_parallel_axes_npar
        specs(23)%first_part_nvars = 3
        specs(23)%ncomponents = jp_parallel_axes_ncomponents
        specs(23)%time_free = jp_parallel_axes_time_free
        specs(23)%component_time_free = jp_parallel_axes_component_time_free
        specs(23)%holonomic = jp_parallel_axes_holonomic
        specs(23)%component_holonomic = jp_parallel_axes_component_holonomic
        specs(23)%parameter_kinds = spread("offset", 1, 9)
        specs(24)%name = "jp_perpendicular"
        specs(24)%ucosub => jp_perpendicular_ucosub
        specs(24)%codes = jp_perpendicular_codes
        specs(24)%npar = jp_perpendicular_npar
        specs(24)%first_part_nvars = 3
        specs(24)%ncomponents = jp_perpendicular_ncomponents
        specs(24)%time_free = jp_perpendicular_time_free
        specs(24)%component_time_free = jp_perpendicular_component_time_free
        specs(24)%holonomic = jp_perpendicular_holonomic
        specs(24)%component_holonomic = jp_perpendicular_component_holonomic
        specs(24)%parameter_kinds = spread("offset", 1, 6)
    end subroutine generated_specs

    !> State k of a series for the given codes: positions in [-2, 2] m; psi, phi in [-pi, pi];
    !> theta within 1e-6 rad of 0 for every 4th k, of pi/2 for the next, else in (0, pi);
    !> velocities in [-10, 10] m/s; rates log-uniform in [1e-2, 1e3] rad/s with random sign.
    subroutine random_state(k, codes, q)
        !> Index in the series, picks the kind of theta
        integer, intent(in) :: k
        !> Codes of the variables
        integer, intent(in) :: codes(:)
        !> Values of the variables
        real(wp), intent(out) :: q(:)
        real(wp) :: u(2)
        integer :: i

        do i = 1, size(codes)
            call random_number(u)
            select case (codes(i))
            case (11:13)
                q(i) = 2.0_wp*(2.0_wp*u(1) - 1.0_wp)
            case (14, 16)
                q(i) = pi*(2.0_wp*u(1) - 1.0_wp)
            case (15)
                select case (mod(k, 4))
                case (0)
                    q(i) = 1.0e-6_wp*(2.0_wp*u(1) - 1.0_wp)
                case (1)
                    q(i) = 0.5_wp*pi + 1.0e-6_wp*(2.0_wp*u(1) - 1.0_wp)
                case default
                    q(i) = pi*u(1)
                end select
            case (21:23)
                q(i) = 10.0_wp*(2.0_wp*u(1) - 1.0_wp)
            case default
                q(i) = sign(10.0_wp**(-2.0_wp + 5.0_wp*u(1)), u(2) - 0.5_wp)
            end select
        end do
    end subroutine random_state

    !> Random physical parameters of a spec, by kind (see generated_spec_type).
    subroutine random_parameters(spec, values)
        !> The spec
        type(generated_spec_type), intent(in) :: spec
        !> One value per parameter, in PAR order
        real(wp), allocatable, intent(out) :: values(:)
        real(wp) :: u
        integer :: i

        allocate(values(size(spec%parameter_kinds)))
        do i = 1, size(values)
            call random_number(u)
            select case (spec%parameter_kinds(i))
            case ("length")
                values(i) = 10.0_wp**(-3.0_wp + 4.0_wp*u)
            case ("offset")
                values(i) = 2.0_wp*u - 1.0_wp
            case default
                values(i) = 5.0_wp*(2.0_wp*u - 1.0_wp)
            end select
        end do
    end subroutine random_parameters

    !> PAR of one UCON statement in the layout every spec shares: part id, codes (a spec of two
    !> parts: then the second part's id, part + 1, and its codes), parameters, then the
    !> component when there are several.
    function spec_par(spec, part, values, component) result(par)
        !> The spec
        type(generated_spec_type), intent(in) :: spec
        !> Part id
        integer, intent(in) :: part
        !> Physical parameters, in PAR order
        real(wp), intent(in) :: values(:)
        !> Component (ignored for a single-component spec)
        integer, intent(in) :: component
        real(wp), allocatable :: par(:)

        par = [real(part, wp), real(spec%codes, wp), values]
        ! a spec of two parts: the second part (id part + 1) and its codes after the first's
        if (spec%first_part_nvars > 0) par = [real(part, wp), &
            & real(spec%codes(:spec%first_part_nvars), wp), real(part + 1, wp), &
            & real(spec%codes(spec%first_part_nvars + 1:), wp), values]
        if (spec%ncomponents > 1) par = [par, real(component, wp)]
    end function spec_par

end module generated_specs_list
