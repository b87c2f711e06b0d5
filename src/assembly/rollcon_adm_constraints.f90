! SPDX-License-Identifier: MIT
!> A dataset's constraints written as expressions, assembled: each GCON, and each coupling of
!> joint motions (a RACKPIN or SCREW joint, a COUPLER, a GEAR) as the GCON of the measures it
!> relates (docs/datasets-model.md, "GCONs and couplers"), added with model%add_gcon. Also the
!> markers an expression reads (a force's or a GCON's), found and checked here for both.
!>
!> A coupling relates each joint's displacement, measured as ADAMS measures a joint's: a
!> translation DZ(I, J, J) along J's z axis, a rotation AZ(I, J) about it (whole turns
!> counted). Each relation holds between the displacements from the start, so a model that
!> starts as written is not moved by its couplers.
module rollcon_adm_constraints
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, place
    use rollcon_rotation, only : cross
    use rollcon_expression, only : expression_type, expression_input_type, evaluate_expression, &
        & op_constant, op_input, op_multiply, op_add, op_subtract, quantity_names, quantity_dx, &
        & quantity_ax, quantity_dif, quantity_dif1, quantity_varval
    use rollcon_marker, only : marker_type, marker_motion
    use rollcon_measures, only : expression_input_values, input_refusal, input_text
    use rollcon_model, only : model_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_joints, only : adm_joint_type
    use rollcon_adm_markers, only : adm_marker, marker_index
    implicit none
    private

    public :: add_expression_constraints, expression_markers

    !> Least |sin| of the angle between a RACKPIN's pinion axis and rack axis, and least share
    !> of PD/2 of J's offset from the pinion's axis: below them the start is not a rack and
    !> pinion (axes parallel; J on the pinion's axis, no side to roll on)
    real(wp), parameter :: least_sine = 1.0e-6_wp, least_offset = 1.0e-6_wp

contains

    !> Every marker `expression` reads (i, j, k, l of each measure), as the model holds them;
    !> refused, after `where` ("file:line: GCON/1 FUNCTION"): a marker the dataset lacks, or
    !> what cannot be read in `kind` ("a force's FUNCTION", "a constraint's FUNCTION":
    !> rollcon_measures' input_refusal).
    subroutine expression_markers(adm, expression, where, kind, markers, error)
        type(adm_model_type), intent(in) :: adm
        type(expression_type), intent(in) :: expression
        character(len=*), intent(in) :: where, kind
        type(marker_type), allocatable, intent(out) :: markers(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: problem
        integer :: n, m, ids(4)

        allocate(markers(0))
        do n = 1, size(expression%inputs)
            associate (input => expression%inputs(n))
                ! VARVAL(id) left in place by the reader: a VARSUB's VARIABLE, valued at run
                ! time (rollcon_user_forces); it names no marker
                if (input%quantity == quantity_varval) cycle
                problem = input_refusal(input, kind)
                if (len(problem) > 0) then
                    call fatal_error(error, where // ": " // problem, stat_input)
                    return
                end if
                ! DIF(id), DIF1(id): a DIFF's id, no marker (rollcon_adm_variables checks it)
                if (input%quantity == quantity_dif .or. input%quantity == quantity_dif1) cycle
                ids = [input%marker, input%j, input%k, input%l]
                do m = 1, 4
                    if (ids(m) == 0) cycle
                    if (marker_index(adm, ids(m)) == 0) then
                        call fatal_error(error, where // ": " // input_text(input) &
                            & // ": no MARKER/" // to_text(ids(m)) // " in the dataset", &
                            & stat_input)
                        return
                    end if
                    if (.not. any(markers%id == ids(m))) &
                        & markers = [markers, adm_marker(adm, ids(m))]
                end do
            end associate
        end do
    end subroutine expression_markers

    !> The dataset's GCONs, then its RACKPIN and SCREW joints, COUPLERs and GEARs, each a GCON
    !> of the model (after its UCONs and joints); q0, u0: the start (model order, SI), from
    !> which couplings measure their joints' displacements.
    subroutine add_expression_constraints(adm, model, q0, u0, error)
        type(adm_model_type), intent(in) :: adm
        type(model_type), intent(inout) :: model
        real(wp), intent(in) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        type(marker_type), allocatable :: markers(:)
        character(len=:), allocatable :: where
        integer :: k

        if (allocated(adm%gcons)) then
            do k = 1, size(adm%gcons)
                associate (gcon => adm%gcons(k))
                    call expression_markers(adm, gcon%function, gcon%function_at, &
                        & "a constraint's FUNCTION", markers, error)
                    if (allocated(error)) return
                    call model%add_gcon(gcon%id, gcon%function, markers, adm_marker(adm, &
                        & gcon%i), error, line=gcon%line)
                    if (allocated(error)) then
                        error%message = place(adm%file, gcon%line) // ": " // error%message
                        return
                    end if
                end associate
            end do
        end if
        do k = 1, size(adm%joints)
            associate (joint => adm%joints(k))
                if (joint%kind /= "RACKPIN" .and. joint%kind /= "SCREW") cycle
                where = place(adm%file, joint%line) // ": JOINT/" // to_text(joint%id)
                call add_coupling_joint(adm, joint, where, model, q0, u0, error)
                if (allocated(error)) return
            end associate
        end do
        if (allocated(adm%couplers)) then
            do k = 1, size(adm%couplers)
                call add_coupler(adm, k, model, q0, u0, error)
                if (allocated(error)) return
            end do
        end if
        if (allocated(adm%gears)) then
            do k = 1, size(adm%gears)
                call add_gear(adm, k, model, q0, u0, error)
                if (allocated(error)) return
            end do
        end if
    end subroutine add_expression_constraints

    !> RACKPIN: DZ(I, J, J) - s PD/2 AZ(I, K), K a marker on J's part whose z axis is the
    !> pinion's (I's z) and whose x axis is the rack's (J's z) at the start, so AZ(I, K) is the
    !> pinion's turn about its axis from the rack's direction; s = +1 when the rack (J's origin)
    !> lies on the side of y_k = z_i x z_j from the pinion's axis, -1 on the other: the pitch
    !> circle then rolls on the rack. SCREW: DZ(I, J, J) - PITCH/(2 pi) AZ(I, J).
    subroutine add_coupling_joint(adm, joint, where, model, q0, u0, error)
        type(adm_model_type), intent(in) :: adm
        type(adm_joint_type), intent(in) :: joint
        character(len=*), intent(in) :: where
        type(model_type), intent(inout) :: model
        real(wp), intent(in) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        type(marker_type) :: i, j, k
        type(marker_type), allocatable :: markers(:)
        type(expression_input_type) :: inputs(2)
        real(wp) :: r_i(3), r_j(3), axes_i(3, 3), axes_j(3, 3), part_axes(3, 3), v(3), w(3), &
            & x_k(3), y_k(3), z_k(3), side, radius
        character(len=:), allocatable :: text

        i = adm_marker(adm, joint%i)
        j = adm_marker(adm, joint%j)
        inputs(1) = expression_input_type(marker=joint%i, quantity=quantity_dx + 2, j=joint%j, &
            & k=joint%j)
        if (joint%kind == "SCREW") then
            inputs(2) = expression_input_type(marker=joint%i, quantity=quantity_ax + 2, &
                & j=joint%j)
            markers = [i, j]
            text = "DZ(" // to_text(joint%i) // ", " // to_text(joint%j) // ", " &
                & // to_text(joint%j) // ") - PITCH/(2 PI) AZ(" // to_text(joint%i) // ", " &
                & // to_text(joint%j) // ")"
            call add_linear(where, joint%line, text, inputs, [1.0_wp, &
                & -joint%pitch/adm%units%length/(2.0_wp*pi)], markers, adm%units%length, &
                & adm%units%time, model, q0, u0, error)
            return
        end if
        call marker_motion(i, q0, u0, r_i, v, axes_i, w)
        call marker_motion(j, q0, u0, r_j, v, axes_j, w)
        z_k = axes_i(:, 3)
        x_k = axes_j(:, 3)
        if (abs(dot_product(z_k, x_k)) > least_sine) then
            call fatal_error(error, where // ": RACKPIN: the pinion's axis (MARKER/" &
                & // to_text(joint%i) // "'s z) is not perpendicular to the rack (MARKER/" &
                & // to_text(joint%j) // "'s z) at the start (cosine " &
                & // to_text(dot_product(z_k, x_k)) // ")", stat_input)
            return
        end if
        y_k = cross(z_k, x_k)
        radius = 0.5_wp*joint%pd
        side = dot_product(r_j - r_i, y_k)
        if (abs(side) < least_offset*radius) then
            call fatal_error(error, where // ": RACKPIN: MARKER/" // to_text(joint%j) &
                & // " (J, on the rack) lies on the pinion's axis at the start; place it on " &
                & // "the rack's pitch line, PD/2 from the pinion's axis, so that the side " &
                & // "the pinion rolls on is known", stat_input)
            return
        end if
        ! K: fixed on J's part, axes x_k, y_k, z_k in that part's principal axes
        k = marker_type(id=-joint%id, part=j%part)
        part_axes = identity()
        if (j%part > 0) part_axes = part_rotation(j, axes_j)
        k%axes(:, 1) = matmul(transpose(part_axes), x_k)
        k%axes(:, 2) = matmul(transpose(part_axes), y_k)
        k%axes(:, 3) = matmul(transpose(part_axes), z_k)
        inputs(2) = expression_input_type(marker=joint%i, quantity=quantity_ax + 2, j=k%id)
        markers = [i, j, k]
        text = "DZ(" // to_text(joint%i) // ", " // to_text(joint%j) // ", " &
            & // to_text(joint%j) // ") " // merge("-", "+", side > 0.0_wp) // " PD/2 AZ(" &
            & // to_text(joint%i) // ", the pinion's turn from the rack's direction)"
        call add_linear(where, joint%line, text, inputs, [1.0_wp, &
            & -sign(radius, side)/adm%units%length], markers, adm%units%length, &
            & adm%units%time, model, q0, u0, error)
    end subroutine add_coupling_joint

    !> The rotation from a moving part's principal axes to ground, from one of its markers'
    !> axes in ground (axes = R marker%axes, marker%axes orthonormal).
    pure function part_rotation(marker, axes) result(r)
        type(marker_type), intent(in) :: marker
        real(wp), intent(in) :: axes(3, 3)
        real(wp) :: r(3, 3)

        r = matmul(axes, transpose(marker%axes))
    end function part_rotation

    !> COUPLER/id: sum_k r_k q_k, q_k a joint's translation (T) or rotation (R).
    subroutine add_coupler(adm, c, model, q0, u0, error)
        type(adm_model_type), intent(in) :: adm
        integer, intent(in) :: c
        type(model_type), intent(inout) :: model
        real(wp), intent(in) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        type(expression_input_type), allocatable :: inputs(:)
        type(marker_type), allocatable :: markers(:)
        character(len=:), allocatable :: where, text
        character(len=1) :: kind
        integer :: k, n

        associate (coupler => adm%couplers(c))
            where = place(adm%file, coupler%line) // ": COUPLER/" // to_text(coupler%id)
            n = size(coupler%joints)
            allocate(inputs(n), markers(0))
            text = ""
            do k = 1, n
                call joint_displacement(adm, coupler%joints(k), coupler%types(k), where, &
                    & inputs(k), kind, error)
                if (allocated(error)) return
                call add_joint_markers(adm, inputs(k), markers)
                if (k > 1) text = text // " + "
                text = text // to_text(coupler%scales(k)) // " " // displacement_text(inputs(k))
            end do
            call add_linear(where, coupler%line, text, inputs, coupler%scales, markers, &
                & adm%units%length, adm%units%time, model, q0, u0, error)
        end associate
    end subroutine add_coupler

    !> GEAR/id: c1 q1 - c2 q2, c_k the speed along CV's z axis of the point of contact (CV's
    !> origin) carried by joint k per unit of its motion, at the start: (z_J x (r_CV - r_I)) .
    !> z_CV for a rotation, z_J . z_CV for a translation.
    subroutine add_gear(adm, g, model, q0, u0, error)
        type(adm_model_type), intent(in) :: adm
        integer, intent(in) :: g
        type(model_type), intent(inout) :: model
        real(wp), intent(in) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        type(expression_input_type) :: inputs(2)
        type(marker_type), allocatable :: markers(:)
        type(marker_type) :: cv, i, j
        real(wp) :: r_cv(3), axes_cv(3, 3), r_i(3), axes_i(3, 3), r_j(3), axes_j(3, 3), v(3), &
            & w(3), c(2)
        character(len=:), allocatable :: where, text
        character(len=1) :: kind
        integer :: k

        associate (gear => adm%gears(g))
            where = place(adm%file, gear%line) // ": GEAR/" // to_text(gear%id)
            cv = adm_marker(adm, gear%cv)
            call marker_motion(cv, q0, u0, r_cv, v, axes_cv, w)
            allocate(markers(0))
            do k = 1, 2
                call joint_displacement(adm, gear%joints(k), " ", where, inputs(k), kind, error)
                if (allocated(error)) return
                i = adm_marker(adm, inputs(k)%marker)
                j = adm_marker(adm, inputs(k)%j)
                if (j%part /= cv%part) then
                    call fatal_error(error, where // ": JOINT/" // to_text(gear%joints(k)) &
                        & // "'s J marker (MARKER/" // to_text(j%id) // ") is not on the " &
                        & // "carrier, the part of CV's MARKER/" // to_text(gear%cv) // ": a " &
                        & // "gear's joints hold both gears to the carrier by their J markers", &
                        & stat_input)
                    return
                end if
                call marker_motion(i, q0, u0, r_i, v, axes_i, w)
                call marker_motion(j, q0, u0, r_j, v, axes_j, w)
                if (kind == "R") then
                    c(k) = dot_product(cross(axes_j(:, 3), r_cv - r_i), axes_cv(:, 3))
                    ! to the dataset's length unit: the expression's AZ is in radians
                    c(k) = c(k)/adm%units%length
                else
                    c(k) = dot_product(axes_j(:, 3), axes_cv(:, 3))
                end if
                call add_joint_markers(adm, inputs(k), markers)
            end do
            if (any(abs(c) <= epsilon(1.0_wp)*max(1.0_wp, maxval(abs(c))))) then
                call fatal_error(error, where // ": a joint's motion does not move the point " &
                    & // "of contact (CV's origin) along CV's z axis at the start: place CV at " &
                    & // "the point of contact, its z axis along the common velocity", stat_input)
                return
            end if
            markers = [markers, cv]
            text = to_text(c(1)) // " " // displacement_text(inputs(1)) // " - " &
                & // to_text(c(2)) // " " // displacement_text(inputs(2))
            call add_linear(where, gear%line, text, inputs, [c(1), -c(2)], markers, &
                & adm%units%length, adm%units%time, model, q0, u0, error)
        end associate
    end subroutine add_gear

    !> The displacement of JOINT/id a coupler reads: T, DZ(I, J, J); R, AZ(I, J). `written`:
    !> TYPE's T or R, " " for none (a REVOLUTE's is R, a TRANSLATIONAL's T; a CYLINDRICAL
    !> needs it); other joints are refused.
    subroutine joint_displacement(adm, id, written, where, input, kind, error)
        type(adm_model_type), intent(in) :: adm
        integer, intent(in) :: id
        character(len=1), intent(in) :: written
        character(len=*), intent(in) :: where
        type(expression_input_type), intent(out) :: input
        character(len=1), intent(out) :: kind
        type(error_type), allocatable, intent(out) :: error
        integer :: k

        k = findloc(adm%joints%id, id, dim=1, mask=.not. adm%joints%primitive)
        kind = written
        associate (joint => adm%joints(k))
            select case (joint%kind)
            case ("REVOLUTE")
                if (kind == " ") kind = "R"
            case ("TRANSLATIONAL")
                if (kind == " ") kind = "T"
            case ("CYLINDRICAL")
                if (kind == " ") then
                    call fatal_error(error, where // ": JOINT/" // to_text(id) // " is " &
                        & // "CYLINDRICAL: say whether its translation or its rotation is " &
                        & // "coupled (TYPE=T or R for it)", stat_input)
                    return
                end if
            case default
                call fatal_error(error, where // ": JOINT/" // to_text(id) // " is " &
                    & // joint%kind // "; couplers relate TRANSLATIONAL, REVOLUTE and " &
                    & // "CYLINDRICAL joints", stat_input)
                return
            end select
            if ((joint%kind == "REVOLUTE" .and. kind == "T") .or. (joint%kind == &
                & "TRANSLATIONAL" .and. kind == "R")) then
                call fatal_error(error, where // " TYPE: JOINT/" // to_text(id) // " is " &
                    & // joint%kind // ", which has no " // merge("translation", "rotation   ", &
                    & kind == "T"), stat_input)
                return
            end if
            if (kind == "T") then
                input = expression_input_type(marker=joint%i, quantity=quantity_dx + 2, &
                    & j=joint%j, k=joint%j)
            else
                input = expression_input_type(marker=joint%i, quantity=quantity_ax + 2, &
                    & j=joint%j)
            end if
        end associate
    end subroutine joint_displacement

    !> "DZ(i, j, k)" or "AZ(i, j)" of an input.
    pure function displacement_text(input) result(text)
        type(expression_input_type), intent(in) :: input
        character(len=:), allocatable :: text

        text = trim(quantity_names(input%quantity)) // "(" // to_text(input%marker) // ", " &
            & // to_text(input%j)
        if (input%k /= 0) text = text // ", " // to_text(input%k)
        text = text // ")"
    end function displacement_text

    !> The markers of a joint displacement's input appended to markers (once each).
    subroutine add_joint_markers(adm, input, markers)
        type(adm_model_type), intent(in) :: adm
        type(expression_input_type), intent(in) :: input
        type(marker_type), allocatable, intent(inout) :: markers(:)

        if (.not. any(markers%id == input%marker)) markers = [markers, adm_marker(adm, &
            & input%marker)]
        if (.not. any(markers%id == input%j)) markers = [markers, adm_marker(adm, input%j)]
    end subroutine add_joint_markers

    !> The GCON sum_k scales(k) inputs(k) - F0, F0 its value at the start, named by `where`
    !> (its statement) with `text` (the sum, for messages), in the dataset's units.
    subroutine add_linear(where, line, text, inputs, scales, markers, length_unit, time_unit, &
            & model, q0, u0, error)
        character(len=*), intent(in) :: where
        !> The statement's line in the dataset
        integer, intent(in) :: line
        character(len=*), intent(in) :: text
        type(expression_input_type), intent(in) :: inputs(:)
        real(wp), intent(in) :: scales(:)
        type(marker_type), intent(in) :: markers(:)
        real(wp), intent(in) :: length_unit, time_unit
        type(model_type), intent(inout) :: model
        real(wp), intent(in) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        type(expression_type) :: expression
        real(wp) :: values(size(inputs)), start
        integer :: k, n

        n = size(inputs)
        allocate(expression%op(0), expression%constant(0))
        do k = 1, n
            expression%op = [expression%op, op_input, op_constant, op_multiply]
            expression%constant = [expression%constant, real(k, wp), scales(k), 0.0_wp]
            if (k > 1) then
                expression%op = [expression%op, op_add]
                expression%constant = [expression%constant, 0.0_wp]
            end if
        end do
        expression%inputs = inputs
        allocate(expression%anchors(n), source=0.0_wp)
        expression%text = text
        expression%uses_time = .false.
        ! the relation holds between displacements from the start
        call expression_input_values(expression, markers, length_unit, time_unit, q0, u0, &
            & values)
        start = evaluate_expression(expression, 0.0_wp, values)
        expression%op = [expression%op, op_constant, op_subtract]
        expression%constant = [expression%constant, start, 0.0_wp]
        expression%text = text // " - (its value at the start, " // to_text(start) // ")"
        call model%add_gcon(0, expression, markers, markers(1), error, &
            & name=where(index(where, ": ", back=.true.) + 2:), line=line)
        if (allocated(error)) then
            ! add_gcon names a GCON/0: name the statement instead
            error%message = where // error%message(index(error%message, ": ") :)
        end if
    end subroutine add_linear

    pure function identity() result(m)
        real(wp) :: m(3, 3)

        m = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], &
            & [3, 3])
    end function identity

end module rollcon_adm_constraints
