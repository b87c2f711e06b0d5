! SPDX-License-Identifier: MIT
!> The principal axes of ADAMS's IP=xx, yy, zz, xy, xz, yz (rollcon_inertia_axes): a tensor
!> worked by hand, the assignment of eigenvectors closest to the CM marker's axes, repeated
!> moments, a tensor that is no body's, and products of 0 kept as written.
module test_inertia_axes
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_inertia_axes, only : principal_axes, inertia_tensor
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_inertia_axes

    !> dsyev's eigenpairs of a 3 x 3 tensor of moments near 1 are exact to a few eps: moments
    !> to 1e-14 kg m^2 and axes to 1e-14 (components) are met with room, while a wrong sign or
    !> order of a product, or a wrong assignment, is off by 0.1 and more
    real(wp), parameter :: tol_eigen = 1.0e-14_wp

contains

    !> Tests of this suite.
    subroutine collect_inertia_axes(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("hand-computed-tensor", test_hand), &
            & new_unittest("closest-to-cm-marker-axes", test_closest), &
            & new_unittest("repeated-moments", test_repeated), &
            & new_unittest("not-positive-definite", test_not_definite), &
            & new_unittest("no-products-kept-as-written", test_no_products)]
    end subroutine collect_inertia_axes

    !> Principal moments 2, 3, 4 along x = (c, 0, -s), y = (0, 1, 0), z = (s, 0, c), the CM
    !> marker's axes turned 30 degrees about y (c = cos 30, s = sin 30). By hand the tensor is
    !> T11 = 2 c^2 + 4 s^2 = 2.5, T33 = 2 s^2 + 4 c^2 = 3.5, T22 = 3, T13 = (4 - 2) s c =
    !> sqrt(3)/2, the rest 0; ADAMS's positive integral is Ixz = -T13 = -sqrt(3)/2.
    subroutine test_hand(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: moments(3), axes(3, 3), expected(3, 3)
        real(wp), parameter :: c = sqrt(3.0_wp)/2.0_wp, s = 0.5_wp

        call principal_axes([2.5_wp, 3.0_wp, 3.5_wp, 0.0_wp, -c, 0.0_wp], moments, axes, error)
        if (allocated(error)) return
        expected(:, 1) = [c, 0.0_wp, -s]
        expected(:, 2) = [0.0_wp, 1.0_wp, 0.0_wp]
        expected(:, 3) = [s, 0.0_wp, c]
        call check(error, all(abs(moments - [2.0_wp, 3.0_wp, 4.0_wp]) <= tol_eigen) .and. &
            & all(abs(axes - expected) <= tol_eigen), "moments " // to_text(moments(1)) &
            & // ", " // to_text(moments(2)) // ", " // to_text(moments(3)) // "; x = (" &
            & // to_text(axes(1, 1)) // ", " // to_text(axes(2, 1)) // ", " &
            & // to_text(axes(3, 1)) // ")")
    end subroutine test_hand

    !> Tiny products keep the CM marker's axes (turned by about the products over the gaps
    !> between moments, 1e-6 rad here) and their moments in the order written, whatever the
    !> order of the eigenvalues; the axes are a rotation and diagonalise the tensor.
    subroutine test_closest(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: moments(3), axes(3, 3), ip(6)
        integer :: case

        do case = 1, 2
            if (case == 1) ip = [1.0_wp, 2.0_wp, 1.5_wp, 1.0e-6_wp, -2.0e-6_wp, 1.0e-6_wp]
            if (case == 2) ip = [1.5_wp, 1.0_wp, 2.0_wp, 0.0_wp, 0.0_wp, 1.0e-6_wp]
            call principal_axes(ip, moments, axes, error)
            if (allocated(error)) return
            ! turned by less than 1e-5 rad: each axis within 1e-5 of the marker's
            call check(error, all(abs(moments - ip(1:3)) <= 1.0e-11_wp) .and. &
                & all(abs(axes - identity()) <= 1.0e-5_wp), "case " // to_text(case) &
                & // ": moments " // to_text(moments(1)) // ", " // to_text(moments(2)) // ", " &
                & // to_text(moments(3)))
            if (allocated(error)) return
            call check_rotation(error, ip, moments, axes)
            if (allocated(error)) return
        end do
    end subroutine test_closest

    !> A disk-like body (moments 1, 1, 2) whose axis is the CM marker's z turned 30 degrees
    !> about x: z = (0, -s, c). Any pair in the plane of the repeated moment is principal; the
    !> one closest to the CM marker's x and y is x = (1, 0, 0), y = (0, c, s). By hand the
    !> tensor is 1 + z z^T: T22 = 1 + s^2, T33 = 1 + c^2, T23 = -s c, so Iyz = s c.
    subroutine test_repeated(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: moments(3), axes(3, 3), expected(3, 3), ip(6)
        real(wp), parameter :: c = sqrt(3.0_wp)/2.0_wp, s = 0.5_wp

        ip = [1.0_wp, 1.0_wp + s**2, 1.0_wp + c**2, 0.0_wp, 0.0_wp, s*c]
        call principal_axes(ip, moments, axes, error)
        if (allocated(error)) return
        expected(:, 1) = [1.0_wp, 0.0_wp, 0.0_wp]
        expected(:, 2) = [0.0_wp, c, s]
        expected(:, 3) = [0.0_wp, -s, c]
        call check(error, all(abs(moments - [1.0_wp, 1.0_wp, 2.0_wp]) <= tol_eigen) .and. &
            & all(abs(axes - expected) <= tol_eigen), "moments " // to_text(moments(1)) &
            & // ", " // to_text(moments(2)) // ", " // to_text(moments(3)) // "; x = (" &
            & // to_text(axes(1, 1)) // ", " // to_text(axes(2, 1)) // ", " &
            & // to_text(axes(3, 1)) // ")")
        if (.not. allocated(error)) call check_rotation(error, ip, moments, axes)
    end subroutine test_repeated

    !> Products too large for the moments: [[1, -2, 0], [-2, 1, 0], [0, 0, 1]] has the
    !> eigenvalues 1 - 2 = -1, 1 and 1 + 2: no body has it, and the message says why.
    subroutine test_not_definite(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: refused
        real(wp) :: moments(3), axes(3, 3)

        call principal_axes([1.0_wp, 1.0_wp, 1.0_wp, 2.0_wp, 0.0_wp, 0.0_wp], moments, axes, &
            & refused)
        call check(error, allocated(refused), "an indefinite tensor accepted")
        if (allocated(error)) return
        call check(error, index(refused%message, "is not positive definite: its eigenvalues " &
            & // "are -1") > 0, refused%message)
    end subroutine test_not_definite

    !> Products of 0: the moments as written, bit for bit, and the CM marker's axes.
    subroutine test_no_products(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: moments(3), axes(3, 3)
        real(wp), parameter :: ip(6) = [0.3_wp, 0.1_wp, 0.25_wp, 0.0_wp, 0.0_wp, 0.0_wp]

        call principal_axes(ip, moments, axes, error)
        if (allocated(error)) return
        call check(error, all(moments == ip(1:3)) .and. all(axes == identity()), &
            & "products of 0 changed the moments or the axes")
    end subroutine test_no_products

    !> axes is a rotation (orthonormal, det +1) and axes diag(moments) axes^T is the tensor.
    subroutine check_rotation(error, ip, moments, axes)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in) :: ip(6), moments(3), axes(3, 3)
        real(wp) :: rebuilt(3, 3), det
        integer :: k

        rebuilt = 0.0_wp
        do k = 1, 3
            rebuilt = rebuilt + moments(k)*spread(axes(:, k), 2, 3)*spread(axes(:, k), 1, 3)
        end do
        det = dot_product(axes(:, 1), [axes(2, 2)*axes(3, 3) - axes(3, 2)*axes(2, 3), &
            & axes(3, 2)*axes(1, 3) - axes(1, 2)*axes(3, 3), axes(1, 2)*axes(2, 3) &
            & - axes(2, 2)*axes(1, 3)])
        call check(error, all(abs(matmul(transpose(axes), axes) - identity()) <= tol_eigen) &
            & .and. abs(det - 1.0_wp) <= tol_eigen .and. all(abs(rebuilt &
            & - inertia_tensor(ip)) <= tol_eigen), "not a rotation diagonalising the tensor " &
            & // "(det " // to_text(det) // ")")
    end subroutine check_rotation

    pure function identity() result(m)
        real(wp) :: m(3, 3)
        integer :: k

        m = 0.0_wp
        do k = 1, 3
            m(k, k) = 1.0_wp
        end do
    end function identity

end module test_inertia_axes
