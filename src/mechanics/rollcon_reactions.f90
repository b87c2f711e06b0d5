! SPDX-License-Identifier: MIT
!> The reaction of each statement (docs/outputs.md, "Reactions"): the force and torque a JOINT
!> or JPRIM exerts on the part of its marker I, at marker I (ADAMS's convention), and the force
!> and torque a UCON exerts on each part it holds, at the part's centre of mass; all in ground
!> axes [N, N m].
!>
!> They come from the generalised constraint forces sum_k lambda_k c_k of the statement's rows
!> (docs/design.md §3) on the part's coordinates: the translational ones are the force in
!> ground axes; the rotational ones are B^T tau' (B the Euler-angle rate matrix, tau' the moment
!> about the centre of mass in the part's principal axes), so tau = R B^-T (its three entries).
!> The moment about marker I is tau - r x F, r from the centre of mass to I. A statement whose
!> marker I is on the ground is served from the part of J (rollcon_joint_primitives): the force
!> on the ground is then minus the force on J's part, and its moment about I minus that force's
!> and moment's about I (the joint's equations depend on the two markers' relative pose only,
!> so the pair is equal and opposite).
module rollcon_reactions
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text, lower_case
    use rollcon_rotation, only : rotation_matrix, rotation_of_sines, times, cross
    use rollcon_marker, only : marker_type
    use rollcon_model, only : model_type, statement_type, statement_joint, statement_jprim, &
        & statement_element
    use rollcon_constraint_matrix, only : constraint_matrix_type
    implicit none
    private

    public :: reaction_site_type, reaction_sites, site_wrench, swapped_wrench, body_moment
    public :: part_attitude_type, part_attitude

    !> Where one statement's reaction is reported, and the rows that make it
    type :: reaction_site_type
        !> The statement (model%statements)
        integer :: statement = 0
        !> The part whose coordinates the rows' forces are taken on (model order)
        integer :: part = 0
        !> A JOINT's or JPRIM's reaction, at marker I; with marker I on the ground (its rows
        !> hold J's part): the reaction on the ground
        logical :: at_marker = .false., on_ground = .false.
        !> The statement's UCONs (model order)
        integer, allocatable :: rows(:)
        !> The stem of its columns: "joint3", "jprim2", "ucon1" (a UCON on one part),
        !> "ucon1_part3" (one of several parts)
        character(len=:), allocatable :: stem
    end type reaction_site_type

    !> What a reaction needs of a part's Euler angles at a state: R(psi, theta, phi) (principal
    !> axes to ground) and the sine and cosine of theta and phi (B's entries, body_moment);
    !> made once a row for all the sites on the part (part_attitude)
    type :: part_attitude_type
        real(wp) :: rotation(3, 3) = 0.0_wp
        real(wp) :: sin_theta = 0.0_wp, cos_theta = 1.0_wp, sin_phi = 0.0_wp, cos_phi = 1.0_wp
    end type part_attitude_type

contains

    !> The attitude of part p (model order) at the coordinates q (n) [rad]: R and the sines and
    !> cosines of its angles theta and phi, the same numbers as rotation_matrix and body_moment
    !> make of them.
    pure function part_attitude(q, p) result(attitude)
        real(wp), intent(in) :: q(:)
        integer, intent(in) :: p
        type(part_attitude_type) :: attitude
        real(wp) :: cos_psi, sin_psi
        integer :: i0

        i0 = 6*(p - 1)
        cos_psi = cos(q(i0 + 4))
        sin_psi = sin(q(i0 + 4))
        attitude%cos_theta = cos(q(i0 + 5))
        attitude%sin_theta = sin(q(i0 + 5))
        attitude%cos_phi = cos(q(i0 + 6))
        attitude%sin_phi = sin(q(i0 + 6))
        attitude%rotation = rotation_of_sines(cos_psi, sin_psi, attitude%cos_theta, &
            & attitude%sin_theta, attitude%cos_phi, attitude%sin_phi)
    end function part_attitude

    !> The reaction sites of a set-up model, in the order of its statements: one per JOINT and
    !> JPRIM, one per part a UCON holds (in model order); none for a dataset's CONTACT (its
    !> contact watch reports its force).
    function reaction_sites(model) result(sites)
        type(model_type), intent(in) :: model
        type(reaction_site_type), allocatable :: sites(:)
        type(reaction_site_type) :: site
        integer, allocatable :: rows(:), parts(:)
        integer :: s, k, p, i

        allocate(sites(0))
        if (.not. allocated(model%statements)) return
        do s = 1, size(model%statements)
            rows = pack([(k, k = 1, model%nc)], model%ucons(:model%nc)%statement == s)
            if (size(rows) == 0) cycle
            ! a dataset's CONTACT: its force is its contact watch's columns (Fx ... Fn, with the
            ! friction while it slides), which the multipliers of its rows alone are not
            if (model%statements(s)%kind == statement_element) then
                if (index(model%statements(s)%name, "CONTACT/") == 1) cycle
            end if
            associate (statement => model%statements(s))
                site%statement = s
                site%rows = rows
                if (any(statement%kind == [statement_joint, statement_jprim])) then
                    site%at_marker = .true.
                    site%on_ground = statement%i%part == 0
                    site%part = statement%i%part
                    if (site%on_ground) site%part = statement%j_part
                    site%stem = trim(merge("joint", "jprim", statement%kind == statement_joint)) &
                        & // to_text(statement%id)
                    call append(sites, site)
                    cycle
                end if
                ! a UCON: each part it holds, in model order
                allocate(parts(0))
                do i = 1, size(rows)
                    do k = 1, model%ucons(rows(i))%nvars
                        p = (model%ucons(rows(i))%coordinate(k) - 1)/6 + 1
                        if (.not. any(parts == p)) parts = [parts, p]
                    end do
                end do
                site%at_marker = .false.
                site%on_ground = .false.
                do p = 1, size(model%parts)
                    if (.not. any(parts == p)) cycle
                    site%part = p
                    site%stem = "ucon" // to_text(statement%id)
                    if (statement%kind == statement_element) site%stem = element_stem(statement)
                    if (size(parts) > 1) site%stem = site%stem // "_part" &
                        & // to_text(model%parts(p)%id)
                    call append(sites, site)
                end do
                deallocate(parts)
            end associate
        end do
    end function reaction_sites

    !> The column stem of an element's reaction: its name in lower case without the slash
    !> ("MOTION/1": "motion1", "COUPLER/2": "coupler2").
    pure function element_stem(statement) result(stem)
        type(statement_type), intent(in) :: statement
        character(len=:), allocatable :: stem
        integer :: slash

        stem = lower_case(statement%name)
        slash = index(stem, "/")
        if (slash > 0) stem = stem(:slash - 1) // stem(slash + 1:)
    end function element_stem

    !> Append one site (element by element: gfortran 12 may mishandle an array constructor of
    !> a type with allocatable components).
    pure subroutine append(sites, site)
        type(reaction_site_type), allocatable, intent(inout) :: sites(:)
        type(reaction_site_type), intent(in) :: site
        type(reaction_site_type), allocatable :: grown(:)
        integer :: k

        allocate(grown(size(sites) + 1))
        do k = 1, size(sites)
            grown(k) = sites(k)
        end do
        grown(size(grown)) = site
        call move_alloc(grown, sites)
    end subroutine append

    !> A site's force and torque (fx, fy, fz, tx, ty, tz) [N, N m], ground axes: on the part of
    !> marker I at marker I (a JOINT or JPRIM), or on the part at its centre of mass (a UCON);
    !> from the constraint rows c (C, nc x n: dF/du, or dF/dq for a position UCON, by rows over
    !> each UCON's coordinates; the site's rows read on the part's six) and the multipliers
    !> lambda (nc) at the coordinates q (n); attitude: the site's part's at q (part_attitude),
    !> when the caller has it already (several sites on one part), else made here.
    pure function site_wrench(model, site, c, lambda, q, attitude) result(wrench)
        type(model_type), intent(in) :: model
        type(reaction_site_type), intent(in) :: site
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: lambda(:), q(:)
        type(part_attitude_type), intent(in), optional :: attitude
        real(wp) :: wrench(6)
        real(wp) :: generalised(6), row(6), s
        type(part_attitude_type) :: made
        integer :: i0, i, k, x, j

        i0 = 6*(site%part - 1)
        generalised = 0.0_wp
        do i = 1, size(site%rows)
            k = site%rows(i)
            s = lambda(k)
            if (ieee_is_finite(s)) then
                ! the row's entries on the part's six alone (C's columns ascend in a row, as
                ! gather reads them): an entry absent would add s 0 = +-0, which changes
                ! nothing (each sum starts at +0, so is never -0)
                do x = c%start(k), c%start(k + 1) - 1
                    if (c%column(x) > i0) exit
                end do
                do x = x, c%start(k + 1) - 1
                    j = c%column(x) - i0
                    if (j > 6) exit
                    generalised(j) = generalised(j) + s*c%value(x)
                end do
            else
                ! a multiplier not finite: the whole row's product (s 0 is NaN)
                call c%gather(k, i0 + 1, row)
                generalised = generalised + s*row
            end if
        end do
        if (present(attitude)) then
            wrench = attitude_wrench(model, site, attitude, generalised, q)
        else
            made = part_attitude(q, site%part)
            wrench = attitude_wrench(model, site, made, generalised, q)
        end if
    end function site_wrench

    !> site_wrench's force and torque from the generalised constraint forces on the part's six
    !> coordinates [N, N m] and the part's attitude at q.
    pure function attitude_wrench(model, site, attitude, generalised, q) result(wrench)
        type(model_type), intent(in) :: model
        type(reaction_site_type), intent(in) :: site
        type(part_attitude_type), intent(in) :: attitude
        real(wp), intent(in) :: generalised(6), q(:)
        real(wp) :: wrench(6)
        real(wp) :: force(3), moment(3)
        integer :: i0

        i0 = 6*(site%part - 1)
        force = generalised(1:3)
        moment = times(attitude%rotation, angles_moment(attitude%sin_theta, attitude%cos_theta, &
            & attitude%sin_phi, attitude%cos_phi, generalised(4:6)))
        if (site%at_marker) then
            associate (marker => model%statements(site%statement)%i)
                if (site%on_ground) then
                    ! minus J's part's force, and minus its moment about I
                    moment = -(moment + cross(q(i0 + 1:i0 + 3) - marker%point, force))
                    force = -force
                else
                    moment = moment - cross(times(attitude%rotation, marker%point), force)
                end if
            end associate
        end if
        wrench(1:3) = force
        wrench(4:6) = moment
    end function attitude_wrench

    !> The reaction on the part of a JOINT's or JPRIM's marker J, at J [N, N m], ground axes,
    !> from its reaction `wrench` on the part of marker I at I (site_wrench): equal and
    !> opposite, its moment taken about J: (-F, -T - (r_I - r_J) x F), r the markers' origins in
    !> ground at the coordinates q.
    pure function swapped_wrench(model, site, wrench, q) result(turned)
        type(model_type), intent(in) :: model
        type(reaction_site_type), intent(in) :: site
        real(wp), intent(in) :: wrench(6), q(:)
        real(wp) :: turned(6)

        associate (statement => model%statements(site%statement))
            turned(1:3) = -wrench(1:3)
            turned(4:6) = -wrench(4:6) - cross(marker_origin(statement%i, q) &
                & - marker_origin(statement%j, q), wrench(1:3))
        end associate
    end function swapped_wrench

    !> A marker's origin in ground [m] at the coordinates q: on the ground as given, on part p
    !> its centre of mass plus R(psi, theta, phi) times the origin in the principal axes.
    pure function marker_origin(marker, q) result(origin)
        type(marker_type), intent(in) :: marker
        real(wp), intent(in) :: q(:)
        real(wp) :: origin(3)
        integer :: i0

        origin = marker%point
        if (marker%part == 0) return
        i0 = 6*(marker%part - 1)
        origin = q(i0 + 1:i0 + 3) + times(rotation_matrix(q(i0 + 4), q(i0 + 5), q(i0 + 6)), &
            & marker%point)
    end function marker_origin

    !> The moment tau' about the centre of mass, principal axes [N m], whose generalised force
    !> on the Euler angles is B^T tau' = q_angles (B: omega' = B (psi', theta', phi'),
    !> docs/design.md §3); sin(theta) must be away from 0 (re-basing keeps it so).
    pure function body_moment(theta, phi, q_angles) result(moment)
        real(wp), intent(in) :: theta, phi, q_angles(3)
        real(wp) :: moment(3)

        moment = angles_moment(sin(theta), cos(theta), sin(phi), cos(phi), q_angles)
    end function body_moment

    !> body_moment from the sines and cosines of theta and phi.
    pure function angles_moment(sin_theta, cos_theta, sin_phi, cos_phi, q_angles) result(moment)
        real(wp), intent(in) :: sin_theta, cos_theta, sin_phi, cos_phi, q_angles(3)
        real(wp) :: moment(3)
        real(wp) :: across

        ! B^T = [s_theta s_phi, s_theta c_phi, c_theta; c_phi, -s_phi, 0; 0, 0, 1]
        moment(3) = q_angles(3)
        across = (q_angles(1) - cos_theta*q_angles(3))/sin_theta
        moment(1) = sin_phi*across + cos_phi*q_angles(2)
        moment(2) = cos_phi*across - sin_phi*q_angles(2)
    end function angles_moment

end module rollcon_reactions
