! SPDX-License-Identifier: MIT
!> ADAMS's measures of markers, as a function expression reads them (docs/datasets.md,
!> "Measures of markers"): with d = r_i - r_j, the axes of marker k (x_k, y_k, z_k), the
!> angular velocity w_l of marker l's frame and the default j, k, l the ground,
!>
!> - DX, DY, DZ(i, j, k) = d . x_k, y_k, z_k; DM(i, j) = |d|;
!> - VX, VY, VZ(i, j, k, l) = (v_i - v_j - w_l x d) . x_k, ... (the time derivative of d taken
!>   in l's frame); VM(i, j, l) its magnitude; VR(i, j, l) = (v_i - v_j) . d / |d| (the rate of
!>   the distance, the same in every frame);
!> - WX, WY, WZ(i, j, k) = (w_i - w_j) . x_k, ...; WM(i, j) = |w_i - w_j|;
!> - AX(i, j) = atan2(-z_i . y_j, z_i . z_j), AY(i, j) = atan2(z_i . x_j, z_i . z_j),
!>   AZ(i, j) = atan2(x_i . y_j, x_i . x_j), counting whole turns as ADAMS does (the branch
!>   nearest the value where the turns were last counted, count_turns);
!> - PSI, THETA, PHI(i, j): the body 3-1-3 angles of i's axes in j's; YAW, PITCH, ROLL(i, j):
!>   the body 3-2-1 angles, PITCH the negative of the second (ADAMS's automotive sign);
!> - ORIENT(system, component, i, j): i's axes in j's, A = A_j^T A_i, in ADAMS's orientation
!>   system 1 to 24 (the body-fixed, then the space-fixed, Euler sequences 1-2-3, 2-3-1,
!>   3-1-2, 1-3-2, 2-1-3, 3-2-1, 1-2-1, 1-3-1, 2-1-2, 2-3-2, 3-1-3, 3-2-3), 27 (the Euler
!>   parameters e0 >= 0, e1, e2, e3), 28 (the Rodrigues parameters) or 29 (the direction
!>   cosines: x_i's in j's axes, then y_i's, then z_i's), as rollcon_adams_utilities'
!>   RCNVRT converts the matrix (its "Bijk", "Sijk", EULPAR, RODPAR, COSINES); systems 25 and
!>   26 (AX, AY, AZ; YAW, PITCH, ROLL) are read as those measures (rollcon_adm_expression_
!>   parser). The numbering: the Adams Solver reference, "ORIENT" (systems 1 to 12), and
!>   BETA CAE's ANSA scripting reference of the same function, ansa.kinetics.Orient (1 to 29).
!>   A value path only: no jet, so only a REQUEST reads it (input_refusal).
!>
!> Each measure has a value path (real numbers from rollcon_marker's marker_motion: every
!> right-hand side of a force) and a jet path (the same definitions over the parts' q and u
!> as jets, rollcon_jet: exact partials to second order, for GCON and the Newton matrices).
!> Accelerations, forces and the values of other statements are not measures of the state:
!> NaN here (the assembly refuses them where they would be read).
module rollcon_measures
    use rollcon_kinds, only : wp
    use rollcon_user_variable_values, only : user_variable_value, user_variable_jet
    use rollcon_constants, only : pi
    use rollcon_adams_utilities, only : convert_rotation, rcnvrt_success
    use rollcon_rotation, only : times, cross, euler_angles
    use rollcon_marker, only : marker_type, marker_motion, marker_quantity
    use rollcon_jet, only : jet_type, jet_constant, jet_variable, jet_dot, jet_cross, &
        & jet_norm, jet_times, operator(+), operator(-), operator(*), operator(/), sin, cos, &
        & sqrt, atan2
    use rollcon_expression, only : expression_type, expression_input_type, quantity_dx, &
        & quantity_vx, quantity_wx, quantity_psi, quantity_dm, quantity_vm, quantity_vr, &
        & quantity_wm, quantity_ax, quantity_yaw, quantity_kind, kind_length, kind_velocity, &
        & kind_angular_velocity, kind_acceleration, kind_angular_acceleration, kind_element, &
        & kind_element_force, quantity_names, quantity_accm, quantity_wdtm, quantity_varval, &
        & quantity_orient
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: measure_value, measure_jet, state_jets_type, new_state_jets, part_slot, marker_jets
    public :: input_markers, expression_input_values, expression_input_jets, quantity_scale
    public :: counts_turns, reads_rates, is_state_measure, unwrap_angle, input_refusal
    public :: input_text, count_turns

    !> The parts' coordinates and rates as jets: the independent variables of a computation of
    !> partials, or constants.
    type :: state_jets_type
        !> The model index of each part held (ground, 0, is never held)
        integer, allocatable :: parts(:)
        !> q and u of each part held (6, size(parts))
        type(jet_type), allocatable :: q(:, :), u(:, :)
    end type state_jets_type

contains

    !> True for a measure of position, velocity or angle of markers (DX ... ROLL): a function
    !> of the parts' coordinates and rates alone.
    elemental logical function is_state_measure(quantity)
        integer, intent(in) :: quantity

        is_state_measure = quantity >= 1 .and. quantity <= quantity_yaw + 2
    end function is_state_measure

    !> Why an input cannot be read in `place` ("a force's FUNCTION", "a constraint's
    !> FUNCTION"): "" for a measure of the state. Accelerations and forces are solved for with
    !> the motion, so reading them in a FUNCTION that gives a force or a constraint makes an
    !> algebraic loop, which rollcon does not solve for an expression; a force (a reaction, an
    !> applied force) read in a VARIABLE's, a DIFF's or a force's FUNCTION would need partials
    !> the expressions' jets do not carry (a reaction's in the coordinates at fixed
    !> multipliers), and the reason names the routine that may read it through SYSFNC
    !> (routine_reading); DIF and DIF1 (a DIFF's state and its rate,
    !> rollcon_diff) are read by forces, VARIABLEs and DIFFs, not by a constraint's or a
    !> MOTION's FUNCTION (a dataset's VARVALs are put in place before: rollcon_adm_variables).
    pure function input_refusal(input, place) result(reason)
        type(expression_input_type), intent(in) :: input
        character(len=*), intent(in) :: place
        character(len=:), allocatable :: reason
        character(len=:), allocatable :: name

        reason = ""
        if (is_state_measure(input%quantity)) return
        name = input_text(input)
        if (input%quantity == quantity_orient) then
            reason = name // ": ORIENT of system " // trim(adjustl(int_text(input%system))) &
                & // " is answered in a REQUEST only: rollcon has no exact partials of it, " &
                & // "which " // place // " needs (its systems 25 and 26, AX, AY, AZ and YAW, " &
                & // "PITCH, ROLL, are read anywhere)"
            return
        end if
        select case (quantity_kind(input%quantity))
        case (kind_acceleration, kind_angular_acceleration)
            reason = name // ": an acceleration, which rollcon knows only once it has solved " &
                & // "for the forces; read in " // place // " (which gives a force or a " &
                & // "constraint) it makes an algebraic loop rollcon does not solve"
        case (kind_element)
            if (input%quantity == quantity_varval) then
                reason = name // ": a VARIABLE's value, which a dataset's reader puts in " &
                    & // "place; a model built in code writes the VARIABLE's expression itself"
            else if (index(place, "constraint") > 0 .or. index(place, "MOTION") > 0) then
                ! a DIFF's state in a constraint would join the constraint's partials
                reason = name // ": a DIFF's state (user differential equation), which " &
                    & // place // " may not read: a force, a VARIABLE or another DIFF may"
            end if
        case default
            reason = name // ": a force, which rollcon solves for together with the motion " &
                & // "(a reaction, or a force that may depend on this one); read in " // place
            if (len(routine_reading(place)) > 0) then
                ! a VARIABLE's, a DIFF's or a force's: the loop is solved for a routine's
                ! reads, whose partials are differenced; an expression's are exact jets
                reason = reason // " it needs partials rollcon's expressions do not carry " &
                    & // "(their exact forward-mode partials are the markers' measures'; a " &
                    & // "reaction's in the coordinates, at fixed multipliers, are the " &
                    & // "constraints' second partials through the joint's markers, and an " &
                    & // "expression is never differenced): read it in " &
                    & // routine_reading(place) // " through SYSFNC (docs/datasets.md, " &
                    & // "'Force measures read by a user's routine')"
            else
                reason = reason // " it makes an algebraic loop rollcon does not solve"
            end if
        end select
    end function input_refusal

    !> The user routine that may read a force measure where `place` (input_refusal's) may
    !> not: "a VARSUB" for a VARIABLE's FUNCTION, "a DIFSUB" for a DIFF's, "a force routine
    !> (FUNCTION=USER: SFOSUB, VFOSUB, VTOSUB, GFOSUB)" for a force's; "" for a constraint's or
    !> a MOTION's (a MOTSUB reads none: a MOTION is a function of TIME alone).
    pure function routine_reading(place) result(routine)
        character(len=*), intent(in) :: place
        character(len=:), allocatable :: routine

        routine = ""
        if (index(place, "VARIABLE") > 0) then
            routine = "a VARSUB"
        else if (index(place, "DIFF") > 0) then
            routine = "a DIFSUB"
        else if (index(place, "force") > 0) then
            routine = "a force routine (FUNCTION=USER: SFOSUB, VFOSUB, VTOSUB, GFOSUB)"
        end if
    end function routine_reading

    !> An input as written: "DX(21, 11)", "VM(21, 0, 31)", "JOINT(3, 0, 2, 0)",
    !> "ORIENT(27, 1, 21, 11)"; the ids not given left out. An element function is named as
    !> ADAMS names the function (BUSH, VTORQ; the statements are BUSHING, VTORQUE).
    pure function input_text(input) result(text)
        type(expression_input_type), intent(in) :: input
        character(len=:), allocatable :: text
        integer :: ids(4), last, m
        character(len=12) :: buffer

        if (input%quantity == quantity_orient) then
            text = "ORIENT(" // trim(adjustl(int_text(input%system))) // ", " &
                & // trim(adjustl(int_text(input%component))) // ", " &
                & // trim(adjustl(int_text(input%marker)))
            if (input%j /= 0) text = text // ", " // trim(adjustl(int_text(input%j)))
            text = text // ")"
            return
        end if
        ids = [input%marker, input%j, input%k, input%l]
        ! VM, VR, ACCM, WDTM are written (i, j, l)
        if (any(input%quantity == [quantity_vm, quantity_vr, quantity_accm, quantity_wdtm])) &
            & ids = [input%marker, input%j, input%l, 0]
        last = 1
        do m = 2, 4
            if (ids(m) /= 0) last = m
        end do
        if (quantity_kind(input%quantity) == kind_element_force) last = 4
        select case (trim(quantity_names(input%quantity)))
        case ("BUSHING")
            text = "BUSH("
        case ("VTORQUE")
            text = "VTORQ("
        case default
            text = trim(quantity_names(input%quantity)) // "("
        end select
        do m = 1, last
            write(buffer, '(i0)') ids(m)
            if (m > 1) text = text // ", "
            text = text // trim(buffer)
        end do
        text = text // ")"
    end function input_text

    !> A whole number as text (blanks around it).
    pure function int_text(n) result(text)
        integer, intent(in) :: n
        character(len=12) :: text

        write(text, '(i0)') n
    end function int_text

    !> True for a measure that reads the parts' rates (velocities, angular velocities).
    elemental logical function reads_rates(quantity)
        integer, intent(in) :: quantity

        reads_rates = any(quantity_kind(quantity) == [kind_velocity, kind_angular_velocity])
    end function reads_rates

    !> True for AX, AY, AZ: angles whose whole turns are counted.
    elemental logical function counts_turns(quantity)
        integer, intent(in) :: quantity

        counts_turns = quantity >= quantity_ax .and. quantity < quantity_ax + 3
    end function counts_turns

    !> The branch of an angle raw (in (-pi, pi]) nearest to anchor [rad].
    elemental real(wp) function unwrap_angle(raw, anchor)
        real(wp), intent(in) :: raw, anchor

        unwrap_angle = raw + 2.0_wp*pi*anint((anchor - raw)/(2.0_wp*pi))
    end function unwrap_angle

    !> The factor that turns a measure's SI value into the dataset's units [dataset unit / SI
    !> unit] (1 for angles and for what is not a measure of the state).
    elemental real(wp) function quantity_scale(quantity, length_unit, time_unit) result(scale)
        integer, intent(in) :: quantity
        !> Size of the dataset's length [m] and time [s] units
        real(wp), intent(in) :: length_unit, time_unit

        select case (quantity_kind(quantity))
        case (kind_length)
            scale = 1.0_wp/length_unit
        case (kind_velocity)
            scale = time_unit/length_unit
        case (kind_angular_velocity)
            scale = time_unit
        case default
            scale = 1.0_wp
        end select
    end function quantity_scale

    !> The markers i, j, k, l of an input among `markers` (by id); a marker not given (id 0) is
    !> the ground's origin and axes; found(m) false for one not among them.
    pure subroutine input_markers(input, markers, chosen, found)
        type(expression_input_type), intent(in) :: input
        type(marker_type), intent(in) :: markers(:)
        type(marker_type), intent(out) :: chosen(4)
        logical, intent(out) :: found(4)
        integer :: ids(4), m, s

        ids = [input%marker, input%j, input%k, input%l]
        do m = 1, 4
            found(m) = ids(m) == 0
            if (found(m)) cycle
            do s = 1, size(markers)
                if (markers(s)%id /= ids(m)) cycle
                chosen(m) = markers(s)
                found(m) = .true.
                exit
            end do
        end do
    end subroutine input_markers

    !> The values of an expression's inputs at (q, u), in the dataset's units (the expression's
    !> own), its AX, AY, AZ on the branches its anchors choose. A marker missing from `markers`
    !> or an input that is not a measure of the state gives NaN.
    pure subroutine expression_input_values(expression, markers, length_unit, time_unit, q, u, &
            & values)
        type(expression_type), intent(in) :: expression
        !> Every marker the expression reads
        type(marker_type), intent(in) :: markers(:)
        !> Size of the dataset's length [m] and time [s] units
        real(wp), intent(in) :: length_unit, time_unit
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        !> One per input, in order
        real(wp), intent(out) :: values(:)
        type(marker_type) :: chosen(4)
        logical :: found(4)
        real(wp) :: scale, anchor
        integer :: k

        do k = 1, size(values)
            associate (input => expression%inputs(k))
                ! VARVAL(id) left in place: a user VARIABLE's (a VARSUB's) value
                if (input%quantity == quantity_varval) then
                    values(k) = user_variable_value(input%marker)
                    cycle
                end if
                call input_markers(input, markers, chosen, found)
                values(k) = ieee_value(1.0_wp, ieee_quiet_nan)
                if (input%quantity == quantity_orient .and. all(found)) then
                    values(k) = orient_value(input%system, input%component, chosen, q, u)
                    cycle
                end if
                if (.not. all(found) .or. .not. is_state_measure(input%quantity)) cycle
                ! the scales as the one-marker forms have always been computed
                scale = 1.0_wp
                if (input%quantity < quantity_psi) scale = 1.0_wp/length_unit
                if (input%quantity < quantity_psi .and. input%quantity >= quantity_wx) &
                    & scale = time_unit
                if (input%quantity < quantity_wx .and. input%quantity >= quantity_vx) &
                    & scale = time_unit/length_unit
                if (input%quantity > quantity_psi + 2) scale = quantity_scale(input%quantity, &
                    & length_unit, time_unit)
                if (one_marker_form(input)) then
                    values(k) = scale*marker_quantity(chosen(1), input%quantity, q, u)
                else
                    anchor = 0.0_wp
                    if (allocated(expression%anchors)) anchor = expression%anchors(k)
                    values(k) = scale*measure_value(input%quantity, chosen, q, u, anchor)
                end if
            end associate
        end do
    end subroutine expression_input_values

    !> Count the whole turns of the expression's AX, AY, AZ at (q, u): each one's anchor set to
    !> its value there, on the branch nearest its anchor (restart: nearest 0, the value in
    !> (-pi, pi]). Made at every output row of a run, so that an angle that turns by less than
    !> half a turn between rows is followed over any number of turns (docs/datasets.md,
    !> "Measures of markers").
    pure subroutine count_turns(expression, markers, length_unit, time_unit, q, u, restart)
        type(expression_type), intent(inout) :: expression
        type(marker_type), intent(in) :: markers(:)
        real(wp), intent(in) :: length_unit, time_unit, q(:), u(:)
        logical, intent(in) :: restart
        integer :: k

        if (.not. allocated(expression%inputs)) return
        ! input by input, and the inputs' values (an automatic array) made only for an
        ! expression that counts turns: a mask of expression%inputs%quantity is a temporary,
        ! and either was an allocation at every output row of every expression
        do k = 1, size(expression%inputs)
            if (counts_turns(expression%inputs(k)%quantity)) exit
        end do
        if (k > size(expression%inputs)) return
        if (.not. allocated(expression%anchors)) &
            & allocate(expression%anchors(size(expression%inputs)), source=0.0_wp)
        if (restart) expression%anchors = 0.0_wp
        call take_anchors(expression, markers, length_unit, time_unit, q, u)
    end subroutine count_turns

    !> count_turns' anchors set: each AX, AY, AZ input's value at (q, u).
    pure subroutine take_anchors(expression, markers, length_unit, time_unit, q, u)
        type(expression_type), intent(inout) :: expression
        type(marker_type), intent(in) :: markers(:)
        real(wp), intent(in) :: length_unit, time_unit, q(:), u(:)
        real(wp) :: values(size(expression%inputs))
        integer :: k

        call expression_input_values(expression, markers, length_unit, time_unit, q, u, values)
        do k = 1, size(expression%inputs)
            if (counts_turns(expression%inputs(k)%quantity)) expression%anchors(k) = values(k)
        end do
    end subroutine take_anchors

    !> DX(i) ... PHI(i): one marker from ground in ground axes (rollcon_marker's marker_quantity,
    !> which reads a principal CM marker's angles as its part's coordinates).
    elemental logical function one_marker_form(input)
        type(expression_input_type), intent(in) :: input

        one_marker_form = input%quantity <= quantity_psi + 2 .and. input%j == 0 &
            & .and. input%k == 0 .and. input%l == 0
    end function one_marker_form

    !> A measure in SI units [m, m/s, rad, rad/s] of markers i, j, k, l (`markers`; a marker
    !> not given: marker_type(), the ground origin and axes) at (q, u); anchor: the value the
    !> turns of AX, AY, AZ were last counted at [rad].
    pure function measure_value(quantity, markers, q, u, anchor) result(value)
        integer, intent(in) :: quantity
        type(marker_type), intent(in) :: markers(4)
        real(wp), intent(in) :: q(:), u(:), anchor
        real(wp) :: value
        real(wp) :: r(3, 4), v(3, 4), w(3, 4), axes(3, 3, 4), d(3), rate(3), relative(3, 3), &
            & angles(3)
        integer :: m, c

        do m = 1, 4
            call marker_motion(markers(m), q, u, r(:, m), v(:, m), axes(:, :, m), w(:, m))
        end do
        d = r(:, 1) - r(:, 2)
        ! the time derivative of d in l's frame
        rate = v(:, 1) - v(:, 2) - cross(w(:, 4), d)
        c = mod(quantity - 1, 3) + 1
        select case (quantity)
        case (quantity_dx:quantity_dx + 2)
            value = dot_product(d, axes(:, c, 3))
        case (quantity_vx:quantity_vx + 2)
            value = dot_product(rate, axes(:, c, 3))
        case (quantity_wx:quantity_wx + 2)
            value = dot_product(w(:, 1) - w(:, 2), axes(:, c, 3))
        case (quantity_psi:quantity_psi + 2)
            relative = matmul(transpose(axes(:, :, 2)), axes(:, :, 1))
            angles = euler_angles(relative)
            value = angles(quantity - quantity_psi + 1)
        case (quantity_dm)
            value = norm2(d)
        case (quantity_vm)
            value = norm2(rate)
        case (quantity_vr)
            value = dot_product(v(:, 1) - v(:, 2), d)/norm2(d)
        case (quantity_wm)
            value = norm2(w(:, 1) - w(:, 2))
        case (quantity_ax:quantity_ax + 2)
            value = unwrap_angle(axis_angle(quantity - quantity_ax + 1, axes(:, :, 1), &
                & axes(:, :, 2)), anchor)
        case (quantity_yaw:quantity_yaw + 2)
            relative = matmul(transpose(axes(:, :, 2)), axes(:, :, 1))
            select case (quantity - quantity_yaw)
            case (0)
                value = atan2(relative(2, 1), relative(1, 1))
            case (1)
                value = atan2(relative(3, 1), hypot(relative(3, 2), relative(3, 3)))
            case default
                value = atan2(relative(3, 2), relative(3, 3))
            end select
        case default
            value = ieee_value(value, ieee_quiet_nan)
        end select
    end function measure_value

    !> ORIENT(system, component, i, j) of markers(1) (i) and markers(2) (j) at (q, u) (module
    !> header): radians for the angles, no unit for the parameters and cosines; NaN for a
    !> system the function does not take here (25, 26: read as AX ... ROLL) and for the
    !> Rodrigues parameters of a half turn (infinite).
    pure function orient_value(system, component, markers, q, u) result(value)
        integer, intent(in) :: system, component
        type(marker_type), intent(in) :: markers(4)
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: value
        character(len=*), parameter :: sequences(12) = [character(len=3) :: "123", "231", &
            & "312", "132", "213", "321", "121", "131", "212", "232", "313", "323"]
        character(len=:), allocatable :: name
        real(wp) :: r(3), v(3), w(3), axes_i(3, 3), axes_j(3, 3), coord(9)
        integer :: istat

        value = ieee_value(value, ieee_quiet_nan)
        select case (system)
        case (1:12)
            name = "B" // sequences(system)
        case (13:24)
            name = "S" // sequences(system - 12)
        case (27)
            name = "EULPAR"
        case (28)
            name = "RODPAR"
        case (29)
            name = "COSINES"
        case default
            return
        end select
        call marker_motion(markers(1), q, u, r, v, axes_i, w)
        call marker_motion(markers(2), q, u, r, v, axes_j, w)
        call convert_rotation("COSINES", reshape(matmul(transpose(axes_j), axes_i), [9]), &
            & name, coord, istat)
        if (istat == rcnvrt_success .and. component >= 1 .and. component <= 9) &
            & value = coord(component)
    end function orient_value

    !> AX (axis 1), AY (2), AZ (3) of axes a_i in a_j, in (-pi, pi].
    pure real(wp) function axis_angle(axis, a_i, a_j) result(angle)
        integer, intent(in) :: axis
        real(wp), intent(in) :: a_i(3, 3), a_j(3, 3)

        select case (axis)
        case (1)
            angle = atan2(-dot_product(a_i(:, 3), a_j(:, 2)), dot_product(a_i(:, 3), a_j(:, 3)))
        case (2)
            angle = atan2(dot_product(a_i(:, 3), a_j(:, 1)), dot_product(a_i(:, 3), a_j(:, 3)))
        case default
            angle = atan2(dot_product(a_i(:, 1), a_j(:, 2)), dot_product(a_i(:, 1), a_j(:, 1)))
        end select
    end function axis_angle

    !> The jets of `parts` at coordinates q(:, s) and rates u(:, s) of part parts(s): its q(c)
    !> is variable q_variable(c, s) and its rate u_variable(c, s) (0: a constant), of n
    !> variables; second: second partials kept.
    pure function new_state_jets(parts, q, u, q_variable, u_variable, n, second) result(state)
        integer, intent(in) :: parts(:)
        real(wp), intent(in) :: q(:, :), u(:, :)
        integer, intent(in) :: q_variable(:, :), u_variable(:, :), n
        logical, intent(in) :: second
        type(state_jets_type) :: state
        integer :: s, c

        state%parts = parts
        allocate(state%q(6, size(parts)), state%u(6, size(parts)))
        do s = 1, size(parts)
            do c = 1, 6
                if (q_variable(c, s) > 0) then
                    state%q(c, s) = jet_variable(q(c, s), q_variable(c, s), n, second)
                else
                    state%q(c, s) = jet_constant(q(c, s))
                end if
                if (u_variable(c, s) > 0) then
                    state%u(c, s) = jet_variable(u(c, s), u_variable(c, s), n, second)
                else
                    state%u(c, s) = jet_constant(u(c, s))
                end if
            end do
        end do
    end function new_state_jets

    !> The place of model part p among the parts held (0: not held).
    pure integer function part_slot(state, p)
        type(state_jets_type), intent(in) :: state
        integer, intent(in) :: p

        part_slot = 0
        if (p > 0) part_slot = findloc(state%parts, p, dim=1)
    end function part_slot

    !> Position [m], axes (columns), velocity [m/s] and angular velocity [rad/s] of a marker,
    !> ground components, as jets (the jet form of rollcon_marker's marker_motion:
    !> R = Rz(psi) Rx(theta) Rz(phi), w = psidot e_Z + thetadot Rz(psi) e_x + phidot R e_z).
    !> rates false: velocity and angular velocity are left constant zeros.
    pure subroutine marker_jets(marker, state, rates, position, axes, velocity, omega)
        type(marker_type), intent(in) :: marker
        type(state_jets_type), intent(in) :: state
        logical, intent(in) :: rates
        type(jet_type), intent(out) :: position(3), axes(3, 3), velocity(3), omega(3)
        type(jet_type) :: rotation(3, 3), arm(3), cps, sps, cth, sth, cph, sph
        integer :: s, k

        s = part_slot(state, marker%part)
        if (s == 0) then
            position = jet_constant(marker%point)
            axes = jet_constant(marker%axes)
            velocity = jet_constant(0.0_wp)
            omega = jet_constant(0.0_wp)
            return
        end if
        associate (q => state%q(:, s), u => state%u(:, s))
            cps = cos(q(4))
            sps = sin(q(4))
            cth = cos(q(5))
            sth = sin(q(5))
            cph = cos(q(6))
            sph = sin(q(6))
            rotation(1, 1) = cps*cph - sps*cth*sph
            rotation(1, 2) = -(cps*sph) - sps*cth*cph
            rotation(1, 3) = sps*sth
            rotation(2, 1) = sps*cph + cps*cth*sph
            rotation(2, 2) = cps*cth*cph - sps*sph
            rotation(2, 3) = -(cps*sth)
            rotation(3, 1) = sth*sph
            rotation(3, 2) = sth*cph
            rotation(3, 3) = cth
            arm = jet_times(rotation, marker%point)
            position = q(1:3) + arm
            do k = 1, 3
                axes(:, k) = jet_times(rotation, marker%axes(:, k))
            end do
            if (.not. rates) then
                velocity = jet_constant(0.0_wp)
                omega = jet_constant(0.0_wp)
                return
            end if
            omega(1) = u(5)*cps + u(6)*rotation(1, 3)
            omega(2) = u(5)*sps + u(6)*rotation(2, 3)
            omega(3) = u(4) + u(6)*cth
            velocity = u(1:3) + jet_cross(omega, arm)
        end associate
    end subroutine marker_jets

    !> A measure of markers i, j, k, l (as measure_value) as a jet over the state's variables.
    pure function measure_jet(quantity, markers, state, anchor) result(value)
        integer, intent(in) :: quantity
        type(marker_type), intent(in) :: markers(4)
        type(state_jets_type), intent(in) :: state
        real(wp), intent(in) :: anchor
        type(jet_type) :: value
        type(jet_type) :: r(3, 4), v(3, 4), w(3, 4), axes(3, 3, 4), d(3), rate(3), &
            & relative(3, 3)
        logical :: rates
        integer :: m, c, a, b

        rates = reads_rates(quantity)
        do m = 1, 4
            call marker_jets(markers(m), state, rates, r(:, m), axes(:, :, m), v(:, m), w(:, m))
        end do
        d = r(:, 1) - r(:, 2)
        c = mod(quantity - 1, 3) + 1
        select case (quantity)
        case (quantity_dx:quantity_dx + 2)
            value = jet_dot(d, axes(:, c, 3))
        case (quantity_vx:quantity_vx + 2)
            rate = v(:, 1) - v(:, 2) - jet_cross(w(:, 4), d)
            value = jet_dot(rate, axes(:, c, 3))
        case (quantity_wx:quantity_wx + 2)
            value = jet_dot(w(:, 1) - w(:, 2), axes(:, c, 3))
        case (quantity_dm)
            value = jet_norm(d)
        case (quantity_vm)
            rate = v(:, 1) - v(:, 2) - jet_cross(w(:, 4), d)
            value = jet_norm(rate)
        case (quantity_vr)
            value = jet_dot(v(:, 1) - v(:, 2), d)/jet_norm(d)
        case (quantity_wm)
            value = jet_norm(w(:, 1) - w(:, 2))
        case (quantity_ax)
            value = atan2(-jet_dot(axes(:, 3, 1), axes(:, 2, 2)), &
                & jet_dot(axes(:, 3, 1), axes(:, 3, 2)))
            value%v = unwrap_angle(value%v, anchor)
        case (quantity_ax + 1)
            value = atan2(jet_dot(axes(:, 3, 1), axes(:, 1, 2)), &
                & jet_dot(axes(:, 3, 1), axes(:, 3, 2)))
            value%v = unwrap_angle(value%v, anchor)
        case (quantity_ax + 2)
            value = atan2(jet_dot(axes(:, 1, 1), axes(:, 2, 2)), &
                & jet_dot(axes(:, 1, 1), axes(:, 1, 2)))
            value%v = unwrap_angle(value%v, anchor)
        case (quantity_psi:quantity_psi + 2, quantity_yaw:quantity_yaw + 2)
            do b = 1, 3
                do a = 1, 3
                    relative(a, b) = jet_dot(axes(:, a, 2), axes(:, b, 1))
                end do
            end do
            value = relative_angle(quantity, relative)
        case default
            value = jet_constant(ieee_value(1.0_wp, ieee_quiet_nan))
        end select
    end function measure_jet

    !> PSI, THETA, PHI (3-1-3, as rollcon_rotation's euler_angles off its singularity) or YAW,
    !> PITCH, ROLL of a relative rotation matrix of jets.
    pure function relative_angle(quantity, m) result(angle)
        integer, intent(in) :: quantity
        type(jet_type), intent(in) :: m(3, 3)
        type(jet_type) :: angle

        select case (quantity)
        case (quantity_psi)
            angle = atan2(m(1, 3), -m(2, 3))
        case (quantity_psi + 1)
            angle = atan2(sqrt(m(1, 3)*m(1, 3) + m(2, 3)*m(2, 3)), m(3, 3))
        case (quantity_psi + 2)
            angle = atan2(m(3, 1), m(3, 2))
        case (quantity_yaw)
            angle = atan2(m(2, 1), m(1, 1))
        case (quantity_yaw + 1)
            angle = atan2(m(3, 1), sqrt(m(3, 2)*m(3, 2) + m(3, 3)*m(3, 3)))
        case default
            angle = atan2(m(3, 2), m(3, 3))
        end select
    end function relative_angle

    !> The jets of an expression's inputs over the state's variables, in the dataset's units (as
    !> expression_input_values gives their values).
    pure subroutine expression_input_jets(expression, markers, length_unit, time_unit, state, &
            & values)
        type(expression_type), intent(in) :: expression
        type(marker_type), intent(in) :: markers(:)
        real(wp), intent(in) :: length_unit, time_unit
        type(state_jets_type), intent(in) :: state
        type(jet_type), intent(out) :: values(:)
        type(marker_type) :: chosen(4)
        logical :: found(4)
        real(wp) :: anchor
        integer :: k, s

        do k = 1, size(values)
            associate (input => expression%inputs(k))
                ! a user VARIABLE's value, with the partials its VARSUB's differences gave
                ! where a Newton matrix is formed (docs/datasets.md, "User routines of
                ! variables"), else a constant
                if (input%quantity == quantity_varval) then
                    values(k) = user_variable_jet(input%marker, state%parts, state%q, state%u)
                    cycle
                end if
                call input_markers(input, markers, chosen, found)
                if (.not. all(found) .or. .not. is_state_measure(input%quantity)) then
                    values(k) = jet_constant(ieee_value(1.0_wp, ieee_quiet_nan))
                    cycle
                end if
                ! a principal CM marker's PSI, THETA, PHI(i) are its part's own coordinates
                ! (as marker_quantity reads them)
                s = part_slot(state, chosen(1)%part)
                if (one_marker_form(input) .and. input%quantity >= quantity_psi .and. &
                    & chosen(1)%principal .and. s > 0) then
                    values(k) = state%q(4 + input%quantity - quantity_psi, s)
                    cycle
                end if
                anchor = 0.0_wp
                if (allocated(expression%anchors)) anchor = expression%anchors(k)
                values(k) = quantity_scale(input%quantity, length_unit, time_unit) &
                    & *measure_jet(input%quantity, chosen, state, anchor)
            end associate
        end do
    end subroutine expression_input_jets

end module rollcon_measures
