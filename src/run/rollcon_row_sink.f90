! SPDX-License-Identifier: MIT
!> Where a run's output rows go besides its CSV and its history: a sink told the layout once,
!> then handed each row as it is made (the rows of a run in a child process go to its parent
!> this way: rollcon_isolated_run).
module rollcon_row_sink
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_output_layout, only : output_layout_type
    implicit none
    private

    public :: row_sink_type

    type, abstract :: row_sink_type
    contains
        procedure(open_interface), deferred :: open
        procedure(put_interface), deferred :: put
        procedure :: between_chunks
    end type row_sink_type

    abstract interface
        !> The rows to come have this layout.
        subroutine open_interface(self, layout, error)
            import :: row_sink_type, output_layout_type, error_type
            class(row_sink_type), intent(inout) :: self
            type(output_layout_type), intent(in) :: layout
            type(error_type), allocatable, intent(out) :: error
        end subroutine open_interface

        !> One row, in the layout's columns.
        subroutine put_interface(self, row, error)
            import :: row_sink_type, wp, error_type
            class(row_sink_type), intent(inout) :: self
            real(wp), intent(in) :: row(:)
            type(error_type), allocatable, intent(out) :: error
        end subroutine put_interface
    end interface

contains

    !> The run is at time [s] on a long way to its next row; grinding: its steps grind (once a
    !> run, rollcon_grind_watch). Nothing here: a sink that passes them on overrides it.
    subroutine between_chunks(self, time, grinding)
        class(row_sink_type), intent(inout) :: self
        real(wp), intent(in) :: time
        logical, intent(in) :: grinding
    end subroutine between_chunks

end module rollcon_row_sink
