! SPDX-License-Identifier: MIT
!> The scene-errors suite's tests of bytes a scene file must not hold: control characters and
!> non-ASCII text outside comments.
module scene_bytes
    use rollcon_error, only : error_type
    use rollcon_scene, only : scene_type
    use scene_texts, only : expect_input_error, expect_accepted, width
    implicit none
    private

    public :: test_control_byte, test_non_ascii

contains

    !> A NUL or other control byte is refused with file, line and column, shown as \xNN.
    subroutine test_control_byte(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "nul", [character(len=width) :: "&disk", &
            & "radius = 0.1" // achar(0), "/"], [character(len=width) :: &
            & "@:2: control character \x00 at column 13"])
        if (allocated(error)) return
        call expect_input_error(error, "escape", [character(len=width) :: &
            & "! a comment with an escape " // achar(27) // "[31m"], [character(len=width) :: &
            & "@:1: control character \x1B at column 28"])
    end subroutine test_control_byte

    !> Non-ASCII characters outside comments are refused and shown as U+XXXX; in comments they
    !> are fine; a byte-order mark past the start is refused by name.
    subroutine test_non_ascii(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: no_break_space = achar(194) // achar(160)
        character(len=*), parameter :: mark = achar(239) // achar(187) // achar(191)
        character(len=*), parameter :: theta = achar(206) // achar(184)
        type(scene_type) :: s

        call expect_input_error(error, "nbsp", [character(len=width) :: &
            & "&disk radius =" // no_break_space // "0.1 /"], [character(len=width) :: &
            & "@:1: non-ASCII character U+00A0 at column 15"])
        if (allocated(error)) return
        call expect_input_error(error, "mark_inside", [character(len=width) :: &
            & "&disk radius = 0.1 /", mark // "&run end_time = 1.0 /"], [character(len=width) :: &
            & "@:2: non-ASCII character U+FEFF at column 1"])
        if (allocated(error)) return
        call expect_input_error(error, "broken_utf8", [character(len=width) :: &
            & "&disk radius = 0.1" // achar(200) // " /"], [character(len=width) :: &
            & "@:1: non-ASCII character \xC8 at column 19"])
        if (allocated(error)) return
        call expect_accepted("utf8_comment", [character(len=width) :: &
            & "&initial theta = 1.0  ! " // theta // " in radians", "/"], s, error)
    end subroutine test_non_ascii

end module scene_bytes
