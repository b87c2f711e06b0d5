! SPDX-License-Identifier: MIT
!> The column layout of a run's output rows (CSV and history): the one place that says which
!> quantity sits in which column and what the column is called. Writers and readers ask it.
!>
!> A row holds, in order:
!> - `t` [s];
!> - for every part, in model order, its 12 coordinates and rates named with the part id,
!>   `X_<id> Y_<id> Z_<id> psi_<id> theta_<id> phi_<id>` [m, rad] and
!>   `Xdot_<id> ... phidot_<id>` [m/s, rad/s] (ADAMS coordinates: centre of mass and body-fixed
!>   3-1-3 Euler angles of the principal axes);
!> - `E`, the total energy [J] (kinetic plus gravitational potential);
!> - for every UCON, in model order, its residual `F_<id>` (the UCON's own unit) ...
!> - ... then its Lagrange multiplier `lambda_<id>` (power or work per unit of F, its
!>   generalised force being lambda dF/dqdot or lambda dF/dq: N for a UCON in m/s or m, N m
!>   for one in rad/s or rad);
!> - the columns the run's watches add, in the order of the watches (rollcon_watch): a part's
!>   principal basis `basis_<id>` when parts may be re-based (rollcon_theta_watch), a rim
!>   contact's force, friction and height residual (rollcon_contact_watch), a dataset's
!>   displacement requests `req<id>_x` ... `req<id>_phi` (rollcon_request_watch), ... Each watch
!>   names its own columns; readers find them by name (`column`).
!> With one part, the part's coordinates are columns 2 to 13 and the energy column 14, whatever
!> its id.
module rollcon_output_layout
    use rollcon_text, only : to_text
    implicit none
    private

    public :: output_layout_type, new_output_layout, read_layout
    public :: coordinate_names, name_length

    !> Length of a column name
    integer, parameter :: name_length = 32
    !> The 12 quantities of a part, in column order (the part id is appended: X_1)
    character(len=*), parameter :: coordinate_names(12) = [character(len=8) :: "X", "Y", "Z", &
        & "psi", "theta", "phi", "Xdot", "Ydot", "Zdot", "psidot", "thetadot", "phidot"]
    !> Column of the time, in every layout
    integer, parameter, public :: time_column = 1
    !> Coordinates of a part, numbered as in coordinate_names
    integer, parameter, public :: coord_x = 1, coord_y = 2, coord_z = 3, coord_psi = 4, &
        & coord_theta = 5, coord_phi = 6, coord_xdot = 7, coord_ydot = 8, coord_zdot = 9, &
        & coord_psidot = 10, coord_thetadot = 11, coord_phidot = 12

    !> Which parts and UCONs a row describes, and the names of the columns its watches add
    type :: output_layout_type
        !> Part ids, in model order
        integer, allocatable :: part_ids(:)
        !> UCON ids, in model order
        integer, allocatable :: ucon_ids(:)
        !> Names of the columns after the multipliers, in order (the watches')
        character(len=name_length), allocatable :: extra(:)
    contains
        procedure :: columns
        procedure :: part_column
        procedure :: energy_column
        procedure :: residual_column
        procedure :: multiplier_column
        procedure :: column
        procedure :: column_name
        procedure :: header
        procedure :: part_index
    end type output_layout_type

contains

    !> The layout of a model's rows.
    pure function new_output_layout(part_ids, ucon_ids, extra) result(layout)
        !> Part ids and UCON ids, in model order
        integer, intent(in) :: part_ids(:), ucon_ids(:)
        !> Names of the columns after the multipliers (none when absent)
        character(len=*), intent(in), optional :: extra(:)
        type(output_layout_type) :: layout

        layout%part_ids = part_ids
        layout%ucon_ids = ucon_ids
        allocate(layout%extra(0))
        if (present(extra)) then
            deallocate(layout%extra)
            allocate(layout%extra(size(extra)))
            layout%extra(:) = extra
        end if
    end function new_output_layout

    !> Number of columns.
    pure integer function columns(self)
        class(output_layout_type), intent(in) :: self

        columns = 2 + 12*size(self%part_ids) + 2*size(self%ucon_ids)
        if (allocated(self%extra)) columns = columns + size(self%extra)
    end function columns

    !> Column of quantity c (coord_x ... coord_phidot) of the p-th part (model order).
    pure integer function part_column(self, p, c)
        class(output_layout_type), intent(in) :: self
        integer, intent(in) :: p, c

        part_column = 1 + 12*(p - 1) + c
    end function part_column

    !> Column of the energy.
    pure integer function energy_column(self)
        class(output_layout_type), intent(in) :: self

        energy_column = 2 + 12*size(self%part_ids)
    end function energy_column

    !> Column of the k-th UCON's residual (model order).
    pure integer function residual_column(self, k)
        class(output_layout_type), intent(in) :: self
        integer, intent(in) :: k

        residual_column = self%energy_column() + k
    end function residual_column

    !> Column of the k-th UCON's multiplier (model order).
    pure integer function multiplier_column(self, k)
        class(output_layout_type), intent(in) :: self
        integer, intent(in) :: k

        multiplier_column = self%energy_column() + size(self%ucon_ids) + k
    end function multiplier_column

    !> Column of the quantity called name: a part's coordinate (X_2), t, E, F_<id>,
    !> lambda_<id> or a watch's column (Fn, basis_2); 0 when the rows have no such column.
    pure integer function column(self, name)
        class(output_layout_type), intent(in) :: self
        character(len=*), intent(in) :: name

        do column = 1, self%columns()
            if (self%column_name(column) == name) return
        end do
        column = 0
    end function column

    !> The name of column j.
    pure function column_name(self, j) result(name)
        class(output_layout_type), intent(in) :: self
        integer, intent(in) :: j
        character(len=name_length) :: name
        integer :: p, c, k

        if (j == 1) then
            name = "t"
        else if (j < self%energy_column()) then
            p = (j - 2)/12 + 1
            c = j - self%part_column(p, 1) + 1
            name = trim(coordinate_names(c)) // "_" // to_text(self%part_ids(p))
        else if (j == self%energy_column()) then
            name = "E"
        else if (j <= self%energy_column() + size(self%ucon_ids)) then
            k = j - self%energy_column()
            name = "F_" // to_text(self%ucon_ids(k))
        else if (j <= self%energy_column() + 2*size(self%ucon_ids)) then
            k = j - self%energy_column() - size(self%ucon_ids)
            name = "lambda_" // to_text(self%ucon_ids(k))
        else
            name = self%extra(j - self%energy_column() - 2*size(self%ucon_ids))
        end if
    end function column_name

    !> Index (model order) of the part with this id; 0 when there is none.
    pure integer function part_index(self, id)
        class(output_layout_type), intent(in) :: self
        integer, intent(in) :: id
        integer :: p

        part_index = 0
        do p = 1, size(self%part_ids)
            if (self%part_ids(p) == id) then
                part_index = p
                return
            end if
        end do
    end function part_index

    !> The column names, in order.
    pure function header(self) result(names)
        class(output_layout_type), intent(in) :: self
        character(len=name_length), allocatable :: names(:)
        integer :: j

        allocate(names(self%columns()))
        do j = 1, size(names)
            names(j) = self%column_name(j)
        end do
    end function header

    !> The layout a header describes; message is allocated, saying what was expected at which
    !> column, when the names are not a header this module writes. With known, each column after
    !> the multipliers must be one of its names, where a name ending in "<id>" stands for that
    !> prefix with the id of any of the header's parts ("basis_<id>"), and "<n>" in a name for
    !> any whole number ("req<n>_x").
    pure subroutine read_layout(names, layout, message, known)
        !> Column names, as read
        character(len=*), intent(in) :: names(:)
        type(output_layout_type), intent(out) :: layout
        character(len=:), allocatable, intent(out) :: message
        !> The watches' columns a reader knows (default: any names)
        character(len=*), intent(in), optional :: known(:)
        integer :: nparts, nucons, column, first_f, p, k, id, extra
        integer, allocatable :: part_ids(:), ucon_ids(:)

        if (size(names) < 1) then
            message = "expected a header starting with t, found no column"
            return
        end if
        if (names(1) /= "t") then
            message = "column 1 must be t, got '" // trim(names(1)) // "'"
            return
        end if
        nparts = 0
        do while (1 + 12*nparts + 1 <= size(names))
            if (names(2 + 12*nparts) == "E") exit
            nparts = nparts + 1
        end do
        if (nparts == 0 .or. 2 + 12*nparts > size(names)) then
            message = "expected groups of 12 part columns (X_<id> ... phidot_<id>) after t, " &
                & // "then E"
            return
        end if
        allocate(part_ids(nparts))
        do p = 1, nparts
            call suffix_id(names(2 + 12*(p - 1)), "X_", id)
            if (id < 0) then
                message = "column " // to_text(2 + 12*(p - 1)) // " must be X_<part id>, got '" &
                    & // trim(names(2 + 12*(p - 1))) // "'"
                return
            end if
            part_ids(p) = id
        end do
        first_f = 3 + 12*nparts
        nucons = 0
        do column = first_f, size(names)
            if (index(names(column), "F_") /= 1) exit
            nucons = nucons + 1
        end do
        allocate(ucon_ids(nucons))
        do k = 1, nucons
            call suffix_id(names(first_f + k - 1), "F_", ucon_ids(k))
            if (ucon_ids(k) < 0) then
                message = "column " // to_text(first_f + k - 1) // " must be F_<UCON id>, got '" &
                    & // trim(names(first_f + k - 1)) // "'"
                return
            end if
        end do
        extra = size(names) - (first_f - 1 + 2*nucons)
        if (extra < 0) then
            message = "expected " // to_text(first_f - 1 + 2*nucons) // " columns for " &
                & // counted(nparts, "part") // " and " // counted(nucons, "UCON") &
                & // " (a residual and a multiplier each), got " // to_text(size(names))
            return
        end if
        call check_extra(names, size(names) - extra + 1, part_ids, message, known)
        if (allocated(message)) return
        layout = new_output_layout(part_ids, ucon_ids, names(size(names) - extra + 1:))
        names_match: block
            character(len=name_length), allocatable :: expected(:)

            expected = layout%header()
            do column = 1, size(names)
                if (names(column) /= expected(column)) then
                    message = "column " // to_text(column) // " must be " &
                        & // trim(expected(column)) // ", got '" // trim(names(column)) // "'"
                    return
                end if
            end do
        end block names_match
    end subroutine read_layout

    !> The watches' columns, names(first:): each name once, and one of known when given.
    pure subroutine check_extra(names, first, part_ids, message, known)
        character(len=*), intent(in) :: names(:)
        integer, intent(in) :: first, part_ids(:)
        character(len=:), allocatable, intent(out) :: message
        character(len=*), intent(in), optional :: known(:)
        integer :: column

        do column = first, size(names)
            if (len_trim(names(column)) == 0 .or. &
                & findloc(names(:column - 1), names(column), dim=1) > 0) then
                message = "column " // to_text(column) // " must have a name of its own, got '" &
                    & // trim(names(column)) // "'"
                return
            end if
            if (.not. present(known)) cycle
            if (is_known(names(column), known, part_ids)) cycle
            message = "column " // to_text(column) // " must be one of " &
                & // known_list(known) // ", got '" // trim(names(column)) // "'"
            return
        end do
    end subroutine check_extra

    !> name is one of known, "<id>" at the end of one standing for any of the part ids, "<n>"
    !> anywhere in one for any whole number of 1 to 9 digits (a request's id).
    pure logical function is_known(name, known, part_ids)
        character(len=*), intent(in) :: name, known(:)
        integer, intent(in) :: part_ids(:)
        integer :: k, p, cut, tail, digits

        is_known = .true.
        do k = 1, size(known)
            if (name == known(k)) return
            cut = index(known(k), "<n>")
            if (cut > 0) then
                tail = len_trim(known(k)) - cut - 2
                digits = len_trim(name) - (cut - 1) - tail
                if (digits < 1 .or. digits > 9) cycle
                if (name(:cut - 1) /= known(k)(:cut - 1)) cycle
                if (verify(name(cut:cut + digits - 1), "0123456789") /= 0) cycle
                if (name(cut + digits:len_trim(name)) == known(k)(cut + 3:len_trim(known(k)))) &
                    & return
                cycle
            end if
            cut = index(known(k), "<id>")
            if (cut == 0) cycle
            do p = 1, size(part_ids)
                if (name == known(k)(:cut - 1) // to_text(part_ids(p))) return
            end do
        end do
        is_known = .false.
    end function is_known

    !> "Fx, Fy, ..., basis_<id>".
    pure function known_list(known) result(text)
        character(len=*), intent(in) :: known(:)
        character(len=:), allocatable :: text
        integer :: k

        text = ""
        do k = 1, size(known)
            if (k > 1) text = text // ", "
            text = text // trim(known(k))
        end do
    end function known_list

    !> "1 part", "2 parts".
    pure function counted(count, noun) result(text)
        integer, intent(in) :: count
        character(len=*), intent(in) :: noun
        character(len=:), allocatable :: text

        text = to_text(count) // " " // noun
        if (count /= 1) text = text // "s"
    end function counted

    !> The whole number after prefix in name (prefix "X_", name "X_12": 12); -1 when name is not
    !> prefix followed by digits.
    pure subroutine suffix_id(name, prefix, id)
        character(len=*), intent(in) :: name, prefix
        integer, intent(out) :: id
        integer :: i, last

        id = -1
        last = len_trim(name)
        if (last <= len(prefix) .or. last > len(prefix) + 9) return
        if (name(:len(prefix)) /= prefix) return
        do i = len(prefix) + 1, last
            if (verify(name(i:i), "0123456789") /= 0) return
        end do
        read(name(len(prefix) + 1:last), *) id
    end subroutine suffix_id

end module rollcon_output_layout
