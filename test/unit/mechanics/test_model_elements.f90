! SPDX-License-Identifier: MIT
!> A model's elements as library calls (docs/library.md): model%add_joint and model%add_jprim
!> between two markers, a marker placed as ADAMS places it (part_marker), a part's start
!> (part_start). The joints' UCONs are judged by what they evaluate to: at a state of two parts
!> in general position, each component against its closed form in the markers' ground
!> positions and axes (ucon/specs/_joint.py: atpoint d = r_I - r_J; parallel_axes z_i.x_j,
!> z_i.y_j; inline d.x_j, d.y_j; inplane d.z_j; a HOOKE's perpendicular x_i.y_j; homokinetic
!> x_i.y_j + y_i.x_j).
module test_model_elements
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface, max_ucon_vars, scalar_value, &
        & array_none, xmatrx_none
    use rollcon_ucon_call, only : evaluate_ucon
    use rollcon_ucosub_catalog, only : find_builtin_ucosub, builtin_ucosub_par
    use rollcon_rotation, only : rotation_matrix, rate_matrix
    use rollcon_body, only : part_type
    use rollcon_marker, only : marker_type, part_marker
    use rollcon_part_frames, only : part_start
    use rollcon_joint_types, only : joint_names, primitive_names, joint_primitives
    use rollcon_model, only : model_type, setup_model
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_model_elements

    !> A UCON's F against its closed form: both are sums of a few products of order-one
    !> numbers, a few roundings (1e-16) apart; 1e-12 leaves room and catches any misplaced
    !> vector (an error of order one)
    real(wp), parameter :: tol_f = 1.0e-12_wp
    !> The state: part 1 (id 7) and part 2 (id 9), X, Y, Z [m] and psi, theta, phi [rad], in
    !> general position (no angle at a special value)
    real(wp), parameter :: q_state(12) = [0.2_wp, 0.1_wp, 0.5_wp, 0.4_wp, 1.2_wp, -0.3_wp, &
        & 0.3_wp, -0.1_wp, 0.45_wp, -0.2_wp, 0.9_wp, 0.8_wp]

contains

    subroutine collect_model_elements(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("revolute-ucons-evaluate-their-closed-form", test_revolute), &
            & new_unittest("joint-is-its-primitives", test_primitives), &
            & new_unittest("hooke-planar-convel-closed-form", test_hooke_planar_convel), &
            & new_unittest("hooke-and-convel-with-i-on-ground", test_ground_i), &
            & new_unittest("marker-i-on-ground-served-swapped", test_swapped), &
            & new_unittest("inline-to-ground-closed-form", test_inline_ground), &
            & new_unittest("origins-in-the-model-length-unit", test_length_unit), &
            & new_unittest("refusals", test_refusals), &
            & new_unittest("open-additions-as-one-by-one", test_open_additions), &
            & new_unittest("part-marker-and-start", test_frames)]
    end subroutine collect_model_elements

    !> Two parts (ids 7 and 9) and UCON/20 (a knife edge on part 7); marker I on part 1, J on
    !> part 2, both away from the centres and turned.
    subroutine two_parts(model, i, j, error)
        type(model_type), intent(out) :: model
        type(marker_type), intent(out) :: i, j
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface), pointer :: knife
        real(wp), allocatable :: par(:)
        logical :: time_free, found

        call model%add_part(part_type(id=7, mass=1.0_wp, inertia=[1.0_wp, 1.5_wp, 2.0_wp]))
        call model%add_part(part_type(id=9, mass=2.0_wp, inertia=[1.0_wp, 1.0_wp, 1.5_wp]))
        call find_builtin_ucosub("knife_edge", knife, time_free, found)
        call builtin_ucosub_par("knife_edge", 7, [real(wp) ::], 1, par, error)
        if (allocated(error)) return
        call model%add_ucon(20, par, knife, time_free=time_free, routine="knife_edge")
        i = marker_type(id=21, part=1, point=[0.1_wp, -0.2_wp, 0.3_wp], &
            & axes=rotation_matrix(0.3_wp, 1.1_wp, -0.4_wp))
        j = marker_type(id=31, part=2, point=[-0.05_wp, 0.15_wp, 0.25_wp], &
            & axes=rotation_matrix(-0.7_wp, 0.6_wp, 0.2_wp))
    end subroutine two_parts

    !> REVOLUTE between parts 7 and 9: UCONs 21 to 25 after UCON/20, ATPOINT's three and
    !> PARALLEL_AXES's two, each F equal to its closed form at q_state.
    subroutine test_revolute(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(marker_type) :: i, j
        real(wp) :: d(3), z_i(3), x_j(3), y_j(3), expected(5)
        integer :: k

        call two_parts(model, i, j, error)
        if (allocated(error)) return
        call model%add_joint(4, "REVOLUTE", i, j, error)
        if (allocated(error)) return
        call check(error, size(model%ucons) == 6, "UCONs: " // to_text(size(model%ucons)))
        if (allocated(error)) return
        call check(error, all(model%ucons(2:)%id == [21, 22, 23, 24, 25]) .and. &
            & all([(model%ucons(k)%routine == "jp_atpoint", k = 2, 4)]) .and. &
            & all([(model%ucons(k)%routine == "jp_parallel_axes", k = 5, 6)]) .and. &
            & all(model%ucons(2:)%time_free), "ids, routines and time_free of the joint's UCONs")
        if (allocated(error)) return
        call setup_model(model, error)
        if (allocated(error)) return
        call marker_frames(i, j, d, z_i, x_j, y_j)
        expected = [d, dot_product(z_i, x_j), dot_product(z_i, y_j)]
        do k = 2, 6
            call check_f(model, k, expected(k - 1), error)
            if (allocated(error)) return
        end do
    end subroutine test_revolute

    !> Every joint type's UCONs are those of its primitives (joint_primitives) added one by
    !> one with add_jprim: the same PAR, routines and geometry. Not a HOOKE (its PERPENDICULAR
    !> takes x_i and y_j) nor a CONVEL (its homokinetic condition is no JPRIM):
    !> test_hooke_planar_convel.
    subroutine test_primitives(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: joint, parts
        type(marker_type) :: i, j
        integer, allocatable :: primitives(:)
        integer :: n, p, k
        logical :: same

        do n = 1, size(joint_names)
            if (joint_names(n) == "HOOKE" .or. joint_names(n) == "CONVEL") cycle
            call two_parts(joint, i, j, error)
            if (allocated(error)) return
            call two_parts(parts, i, j, error)
            if (allocated(error)) return
            call joint%add_joint(1, trim(joint_names(n)), i, j, error)
            if (allocated(error)) return
            primitives = joint_primitives(trim(joint_names(n)))
            do p = 1, size(primitives)
                call parts%add_jprim(p, trim(primitive_names(primitives(p))), i, j, error)
                if (allocated(error)) return
            end do
            same = size(joint%ucons) == size(parts%ucons) .and. size(joint%ucons) > 2
            do k = 2, min(size(joint%ucons), size(parts%ucons))
                same = same .and. joint%ucons(k)%id == parts%ucons(k)%id .and. &
                    & joint%ucons(k)%routine == parts%ucons(k)%routine .and. &
                    & size(joint%ucons(k)%par) == size(parts%ucons(k)%par) .and. &
                    & size(joint%ucons(k)%geometry_par) == size(parts%ucons(k)%geometry_par)
                if (same) same = all(joint%ucons(k)%par == parts%ucons(k)%par) .and. &
                    & all(joint%ucons(k)%geometry_par == parts%ucons(k)%geometry_par) .and. &
                    & all(joint%ucons(k)%geometry_parts == parts%ucons(k)%geometry_parts)
            end do
            call check(error, same, trim(joint_names(n)) // ": not the UCONs of its primitives")
            if (allocated(error)) return
        end do
    end subroutine test_primitives

    !> HOOKE, PLANAR and CONVEL between parts 7 and 9, each F against its closed form at
    !> q_state: a HOOKE is 4 UCONs, ATPOINT's d and x_i.y_j (its cross pins, by
    !> jp_perpendicular); a PLANAR 3, d.z_j (jp_inplane), z_i.x_j and z_i.y_j; a CONVEL 4,
    !> d and x_i.y_j + y_i.x_j (jp_homokinetic): the equations each removes.
    subroutine test_hooke_planar_convel(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: kinds(3) = [character(len=6) :: "HOOKE", "PLANAR", &
            & "CONVEL"]
        character(len=*), parameter :: routines(4, 3) = reshape([character(len=16) :: &
            & "jp_atpoint", "jp_atpoint", "jp_atpoint", "jp_perpendicular", &
            & "jp_inplane", "jp_parallel_axes", "jp_parallel_axes", "", &
            & "jp_atpoint", "jp_atpoint", "jp_atpoint", "jp_homokinetic"], [4, 3])
        integer, parameter :: counts(3) = [4, 3, 4]
        type(model_type) :: model
        type(marker_type) :: i, j
        real(wp) :: d(3), axes_i(3, 3), axes_j(3, 3), expected(4)
        integer :: n, k

        do n = 1, size(kinds)
            call two_parts(model, i, j, error)
            if (allocated(error)) return
            call model%add_joint(n, trim(kinds(n)), i, j, error)
            if (allocated(error)) return
            call check(error, size(model%ucons) == 1 + counts(n), trim(kinds(n)) // ": " &
                & // to_text(size(model%ucons) - 1) // " UCONs, not " // to_text(counts(n)))
            if (allocated(error)) return
            call check(error, all([(model%ucons(k + 1)%routine == trim(routines(k, n)), &
                & k = 1, counts(n))]) .and. all(model%ucons(2:)%id == [(20 + k, &
                & k = 1, counts(n))]), trim(kinds(n)) // ": not the routines and ids expected")
            if (allocated(error)) return
            call setup_model(model, error)
            if (allocated(error)) return
            call ground_frames(i, j, d, axes_i, axes_j)
            select case (trim(kinds(n)))
            case ("HOOKE")
                expected = [d, dot_product(axes_i(:, 1), axes_j(:, 2))]
            case ("PLANAR")
                expected = [dot_product(d, axes_j(:, 3)), dot_product(axes_i(:, 3), &
                    & axes_j(:, 1)), dot_product(axes_i(:, 3), axes_j(:, 2)), 0.0_wp]
            case default
                expected = [d, dot_product(axes_i(:, 1), axes_j(:, 2)) &
                    & + dot_product(axes_i(:, 2), axes_j(:, 1))]
            end select
            do k = 1, counts(n)
                call check_f(model, k + 1, expected(k), error)
                if (allocated(error)) then
                    error%message = trim(kinds(n)) // ": " // error%message
                    return
                end if
            end do
        end do
    end subroutine test_hooke_planar_convel

    !> A HOOKE and a CONVEL from a ground marker I to part 7's marker J are served from the
    !> part's side (gnd_perpendicular, gnd_homokinetic) and mean what their markers say: the
    !> HOOKE's pins stay with their markers, x of the ground marker and y of the part's
    !> (x_I.y_J), and the CONVEL's equation is symmetric (x_I.y_J + y_I.x_J).
    subroutine test_ground_i(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: kinds(2) = [character(len=6) :: "HOOKE", "CONVEL"]
        character(len=*), parameter :: routines(2) = [character(len=17) :: &
            & "gnd_perpendicular", "gnd_homokinetic"]
        type(model_type) :: model
        type(marker_type) :: i, j, ground
        real(wp) :: d(3), axes_part(3, 3), axes_ground(3, 3), expected(2)
        integer :: n

        do n = 1, size(kinds)
            call two_parts(model, i, j, error)
            if (allocated(error)) return
            ground = marker_type(id=5, part=0, point=[0.0_wp, 0.2_wp, 1.0_wp], &
                & axes=rotation_matrix(0.1_wp, 0.5_wp, 0.3_wp))
            call model%add_joint(n, trim(kinds(n)), ground, i, error)
            if (allocated(error)) return
            call check(error, size(model%ucons) == 5 .and. model%ucons(5)%routine &
                & == trim(routines(n)), trim(kinds(n)) // ": not 3 gnd_atpoint and " &
                & // trim(routines(n)))
            if (allocated(error)) return
            call setup_model(model, error)
            if (allocated(error)) return
            ! the part's marker as "I" of ground_frames, the ground's as its "J"
            call ground_frames(i, ground, d, axes_part, axes_ground)
            expected = [dot_product(axes_ground(:, 1), axes_part(:, 2)), &
                & dot_product(axes_ground(:, 1), axes_part(:, 2)) &
                & + dot_product(axes_ground(:, 2), axes_part(:, 1))]
            call check_f(model, 5, expected(n), error)
            if (allocated(error)) then
                error%message = trim(kinds(n)) // ": " // error%message
                return
            end if
        end do
    end subroutine test_ground_i

    !> A REVOLUTE from a ground marker to a part's marker is served from the part's side: the
    !> same UCONs as with the markers swapped (every joint is symmetric in I and J).
    subroutine test_swapped(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: forward, backward
        type(marker_type) :: i, j, ground
        integer :: k
        logical :: same

        call two_parts(forward, i, j, error)
        if (allocated(error)) return
        call two_parts(backward, i, j, error)
        if (allocated(error)) return
        ground = marker_type(id=5, part=0, point=[0.0_wp, 0.2_wp, 1.0_wp], &
            & axes=rotation_matrix(0.1_wp, 0.5_wp, 0.0_wp))
        call forward%add_joint(1, "REVOLUTE", i, ground, error)
        if (allocated(error)) return
        call backward%add_joint(1, "REVOLUTE", ground, i, error)
        if (allocated(error)) return
        same = size(forward%ucons) == 6 .and. size(backward%ucons) == 6
        do k = 2, min(size(forward%ucons), size(backward%ucons))
            same = same .and. forward%ucons(k)%routine(:4) == "gnd_" .and. &
                & forward%ucons(k)%routine == backward%ucons(k)%routine .and. &
                & size(forward%ucons(k)%par) == size(backward%ucons(k)%par)
            if (same) same = all(forward%ucons(k)%par == backward%ucons(k)%par)
        end do
        call check(error, same, "a ground marker as I: not the UCONs of the swapped joint")
    end subroutine test_swapped

    !> JPRIM INLINE from part 7's marker I to a ground marker J: d.x_j and d.y_j, J's origin and
    !> axes in ground.
    subroutine test_inline_ground(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(marker_type) :: i, j, ground
        real(wp) :: d(3), z_i(3), x_j(3), y_j(3)

        call two_parts(model, i, j, error)
        if (allocated(error)) return
        ground = marker_type(id=5, part=0, point=[0.0_wp, 0.2_wp, 1.0_wp], &
            & axes=rotation_matrix(0.1_wp, 0.5_wp, 0.0_wp))
        call model%add_jprim(3, "INLINE", i, ground, error)
        if (allocated(error)) return
        call check(error, size(model%ucons) == 3 .and. model%ucons(2)%routine == "gnd_inline", &
            & "an INLINE to ground is two UCONs of gnd_inline")
        if (allocated(error)) return
        call setup_model(model, error)
        if (allocated(error)) return
        call marker_frames(i, ground, d, z_i, x_j, y_j)
        call check_f(model, 2, dot_product(d, x_j), error)
        if (allocated(error)) return
        call check_f(model, 3, dot_product(d, y_j), error)
    end subroutine test_inline_ground

    !> The routines compute in the model's units: with lengths in millimetres, the markers'
    !> origins in PAR are in millimetres, and the axes unchanged.
    subroutine test_length_unit(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(marker_type) :: i, j
        real(wp), allocatable :: par(:)
        integer :: s

        call two_parts(model, i, j, error)
        if (allocated(error)) return
        model%ucosub_units%length = 1.0e-3_wp
        call model%add_jprim(1, "ATPOINT", i, j, error)
        if (allocated(error)) return
        par = model%ucons(2)%par
        s = model%ucons(2)%geometry_par(1)
        call check(error, all(par(s:s + 2) == i%point/1.0e-3_wp) .and. &
            & all(model%ucons(2)%geometry_parts == [1, 2]), "I's origin in PAR " &
            & // to_text(par(s)) // ", " // to_text(par(s + 1)) // ", " // to_text(par(s + 2)))
    end subroutine test_length_unit

    !> What the model cannot join, refused with the statement's words.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(marker_type) :: i, j, other, ground, outside

        call two_parts(model, i, j, error)
        if (allocated(error)) return
        other = marker_type(id=22, part=1)
        ground = marker_type(id=5, part=0)
        outside = marker_type(id=99, part=3)
        call refused("JOINT", 1, "HINGE", i, j, "JOINT/1: 'HINGE' is not a joint (CONVEL, " &
            & // "CYLINDRICAL, FIXED, HOOKE, PLANAR, REVOLUTE, SPHERICAL, TRANSLATIONAL, " &
            & // "UNIVERSAL)", error)
        if (allocated(error)) return
        call refused("JPRIM", 2, "REVOLUTE", i, j, "JPRIM/2: 'REVOLUTE' is not a joint " &
            & // "primitive (ATPOINT, INLINE, INPLANE, PARALLEL_AXES, PERPENDICULAR, " &
            & // "ORIENTATION)", error)
        if (allocated(error)) return
        call refused("JOINT", 3, "FIXED", i, other, "JOINT/3: its markers I (MARKER/21) and J " &
            & // "(MARKER/22) are both on PART/7; a joint connects two parts", error)
        if (allocated(error)) return
        call refused("JOINT", 4, "FIXED", ground, ground, "JOINT/4: its markers I (MARKER/5) " &
            & // "and J (MARKER/5) are both on the ground", error)
        if (allocated(error)) return
        call refused("JPRIM", 5, "INPLANE", ground, i, "JPRIM/5 I: MARKER/5 is on the ground " &
            & // "part; an INPLANE primitive is not symmetric in I and J", error)
        if (allocated(error)) return
        call refused("JOINT", 6, "SPHERICAL", i, outside, "JOINT/6: its markers I (MARKER/21) " &
            & // "and J (MARKER/99) must be on parts of the model (1 to 2)", error)
        if (allocated(error)) return
        call refused("JOINT", 7, "HOOKE", i, other, "JOINT/7: its markers I (MARKER/21) and J " &
            & // "(MARKER/22) are both on PART/7; a joint connects two parts", error)
        if (allocated(error)) return
        call refused("JOINT", 8, "CONVEL", ground, ground, "JOINT/8: its markers I (MARKER/5) " &
            & // "and J (MARKER/5) are both on the ground", error)
        if (allocated(error)) return
        call refused("JOINT", 9, "PLANAR", outside, j, "JOINT/9: its markers I (MARKER/99) " &
            & // "and J (MARKER/31) must be on parts of the model (1 to 2)", error)

    contains

        subroutine refused(statement, id, kind, i, j, expected, error)
            character(len=*), intent(in) :: statement, kind, expected
            integer, intent(in) :: id
            type(marker_type), intent(in) :: i, j
            type(error_type), allocatable, intent(out) :: error
            type(error_type), allocatable :: failure

            if (statement == "JOINT") then
                call model%add_joint(id, kind, i, j, failure)
            else
                call model%add_jprim(id, kind, i, j, failure)
            end if
            call check(error, allocated(failure), statement // " " // kind // ": accepted")
            if (allocated(error)) return
            call check(error, index(failure%message, expected) == 1 .and. &
                & size(model%ucons) == 1, "message '" // failure%message // "', expected '" &
                & // expected // "', and no UCON added")
        end subroutine refused

    end subroutine test_refusals

    !> The same 61 statements (UCON/20, then 30 REVOLUTE joints and 30 ATPOINT primitives in
    !> turn, a UCON/500 among them) added one by one and with the additions open (the arrays
    !> grown by doubling, model%open_additions): while open, the counts are the statements' and
    !> UCONs' so far, not the arrays' capacity; closed, the two models have the same UCONs (id,
    !> statement, equation, routine, constants) and statements (kind, id, line), and set up to
    !> the same coordinates. A joint's UCONs take the ids after the largest so far (UCON/500's
    !> among them), which the open additions track without reading the arrays.
    subroutine test_open_additions(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: one_by_one, open
        type(marker_type) :: i, j
        integer :: k, ucons, statements

        call two_parts(one_by_one, i, j, error)
        if (allocated(error)) return
        call two_parts(open, i, j, error)
        if (allocated(error)) return
        call open%open_additions()
        call add_all(one_by_one, error)
        if (allocated(error)) return
        call add_all(open, error)
        if (allocated(error)) return
        ucons = size(one_by_one%ucons)
        statements = size(one_by_one%statements)
        ! 1 + 30*5 + 30*3 + 1 UCONs in 62 statements
        call check(error, ucons == 242 .and. statements == 62, "one by one: " &
            & // to_text(ucons) // " UCONs in " // to_text(statements) // " statements")
        if (allocated(error)) return
        call check(error, open%ucon_count() == ucons .and. open%statement_count() &
            & == statements .and. size(open%ucons) >= ucons, "open: counts " &
            & // to_text(open%ucon_count()) // " and " // to_text(open%statement_count()))
        if (allocated(error)) return
        call open%close_additions()
        call check(error, size(open%ucons) == ucons .and. size(open%statements) == statements &
            & .and. open%ucon_count() == ucons, "closed: " // to_text(size(open%ucons)) &
            & // " UCONs in " // to_text(size(open%statements)) // " statements")
        if (allocated(error)) return
        do k = 1, ucons
            associate (a => one_by_one%ucons(k), b => open%ucons(k))
                call check(error, a%id == b%id .and. a%statement == b%statement .and. &
                    & a%equation == b%equation .and. a%routine == b%routine .and. &
                    & size(a%par) == size(b%par), "UCON " // to_text(k) // " differs")
                if (allocated(error)) return
                call check(error, all(a%par == b%par), "UCON " // to_text(k) // "'s constants")
                if (allocated(error)) return
            end associate
        end do
        ! UCON/20, 14 joints' and primitives' UCONs 21 .. 132, joint 15's 133 .. 137, UCON/500,
        ! then primitive 15's 501 .. 503 and the rest on to 623
        call check(error, open%ucons(118)%id == 137 .and. open%ucons(119)%id == 500 .and. &
            & open%ucons(120)%id == 501 .and. open%ucons(ucons)%id == 623, "the ids after " &
            & // "UCON/500: " // to_text(open%ucons(120)%id) // " ... " &
            & // to_text(open%ucons(ucons)%id))
        if (allocated(error)) return
        do k = 1, statements
            associate (a => one_by_one%statements(k), b => open%statements(k))
                call check(error, a%kind == b%kind .and. a%id == b%id .and. a%line == b%line, &
                    & "statement " // to_text(k) // " differs")
                if (allocated(error)) return
            end associate
        end do
        call setup_model(one_by_one, error)
        if (allocated(error)) return
        call setup_model(open, error)
        if (allocated(error)) return
        do k = 1, ucons
            call check(error, one_by_one%ucons(k)%nvars == open%ucons(k)%nvars, "nvars")
            if (allocated(error)) return
            call check(error, all(one_by_one%ucons(k)%coordinate == open%ucons(k)%coordinate), &
                & "UCON " // to_text(k) // "'s coordinates")
            if (allocated(error)) return
        end do
    contains
        subroutine add_all(model, error)
            type(model_type), intent(inout) :: model
            type(error_type), allocatable, intent(out) :: error
            procedure(ucosub_interface), pointer :: knife
            real(wp), allocatable :: par(:)
            logical :: time_free, found
            integer :: n

            call find_builtin_ucosub("knife_edge", knife, time_free, found)
            call builtin_ucosub_par("knife_edge", 9, [real(wp) ::], 1, par, error)
            if (allocated(error)) return
            do n = 1, 30
                call model%add_joint(n, "REVOLUTE", i, j, error, line=10 + n)
                if (allocated(error)) return
                if (n == 15) call model%add_ucon(500, par, knife, time_free=time_free, &
                    & routine="knife_edge", line=100)
                call model%add_jprim(100 + n, "ATPOINT", i, j, error, line=200 + n)
                if (allocated(error)) return
            end do
        end subroutine add_all
    end subroutine test_open_additions

    !> part_marker: a marker given in its part's frame is in the principal axes at the centre
    !> of mass (R_cm^T (origin - cm_origin)), so part_start's pose of the part puts it back at
    !> its place in ground. part_start of a part whose CM marker's z is along ground z, spinning
    !> mostly about its y, starts in basis 1 (theta = pi/2) with the same angular velocity.
    subroutine test_frames(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: frame_origin(3) = [1.0_wp, -2.0_wp, 0.5_wp]
        real(wp), parameter :: frame_angles(3) = [0.3_wp, 0.8_wp, -0.2_wp]
        real(wp), parameter :: cm_origin(3) = [0.1_wp, 0.2_wp, -0.3_wp]
        real(wp), parameter :: cm_angles(3) = [-0.4_wp, 1.0_wp, 0.6_wp]
        real(wp), parameter :: origin(3) = [0.5_wp, -0.1_wp, 0.2_wp]
        real(wp), parameter :: omega(3) = [0.3_wp, -0.7_wp, 1.1_wp]
        real(wp) :: principal(3, 3), r_frame(3, 3), q(6), u(6), in_ground(3), omega_body(3)
        type(marker_type) :: marker
        integer :: basis

        principal = rotation_matrix(0.2_wp, 0.4_wp, 0.1_wp)
        r_frame = rotation_matrix(frame_angles(1), frame_angles(2), frame_angles(3))
        marker = part_marker(3, 1, origin, rotation_matrix(0.0_wp, 0.0_wp, 0.0_wp), cm_origin, &
            & rotation_matrix(cm_angles(1), cm_angles(2), cm_angles(3)), principal)
        call part_start(frame_origin, frame_angles, cm_origin, cm_angles, principal, &
            & [0.0_wp, 0.0_wp, 0.0_wp], omega, q, u, basis)
        in_ground = q(1:3) + matmul(rotation_matrix(q(4), q(5), q(6)), marker%point)
        call check(error, basis == 0 .and. maxval(abs(in_ground - (frame_origin &
            & + matmul(r_frame, origin)))) <= tol_f, "marker back in ground off by " &
            & // to_text(maxval(abs(in_ground - (frame_origin + matmul(r_frame, origin))))))
        if (allocated(error)) return
        ! the CM marker's z along ground z: basis 1, the axes turned 90 degrees about x (the
        ! rule's turn: |omega_y| > |omega_x|)
        call part_start(frame_origin, [0.0_wp, 0.0_wp, 0.0_wp], cm_origin, &
            & [0.5_wp, 0.0_wp, 0.0_wp], rotation_matrix(0.0_wp, 0.0_wp, 0.0_wp), &
            & [0.0_wp, 0.0_wp, 0.0_wp], omega, q, u, basis)
        omega_body = matmul(rate_matrix(q(5), q(6)), u(4:6))
        call check(error, basis == 1 .and. abs(q(5) - 0.5_wp*pi) <= tol_f .and. &
            & maxval(abs(omega_body - [omega(1), -omega(3), omega(2)])) <= tol_f, "basis " &
            & // to_text(basis) // ", theta " // to_text(q(5)) // ", angular velocity off by " &
            & // to_text(maxval(abs(omega_body - [omega(1), -omega(3), omega(2)]))))
    end subroutine test_frames

    !> At q_state: d = r_I - r_J and the axes z_i, x_j, y_j in ground.
    subroutine marker_frames(i, j, d, z_i, x_j, y_j)
        type(marker_type), intent(in) :: i, j
        real(wp), intent(out) :: d(3), z_i(3), x_j(3), y_j(3)
        real(wp) :: r_i(3, 3), r_j(3, 3), origin_j(3)

        r_i = rotation_matrix(q_state(4), q_state(5), q_state(6))
        r_j = rotation_matrix(q_state(10), q_state(11), q_state(12))
        origin_j = q_state(7:9)
        if (j%part == 0) then
            r_j = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
                & 1.0_wp], [3, 3])
            origin_j = 0.0_wp
        end if
        d = q_state(1:3) + matmul(r_i, i%point) - (origin_j + matmul(r_j, j%point))
        z_i = matmul(r_i, i%axes(:, 3))
        x_j = matmul(r_j, j%axes(:, 1))
        y_j = matmul(r_j, j%axes(:, 2))
    end subroutine marker_frames

    !> At q_state: d = r_I - r_J and both markers' axes in ground (columns x, y, z); J on the
    !> ground keeps its own.
    subroutine ground_frames(i, j, d, axes_i, axes_j)
        type(marker_type), intent(in) :: i, j
        real(wp), intent(out) :: d(3), axes_i(3, 3), axes_j(3, 3)
        real(wp) :: r_i(3, 3), r_j(3, 3), origin_j(3)

        r_i = rotation_matrix(q_state(4), q_state(5), q_state(6))
        r_j = rotation_matrix(q_state(10), q_state(11), q_state(12))
        origin_j = q_state(7:9)
        if (j%part == 0) then
            r_j = rotation_matrix(0.0_wp, 0.0_wp, 0.0_wp)
            origin_j = 0.0_wp
        end if
        d = q_state(1:3) + matmul(r_i, i%point) - (origin_j + matmul(r_j, j%point))
        axes_i = matmul(r_i, i%axes)
        axes_j = matmul(r_j, j%axes)
    end subroutine ground_frames

    !> UCON k of the set-up model evaluated at q_state, against expected.
    subroutine check_f(model, k, expected, error)
        type(model_type), intent(in) :: model
        integer, intent(in) :: k
        real(wp), intent(in) :: expected
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: q(max_ucon_vars), scalar, array(max_ucon_vars)
        real(wp) :: xmatrx(max_ucon_vars, max_ucon_vars)
        integer :: n

        q = 0.0_wp
        associate (ucon => model%ucons(k))
            do n = 1, ucon%nvars
                q(n) = q_state(ucon%coordinate(n))
            end do
            call evaluate_ucon(ucon%ucosub, ucon%id, 0.0_wp, q, ucon%par, [scalar_value, &
                & array_none, xmatrx_none], scalar, array, xmatrx, error, ucon%nvars)
            if (allocated(error)) return
            call check(error, scalar, expected, "UCON/" // to_text(ucon%id) // " (" &
                & // ucon%routine // ")", abs_tol=tol_f)
        end associate
    end subroutine check_f

end module test_model_elements
