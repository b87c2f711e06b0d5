! SPDX-License-Identifier: MIT
!> The ADAMS utility subroutines of pure arithmetic a user's routine calls: STEP (the cubic
!> step and its derivatives) and RCNVRT (a rotation from one representation to another), with
!> ADAMS's meanings (docs/datasets.md, "User force routines"). The host serves a routine's
!> calls to them through the shim compiled into its library (rollcon_user_shim).
!>
!>     CALL STEP(X, X0, H0, X1, H1, IORD, VALUE, ERRFLG)
!>     CALL RCNVRT(SYS1, COORD1, SYS2, COORD2, ISTAT)
!>
!> Every rotation is the direction cosine matrix A whose columns are the rotated frame's axes
!> in the reference frame (body components to reference components). A body sequence
!> "Bijk" (angles a1, a2, a3) is A = R_i(a1) R_j(a2) R_k(a3), rotations about the moving
!> axes; a space sequence "Sijk" is A = R_k(a3) R_j(a2) R_i(a1), rotations about the fixed
!> axes; R_1, R_2, R_3 the right-handed rotations about x, y, z. EULER is B313 (ADAMS's psi,
!> theta, phi), YPR is B321 (yaw, pitch, roll as the body 3-2-1 angles), BRYANT is B123.
!> EULPAR are the Euler parameters (e0 = cos(angle/2), (e1, e2, e3) = the axis times
!> sin(angle/2)), RODPAR the Rodrigues parameters (e1, e2, e3)/e0, COSINES the nine entries
!> of A by columns (a11, a21, a31, a12, ...). Angles are in radians. Sources: P. E. Nikravesh,
!> Computer-Aided Analysis of Mechanical Systems (1988), ch. 6 (Euler parameters and the
!> matrix); S. W. Shepperd, J. Guidance Control 1 (1978) 223-224 (parameters from a matrix).
module rollcon_adams_utilities
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: step_utility, convert_rotation, rotation_size, rotation_systems
    public :: rcnvrt_success, rcnvrt_failure

    !> ISTAT of RCNVRT: converted; not converted (a system rollcon does not know, or RODPAR of
    !> a half turn, where the Rodrigues parameters are infinite)
    integer, parameter :: rcnvrt_success = 0, rcnvrt_failure = -10

    !> The systems RCNVRT knows
    character(len=*), parameter :: rotation_systems(30) = [character(len=7) :: "EULER", &
        & "EULPAR", "RODPAR", "YPR", "BRYANT", "COSINES", "B123", "B132", "B213", "B231", &
        & "B312", "B321", "B121", "B131", "B212", "B232", "B313", "B323", "S123", "S132", &
        & "S213", "S231", "S312", "S321", "S121", "S131", "S212", "S232", "S313", "S323"]

contains

    !> STEP(X, X0, H0, X1, H1, IORD, VALUE, ERRFLG): ADAMS's cubic step from h0 at x0 to h1 at
    !> x1, value = h0 + (h1 - h0) s^2 (3 - 2 s), s = (x - x0)/(x1 - x0), constant h0 before x0
    !> and h1 after x1, or its derivative of order iord (0, 1, 2) in x. errflg is set, and
    !> value 0, when x1 <= x0 or iord is not 0, 1 or 2. Units: value in h's, its derivatives
    !> in h's per x's to the power iord.
    pure subroutine step_utility(x, x0, h0, x1, h1, iord, value, errflg)
        real(wp), intent(in) :: x, x0, h0, x1, h1
        integer, intent(in) :: iord
        real(wp), intent(out) :: value
        logical, intent(out) :: errflg
        real(wp) :: width, s

        value = 0.0_wp
        errflg = .not. (x1 > x0) .or. iord < 0 .or. iord > 2
        if (errflg) return
        if (x <= x0) then
            if (iord == 0) value = h0
            return
        else if (x >= x1) then
            if (iord == 0) value = h1
            return
        end if
        width = x1 - x0
        s = (x - x0)/width
        select case (iord)
        case (0)
            value = h0 + (h1 - h0)*s*s*(3.0_wp - 2.0_wp*s)
        case (1)
            value = (h1 - h0)*6.0_wp*s*(1.0_wp - s)/width
        case default
            value = (h1 - h0)*6.0_wp*(1.0_wp - 2.0_wp*s)/(width*width)
        end select
    end subroutine step_utility

    !> Number of coordinates of a system: 4 (EULPAR), 9 (COSINES), 3 (the others); 0 for a
    !> name RCNVRT does not know. Names in any case, blanks around them ignored.
    pure integer function rotation_size(system) result(n)
        character(len=*), intent(in) :: system
        integer :: frame, axes(3)

        select case (upper(system))
        case ("EULPAR")
            n = 4
        case ("COSINES")
            n = 9
        case ("RODPAR")
            n = 3
        case default
            call parse_sequence(upper(system), frame, axes)
            n = merge(3, 0, frame > 0)
        end select
    end function rotation_size

    !> RCNVRT(SYS1, COORD1, SYS2, COORD2, ISTAT): coord1 in system sys1 as coord2 in sys2
    !> (rotation_size(sys2) values). Angles out of a sequence lie in (-pi, pi], the middle one
    !> of a Tait-Bryan sequence in [-pi/2, pi/2] and of a proper Euler sequence in [0, pi];
    !> where the sequence is singular (the middle angle at a bound) the first takes the whole
    !> rotation about its axis and the last is 0. EULPAR out has e0 >= 0; EULPAR in is
    !> normalised. istat is rcnvrt_failure, and coord2 zero, for a name RCNVRT does not know,
    !> for AXAYAZ (ADAMS's AX, AY, AZ do not determine a rotation), and for RODPAR out of a
    !> half turn (e0 <= 2.2e-16, the rounding of the matrix: the parameters are infinite).
    pure subroutine convert_rotation(sys1, coord1, sys2, coord2, istat)
        character(len=*), intent(in) :: sys1, sys2
        real(wp), intent(in) :: coord1(:)
        real(wp), intent(out) :: coord2(:)
        integer, intent(out) :: istat
        real(wp) :: a(3, 3)
        integer :: n1, n2

        coord2 = 0.0_wp
        istat = rcnvrt_failure
        n1 = rotation_size(sys1)
        n2 = rotation_size(sys2)
        if (n1 == 0 .or. n2 == 0 .or. upper(sys1) == "AXAYAZ" .or. upper(sys2) == "AXAYAZ") &
            & return
        if (size(coord1) < n1 .or. size(coord2) < n2) return
        call to_matrix(upper(sys1), coord1(:n1), a, istat)
        if (istat /= rcnvrt_success) return
        call from_matrix(upper(sys2), a, coord2(:n2), istat)
        if (istat /= rcnvrt_success) coord2 = 0.0_wp
    end subroutine convert_rotation

    !> The matrix of coordinates in a known system.
    pure subroutine to_matrix(system, coord, a, istat)
        character(len=*), intent(in) :: system
        real(wp), intent(in) :: coord(:)
        real(wp), intent(out) :: a(3, 3)
        integer, intent(out) :: istat
        integer :: axes(3), frame
        real(wp) :: e(0:3), norm

        istat = rcnvrt_success
        select case (system)
        case ("COSINES")
            a = reshape(coord(1:9), [3, 3])
        case ("EULPAR", "RODPAR")
            if (system == "EULPAR") then
                e = coord(1:4)
            else
                e = [1.0_wp, coord(1:3)]
            end if
            norm = norm2(e)
            if (.not. norm > 0.0_wp) then
                istat = rcnvrt_failure
                return
            end if
            e = e/norm
            a = parameter_matrix(e)
        case default
            call parse_sequence(system, frame, axes)
            if (frame == 1) then
                a = matmul(matmul(axis_rotation(axes(1), coord(1)), &
                    & axis_rotation(axes(2), coord(2))), axis_rotation(axes(3), coord(3)))
            else
                a = matmul(matmul(axis_rotation(axes(3), coord(3)), &
                    & axis_rotation(axes(2), coord(2))), axis_rotation(axes(1), coord(1)))
            end if
        end select
    end subroutine to_matrix

    !> The coordinates of a matrix in a known system.
    pure subroutine from_matrix(system, a, coord, istat)
        character(len=*), intent(in) :: system
        real(wp), intent(in) :: a(3, 3)
        real(wp), intent(out) :: coord(:)
        integer, intent(out) :: istat
        integer :: axes(3), frame
        real(wp) :: e(0:3), angles(3)

        istat = rcnvrt_success
        select case (system)
        case ("COSINES")
            coord(1:9) = reshape(a, [9])
        case ("EULPAR")
            coord(1:4) = matrix_parameters(a)
        case ("RODPAR")
            e = matrix_parameters(a)
            ! a half turn to within rounding: e0 no larger than the rounding of the matrix
            if (.not. e(0) > epsilon(1.0_wp)) then
                istat = rcnvrt_failure
                return
            end if
            coord(1:3) = e(1:3)/e(0)
        case default
            call parse_sequence(system, frame, axes)
            if (frame == 1) then
                angles = body_angles(axes, a)
            else
                ! A = R_k(a3) R_j(a2) R_i(a1) is the body sequence (k, j, i) of (a3, a2, a1)
                angles = body_angles([axes(3), axes(2), axes(1)], a)
                angles = [angles(3), angles(2), angles(1)]
            end if
            coord(1:3) = angles
        end select
    end subroutine from_matrix

    !> The angles of body sequence (i, j, k) of a matrix a = R_i(a1) R_j(a2) R_k(a3).
    pure function body_angles(axes, a) result(angles)
        integer, intent(in) :: axes(3)
        real(wp), intent(in) :: a(3, 3)
        real(wp) :: angles(3)
        integer :: i, j, k, l
        real(wp) :: s, c2

        i = axes(1)
        j = axes(2)
        k = axes(3)
        ! s = +1 when j follows i cyclically (1 2 3), -1 otherwise
        s = merge(1.0_wp, -1.0_wp, modulo(j - i, 3) == 1)
        if (i /= k) then
            ! Tait-Bryan: a(i, k) = s sin(a2)
            c2 = hypot(a(i, i), a(i, j))
            angles(2) = atan2(s*a(i, k), c2)
            if (c2 > 0.0_wp) then
                angles(1) = atan2(-s*a(j, k), a(k, k))
                angles(3) = atan2(-s*a(i, j), a(i, i))
            else
                ! gimbal lock: the first angle takes the rotation, the last is 0
                angles(1) = atan2(s*a(k, j), a(j, j))
                angles(3) = 0.0_wp
            end if
        else
            ! proper Euler: a(i, i) = cos(a2)
            l = 6 - i - j
            c2 = hypot(a(i, j), a(i, l))
            angles(2) = atan2(c2, a(i, i))
            if (c2 > 0.0_wp) then
                angles(1) = atan2(a(j, i), -s*a(l, i))
                angles(3) = atan2(a(i, j), s*a(i, l))
            else
                angles(1) = atan2(s*a(l, j), a(j, j))
                angles(3) = 0.0_wp
            end if
        end if
    end function body_angles

    !> The Euler parameters of a rotation matrix (Shepperd's choice of the largest of the four
    !> to divide by), e0 >= 0.
    pure function matrix_parameters(a) result(e)
        real(wp), intent(in) :: a(3, 3)
        real(wp) :: e(0:3)
        real(wp) :: trace, largest
        integer :: pick

        trace = a(1, 1) + a(2, 2) + a(3, 3)
        largest = trace
        pick = 0
        if (a(1, 1) > largest) then
            largest = a(1, 1)
            pick = 1
        end if
        if (a(2, 2) > largest) then
            largest = a(2, 2)
            pick = 2
        end if
        if (a(3, 3) > largest) pick = 3
        select case (pick)
        case (0)
            e(0) = 0.5_wp*sqrt(1.0_wp + trace)
            e(1) = (a(3, 2) - a(2, 3))/(4.0_wp*e(0))
            e(2) = (a(1, 3) - a(3, 1))/(4.0_wp*e(0))
            e(3) = (a(2, 1) - a(1, 2))/(4.0_wp*e(0))
        case (1)
            e(1) = 0.5_wp*sqrt(1.0_wp + 2.0_wp*a(1, 1) - trace)
            e(0) = (a(3, 2) - a(2, 3))/(4.0_wp*e(1))
            e(2) = (a(1, 2) + a(2, 1))/(4.0_wp*e(1))
            e(3) = (a(1, 3) + a(3, 1))/(4.0_wp*e(1))
        case (2)
            e(2) = 0.5_wp*sqrt(1.0_wp + 2.0_wp*a(2, 2) - trace)
            e(0) = (a(1, 3) - a(3, 1))/(4.0_wp*e(2))
            e(1) = (a(1, 2) + a(2, 1))/(4.0_wp*e(2))
            e(3) = (a(2, 3) + a(3, 2))/(4.0_wp*e(2))
        case default
            e(3) = 0.5_wp*sqrt(1.0_wp + 2.0_wp*a(3, 3) - trace)
            e(0) = (a(2, 1) - a(1, 2))/(4.0_wp*e(3))
            e(1) = (a(1, 3) + a(3, 1))/(4.0_wp*e(3))
            e(2) = (a(2, 3) + a(3, 2))/(4.0_wp*e(3))
        end select
        if (e(0) < 0.0_wp) e = -e
    end function matrix_parameters

    !> A = (e0^2 - e.e) I + 2 e e^T + 2 e0 [e x] of unit Euler parameters.
    pure function parameter_matrix(e) result(a)
        real(wp), intent(in) :: e(0:3)
        real(wp) :: a(3, 3)
        integer :: r

        a = 0.0_wp
        do r = 1, 3
            a(r, r) = e(0)**2 - sum(e(1:3)**2)
            a(r, :) = a(r, :) + 2.0_wp*e(r)*e(1:3)
        end do
        a(1, 2) = a(1, 2) - 2.0_wp*e(0)*e(3)
        a(2, 1) = a(2, 1) + 2.0_wp*e(0)*e(3)
        a(1, 3) = a(1, 3) + 2.0_wp*e(0)*e(2)
        a(3, 1) = a(3, 1) - 2.0_wp*e(0)*e(2)
        a(2, 3) = a(2, 3) - 2.0_wp*e(0)*e(1)
        a(3, 2) = a(3, 2) + 2.0_wp*e(0)*e(1)
    end function parameter_matrix

    !> The right-handed rotation by angle about axis 1, 2 or 3.
    pure function axis_rotation(axis, angle) result(r)
        integer, intent(in) :: axis
        real(wp), intent(in) :: angle
        real(wp) :: r(3, 3)
        integer :: p, q

        r = 0.0_wp
        r(axis, axis) = 1.0_wp
        p = modulo(axis, 3) + 1
        q = modulo(axis + 1, 3) + 1
        r(p, p) = cos(angle)
        r(q, q) = cos(angle)
        r(q, p) = sin(angle)
        r(p, q) = -sin(angle)
    end function axis_rotation

    !> frame 1 for a body sequence, 2 for a space sequence, 0 otherwise; its axes.
    pure subroutine parse_sequence(system, frame, axes)
        character(len=*), intent(in) :: system
        integer, intent(out) :: frame, axes(3)
        character(len=4) :: name
        integer :: k, digits(3)

        frame = 0
        axes = 0
        select case (system)
        case ("EULER")
            name = "B313"
        case ("YPR")
            name = "B321"
        case ("BRYANT")
            name = "B123"
        case default
            if (len(system) /= 4) return
            name = system
        end select
        if (name(1:1) /= "B" .and. name(1:1) /= "S") return
        do k = 1, 3
            digits(k) = index("123", name(k + 1:k + 1))
        end do
        if (any(digits == 0)) return
        if (digits(1) == digits(2) .or. digits(2) == digits(3)) return
        frame = merge(1, 2, name(1:1) == "B")
        axes = digits
    end subroutine parse_sequence

    !> Upper case of text, blanks around it removed.
    pure function upper(text) result(word)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: word
        integer :: k, code

        word = trim(adjustl(text))
        do k = 1, len(word)
            code = iachar(word(k:k))
            if (code >= iachar("a") .and. code <= iachar("z")) word(k:k) = achar(code - 32)
        end do
    end function upper

end module rollcon_adams_utilities
