! SPDX-License-Identifier: MIT
!> What each part of a run looks like in the pictures: a disk (radius, thickness) or the uniform
!> solid ellipsoid with the part's mass and principal moments; and the small text file,
!> DIR/NAME.parts beside DIR/NAME.csv, that carries these shapes from a run to its pictures.
!>
!> The file (lengths in metres; `#` starts a comment line; one line per part, in model order):
!>
!>     part <id> disk <radius> <thickness>
!>     part <id> ellipsoid <a> <b> <c>        semi-axes along the body x, y, z axes
module rollcon_part_shapes
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, input_error, stat_input, stat_io
    use rollcon_text, only : to_text
    use rollcon_model, only : model_type
    use rollcon_rebasing, only : own_axes_inertia
    use rollcon_output_files, only : close_checked
    use rollcon_input_files, only : input_file_type, text_input_limit
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use, intrinsic :: ieee_exceptions, only : ieee_set_flag, ieee_overflow, ieee_underflow
    implicit none
    private

    public :: part_shape_type, part_shapes_of, ellipsoid_semi_axes, write_part_shapes, &
        & read_part_shapes, parts_path, write_model_shapes, shape_extent

    !> Kinds of shape
    integer, parameter, public :: shape_disk = 1, shape_ellipsoid = 2
    !> Largest length a shape may have [m]: as the CSV reader's largest value, so that the
    !> meshes' arithmetic cannot overflow
    real(wp), parameter, public :: largest_length = 1.0e100_wp
    !> What a line of a .parts file must be
    character(len=*), parameter :: line_forms = "expected 'part <id> disk <radius> " &
        & // "<thickness>' or 'part <id> ellipsoid <a> <b> <c>' (lengths in m)"
    !> Round-off allowed in the triangle inequalities of the principal moments, relative to
    !> their sum: a thin disk's I1 + I2 - I3 is a few roundings away from zero
    real(wp), parameter :: inertia_round_off = 8.0_wp*epsilon(1.0_wp)

    !> The shape of one part
    type :: part_shape_type
        !> Part id
        integer :: id = 0
        !> shape_disk or shape_ellipsoid
        integer :: kind = shape_ellipsoid
        !> Disk: radius and thickness [m] (the disk axis is body z)
        real(wp) :: radius = 0.0_wp, thickness = 0.0_wp
        !> Ellipsoid: semi-axes along the body x, y, z axes [m]
        real(wp) :: semi_axes(3) = 0.0_wp
    end type part_shape_type

contains

    !> The shapes of a model's parts, in model order: the uniform solid ellipsoid of each part's
    !> mass and principal moments (ellipsoid_semi_axes) about its own axes (its CM marker's),
    !> except the disk of a disk scene and a part that rolls as a disk (wheel_shape).
    subroutine part_shapes_of(model, shapes, error, disk_radius, disk_thickness, disk_part, &
        & bases)
        type(model_type), intent(in) :: model
        type(part_shape_type), allocatable, intent(out) :: shapes(:)
        type(error_type), allocatable, intent(out) :: error
        !> Radius and thickness of the disk [m] (the disk scenes)
        real(wp), intent(in), optional :: disk_radius, disk_thickness
        !> Which part (model order) is the disk; default 1
        integer, intent(in), optional :: disk_part
        !> The basis each part of the model is in (problem%start_bases; default: its own axes):
        !> the semi-axes are given along the part's own axes all the same
        integer, intent(in), optional :: bases(:)
        character(len=:), allocatable :: message
        integer :: p, disk, basis

        disk = 0
        if (present(disk_radius)) disk = 1
        if (present(disk_radius) .and. present(disk_part)) disk = disk_part
        if (allocated(model%parts)) then
            allocate(shapes(size(model%parts)))
        else
            allocate(shapes(0))
        end if
        do p = 1, size(shapes)
            shapes(p)%id = model%parts(p)%id
            if (p == disk) then
                shapes(p)%kind = shape_disk
                shapes(p)%radius = disk_radius
                if (present(disk_thickness)) shapes(p)%thickness = disk_thickness
                cycle
            end if
            basis = 0
            if (present(bases)) basis = bases(p)
            if (disk == 0 .and. wheel_shape(model, p, shapes(p))) cycle
            call ellipsoid_semi_axes(model%parts(p)%mass, &
                & own_axes_inertia(model%parts(p)%inertia, basis), shapes(p)%semi_axes, message)
            if (allocated(message)) then
                call fatal_error(error, "part " // to_text(model%parts(p)%id) // ": " &
                    & // message, stat_input)
                return
            end if
        end do
    end subroutine part_shapes_of

    !> A part that a disk routine holds on the ground (a UCON that names rolling_disk,
    !> disk_height or the hand-checked disk as its ROUTINE, whose PAR holds the radius R after
    !> the codes, in the model's length unit; a UCON served by the model's UCOSUB may be any) is
    !> drawn as a disk of that radius about its body z axis (the
    !> routines' axle): its thickness that of a uniform disk with the part's mass and moment A
    !> about a diameter, h^2 = 12 A/m - 3 R^2, at most R/10 (a wheel's moments are a rim's,
    !> not a uniform disk's) and 0 when the moments give none.
    logical function wheel_shape(model, p, shape)
        type(model_type), intent(in) :: model
        !> The part's number (model order)
        integer, intent(in) :: p
        type(part_shape_type), intent(inout) :: shape
        real(wp) :: radius, square
        integer :: k

        wheel_shape = .false.
        if (.not. allocated(model%ucons)) return
        do k = 1, size(model%ucons)
            associate (ucon => model%ucons(k))
                if (.not. allocated(ucon%routine) .or. .not. allocated(ucon%par)) cycle
                if (ucon%routine /= "rolling_disk" .and. ucon%routine /= "disk_height" &
                    & .and. ucon%routine /= "disk") cycle
                if (size(ucon%par) < ucon%nvars + 2) cycle
                if (nint(ucon%par(1)) /= model%parts(p)%id) cycle
                radius = ucon%par(ucon%nvars + 2)*model%ucosub_units%length
                if (.not. (radius > 0.0_wp .and. radius <= largest_length)) cycle
                shape%kind = shape_disk
                shape%radius = radius
                square = 0.0_wp
                if (model%parts(p)%mass > 0.0_wp) square = 12.0_wp*model%parts(p)%inertia(1) &
                    & /model%parts(p)%mass - 3.0_wp*radius**2
                shape%thickness = min(sqrt(max(square, 0.0_wp)), 0.1_wp*radius)
                wheel_shape = .true.
                return
            end associate
        end do
    end function wheel_shape

    !> Semi-axes of the uniform solid ellipsoid with this mass and these principal moments:
    !> I1 = m (b^2 + c^2)/5 and so on, hence a^2 = 5 (I2 + I3 - I1)/(2 m), b^2 = 5 (I1 + I3 - I2)
    !> /(2 m), c^2 = 5 (I1 + I2 - I3)/(2 m). message is allocated, and axes zero, when the mass
    !> is not positive or the moments are not a rigid body's (each positive, each at most the
    !> sum of the other two).
    pure subroutine ellipsoid_semi_axes(mass, inertia, axes, message)
        !> Mass [kg]
        real(wp), intent(in) :: mass
        !> Principal moments about the body x, y, z axes [kg m^2]
        real(wp), intent(in) :: inertia(3)
        !> Semi-axes a, b, c along the body x, y, z axes [m]
        real(wp), intent(out) :: axes(3)
        character(len=:), allocatable, intent(out) :: message
        real(wp) :: excess(3)
        integer :: i

        axes = 0.0_wp
        if (.not. (ieee_is_finite(mass) .and. mass > 0.0_wp)) then
            message = "the mass must be a positive number of kg, got " // to_text(mass)
            return
        end if
        if (.not. all(ieee_is_finite(inertia) .and. inertia > 0.0_wp)) then
            message = "the principal moments must be positive [kg m^2], got " // moments(inertia)
            return
        end if
        excess = sum(inertia) - 2.0_wp*inertia
        do i = 1, 3
            if (excess(i) < -inertia_round_off*sum(inertia)) then
                message = "the principal moments " // moments(inertia) // " kg m^2 are not " &
                    & // "those of a rigid body: I" // to_text(i) // " = " &
                    & // to_text(inertia(i)) // " exceeds the sum of the other two"
                return
            end if
        end do
        axes = sqrt(5.0_wp*max(excess, 0.0_wp)/(2.0_wp*mass))
    contains
        pure function moments(values) result(text)
            real(wp), intent(in) :: values(3)
            character(len=:), allocatable :: text

            text = "(" // to_text(values(1)) // ", " // to_text(values(2)) // ", " &
                & // to_text(values(3)) // ")"
        end function moments
    end subroutine ellipsoid_semi_axes

    !> The .parts file of a CSV: DIR/NAME.csv gives DIR/NAME.parts.
    pure function parts_path(csv_path) result(path)
        character(len=*), intent(in) :: csv_path
        character(len=:), allocatable :: path

        path = csv_path // ".parts"
        if (len(csv_path) >= 4) then
            if (csv_path(len(csv_path) - 3:) == ".csv") path = csv_path(:len(csv_path) - 4) &
                & // ".parts"
        end if
    end function parts_path

    !> The one call a run makes: the shapes of model's parts (part_shapes_of) written beside its
    !> CSV, as parts_path(csv_path).
    subroutine write_model_shapes(csv_path, model, error, disk_radius, disk_thickness, disk_part)
        !> The run's CSV (its final name)
        character(len=*), intent(in) :: csv_path
        type(model_type), intent(in) :: model
        type(error_type), allocatable, intent(out) :: error
        !> Radius and thickness of the disk [m] (the disk scenes)
        real(wp), intent(in), optional :: disk_radius, disk_thickness
        !> Which part (model order) is the disk; default 1
        integer, intent(in), optional :: disk_part
        type(part_shape_type), allocatable :: shapes(:)

        call part_shapes_of(model, shapes, error, disk_radius, disk_thickness, disk_part)
        if (allocated(error)) return
        call write_part_shapes(parts_path(csv_path), shapes, error)
    end subroutine write_model_shapes

    !> Write a .parts file (format in this module's header).
    subroutine write_part_shapes(path, shapes, error, record)
        character(len=*), intent(in) :: path
        type(part_shape_type), intent(in) :: shapes(:)
        type(error_type), allocatable, intent(out) :: error
        !> Lines (each ending in a newline) written as comments after the header: the run's
        !> provenance
        character(len=*), intent(in), optional :: record
        character(len=256) :: message
        integer :: unit, stat, p, first, last

        message = "a write failed"
        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="formatted", iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot write the part shapes: " // trim(message), &
                & stat_io)
            return
        end if
        write(unit, '(a)', iostat=stat) "# rollcon part shapes: one line per " &
            & // "part, in model order; lengths in metres.", "#   part <id> disk <radius> " &
            & // "<thickness>", "#   part <id> ellipsoid <a> <b> <c>   (semi-axes along the " &
            & // "body x, y, z axes: the uniform solid ellipsoid of the part's inertia)"
        if (present(record)) then
            first = 1
            do while (first <= len(record) .and. stat == 0)
                last = index(record(first:), new_line("a"))
                if (last == 0) last = len(record) - first + 2
                write(unit, '(a)', iostat=stat) "# " // record(first:first + last - 2)
                first = first + last
            end do
        end if
        do p = 1, size(shapes)
            if (stat /= 0) exit
            if (shapes(p)%kind == shape_disk) then
                write(unit, '(a, i0, a, 2(1x, es24.16e3))', iostat=stat) "part ", &
                    & shapes(p)%id, " disk", shapes(p)%radius, shapes(p)%thickness
            else
                write(unit, '(a, i0, a, 3(1x, es24.16e3))', iostat=stat) "part ", &
                    & shapes(p)%id, " ellipsoid", shapes(p)%semi_axes
            end if
        end do
        call close_checked(unit, path, error)
        if (allocated(error)) return
        if (stat /= 0) call fatal_error(error, path // ": cannot write the part shapes: " &
            & // trim(message), stat_io)
    end subroutine write_part_shapes

    !> Read a .parts file: every line a comment, blank, or a part's shape; ids unique, lengths
    !> finite, positive (a thickness or one semi-axis may be zero) and at most largest_length.
    subroutine read_part_shapes(path, shapes, error)
        character(len=*), intent(in) :: path
        type(part_shape_type), allocatable, intent(out) :: shapes(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: line
        integer, allocatable :: lines(:)
        type(part_shape_type) :: shape
        type(input_file_type) :: file
        integer :: number, p
        logical :: done

        allocate(shapes(0), lines(0))
        ! a regular file of at most text_input_limit bytes (rollcon_input_files)
        call file%open(path, "part shapes file", text_input_limit, error)
        if (allocated(error)) return
        number = 0
        do
            call file%next_line(line, done, error)
            if (done .or. allocated(error)) exit
            number = number + 1
            line = adjustl(line)
            if (len_trim(line) == 0) cycle
            if (line(1:1) == "#") cycle
            call parse_shape(path, number, trim(line), shape, error)
            if (allocated(error)) exit
            do p = 1, size(shapes)
                if (shapes(p)%id /= shape%id) cycle
                call input_error(error, path, number, "", "part " // to_text(shape%id) &
                    & // " is described twice (first on line " // to_text(lines(p)) // ")")
                exit
            end do
            if (allocated(error)) exit
            shapes = [shapes, shape]
            lines = [lines, number]
        end do
        call file%close()
        if (.not. allocated(error) .and. size(shapes) == 0) call input_error(error, path, 0, "", &
            & "describes no part: " // line_forms)
    end subroutine read_part_shapes

    !> One part line of a .parts file.
    subroutine parse_shape(path, number, line, shape, error)
        character(len=*), intent(in) :: path, line
        integer, intent(in) :: number
        type(part_shape_type), intent(out) :: shape
        type(error_type), allocatable, intent(out) :: error
        character(len=len(line)) :: words(7)
        real(wp) :: values(3)
        integer :: nwords, needed, i, stat
        character(len=*), parameter :: disk_names(2) = [character(len=9) :: "radius", &
            & "thickness"], axis_names(3) = [character(len=9) :: "a", "b", "c"]

        call split_words(line, words, nwords)
        needed = 0
        if (nwords >= 3) then
            if (words(3) == "disk") needed = 5
            if (words(3) == "ellipsoid") needed = 6
        end if
        stat = 1
        if (nwords == needed .and. words(1) == "part" .and. &
            & verify(trim(words(2)), "0123456789") == 0 .and. len_trim(words(2)) <= 9) &
            & read(words(2), *, iostat=stat) shape%id
        if (stat /= 0) then
            call input_error(error, path, number, "", line_forms // ", got '" // line // "'")
            return
        end if
        do i = 4, nwords
            call read_length(words(i), values(i - 3), stat)
            if (stat /= 0) then
                if (needed == 5) call input_error(error, path, number, trim(disk_names(i - 3)), &
                    & "must be a length >= 0 and at most " // to_text(largest_length) &
                    & // " [m], got '" // trim(words(i)) // "'")
                if (needed == 6) call input_error(error, path, number, trim(axis_names(i - 3)), &
                    & "must be a length >= 0 and at most " // to_text(largest_length) &
                    & // " [m], got '" // trim(words(i)) // "'")
                return
            end if
        end do
        if (needed == 5) then
            shape%kind = shape_disk
            shape%radius = values(1)
            shape%thickness = values(2)
            if (.not. shape%radius > 0.0_wp) call input_error(error, path, number, "radius", &
                & "must be > 0 [m], got 0")
        else
            shape%kind = shape_ellipsoid
            shape%semi_axes = values
            if (count([values == 0.0_wp]) > 1) call input_error(error, path, number, "", &
                & "an ellipsoid may have at most one zero semi-axis (a flat one), got '" &
                & // line // "'")
        end if
    end subroutine parse_shape

    !> A length >= 0, finite and at most largest_length, read strictly (stat /= 0 otherwise).
    subroutine read_length(word, value, stat)
        character(len=*), intent(in) :: word
        real(wp), intent(out) :: value
        integer, intent(out) :: stat

        value = 0.0_wp
        stat = 1
        ! List-directed input would also take '/', '3*1.0' and ',': refuse them.
        if (scan(trim(word), "/*,;") /= 0) return
        read(word, *, iostat=stat) value
        ! Reading 1e999 or 1e-999 raises overflow or underflow: the value is refused or read
        ! as it is, so quiet the flags.
        call ieee_set_flag([ieee_overflow, ieee_underflow], .false.)
        if (stat /= 0) return
        if (.not. (ieee_is_finite(value) .and. value >= 0.0_wp .and. value <= largest_length)) &
            & stat = 1
    end subroutine read_length

    !> The blank-separated words of a line (at most size(words); count may exceed it).
    pure subroutine split_words(line, words, count)
        character(len=*), intent(in) :: line
        character(len=*), intent(out) :: words(:)
        integer, intent(out) :: count
        integer :: i, start

        words = ""
        count = 0
        start = 0
        do i = 1, len(line) + 1
            if (i <= len(line)) then
                if (line(i:i) /= " " .and. line(i:i) /= achar(9)) then
                    if (start == 0) start = i
                    cycle
                end if
            end if
            if (start == 0) cycle
            count = count + 1
            if (count <= size(words)) words(count) = line(start:i - 1)
            start = 0
        end do
    end subroutine split_words

    !> Half the largest size of a shape [m]: its radius, or its largest semi-axis.
    elemental function shape_extent(shape) result(extent)
        type(part_shape_type), intent(in) :: shape
        real(wp) :: extent

        if (shape%kind == shape_disk) then
            extent = max(shape%radius, 0.5_wp*shape%thickness)
        else
            extent = maxval(shape%semi_axes)
        end if
    end function shape_extent

end module rollcon_part_shapes
