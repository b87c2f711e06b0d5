! SPDX-License-Identifier: MIT
!> The output rows of a run kept in memory (the CSV's rows, as a run fills them or as the
!> pictures read them back), with their column layout (rollcon_output_layout). A value of its
!> own, apart from the run that fills it: a program reading a CSV needs nothing of the
!> mechanics.
module rollcon_history
    use rollcon_kinds, only : wp
    use rollcon_output_layout, only : output_layout_type
    implicit none
    private

    public :: history_type

    !> The output rows kept in memory, for programs, tests and benchmarks
    type :: history_type
        !> What the columns hold (set by the run that fills the rows)
        type(output_layout_type) :: layout
        !> rows(:, i) is output row i; only the first count rows are filled
        real(wp), allocatable :: rows(:, :)
        integer :: count = 0
    contains
        procedure :: add => history_add
        procedure :: column => history_column
        procedure :: part_values => history_part_values
        procedure :: part_state => history_part_state
    end type history_type

contains

    !> Append a row, growing the storage geometrically.
    pure subroutine history_add(self, row)
        class(history_type), intent(inout) :: self
        real(wp), intent(in) :: row(:)
        real(wp), allocatable :: grown(:, :)

        if (.not. allocated(self%rows)) allocate(self%rows(size(row), 256))
        if (self%count == size(self%rows, 2)) then
            allocate(grown(size(row), 2*self%count))
            grown(:, :self%count) = self%rows(:, :self%count)
            call move_alloc(grown, self%rows)
        end if
        self%count = self%count + 1
        self%rows(:, self%count) = row
    end subroutine history_add

    !> Column j over the filled rows.
    pure function history_column(self, j) result(values)
        class(history_type), intent(in) :: self
        integer, intent(in) :: j
        real(wp), allocatable :: values(:)

        values = self%rows(j, :self%count)
    end function history_column

    !> Quantity c (coord_x ... coord_phidot) of the p-th part (model order) over the filled
    !> rows.
    pure function history_part_values(self, p, c) result(values)
        class(history_type), intent(in) :: self
        integer, intent(in) :: p, c
        real(wp), allocatable :: values(:)

        values = self%rows(self%layout%part_column(p, c), :self%count)
    end function history_part_values

    !> The 12 coordinates and rates (X ... phi, Xdot ... phidot) of the p-th part (model order)
    !> in row i.
    pure function history_part_state(self, p, i) result(state)
        class(history_type), intent(in) :: self
        integer, intent(in) :: p, i
        real(wp) :: state(12)

        state = self%rows(self%layout%part_column(p, 1):self%layout%part_column(p, 12), i)
    end function history_part_state

end module rollcon_history
