! SPDX-License-Identifier: MIT
!> What a linear analysis (rollcon_linearisation) found, as text: the printed table of the
!> eigenvalues with their frequencies and damping ratios, and the rows of the eigenvalue CSV
!> (docs/linear.md).
module rollcon_linear_report
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_text, only : to_text
    use rollcon_linearisation, only : linear_result_type, invariance_limit
    implicit none
    private

    public :: linear_table_text, eigen_csv_rows, natural_frequency, damped_frequency, &
        & damping_ratio

contains

    !> Undamped natural frequency |lambda| / (2 pi) [Hz].
    elemental real(wp) function natural_frequency(re, im)
        real(wp), intent(in) :: re, im

        natural_frequency = hypot(re, im)/(2.0_wp*pi)
    end function natural_frequency

    !> Damped frequency |Im lambda| / (2 pi) [Hz].
    elemental real(wp) function damped_frequency(re, im)
        real(wp), intent(in) :: re, im

        damped_frequency = abs(im)/(2.0_wp*pi) + 0.0_wp*re
    end function damped_frequency

    !> Damping ratio -Re lambda / |lambda| (0 for lambda = 0, and below 1e-12 in size).
    elemental real(wp) function damping_ratio(re, im)
        real(wp), intent(in) :: re, im

        damping_ratio = 0.0_wp
        if (hypot(re, im) > 0.0_wp) damping_ratio = -re/hypot(re, im)
        ! rounding's sign (-1e-17) is no damping: print 0, not -0.0000000
        if (abs(damping_ratio) < 1.0e-12_wp) damping_ratio = 0.0_wp
    end function damping_ratio

    !> " and 2 DIFF states" ("" without DIFFs).
    pure function diff_words(count) result(text)
        integer, intent(in) :: count
        character(len=:), allocatable :: text

        text = ""
        if (count > 0) text = " and " // to_text(count) // " DIFF state" &
            & // trim(merge("s", " ", count > 1))
    end function diff_words

    !> The table `rollcon linear` prints: a header line, one line per eigenvalue (zeros marked,
    !> with no frequency or damping), the count of zeros and the tangent space's invariance.
    function linear_table_text(result, title) result(text)
        type(linear_result_type), intent(in) :: result
        !> What was linearised, e.g. "data/coin.adm at t = 0 s"
        character(len=*), intent(in) :: title
        character(len=:), allocatable :: text
        character(len=120) :: line
        character(len=1), parameter :: nl = new_line("a")
        integer :: k

        text = "linear analysis of " // title // ": " // to_text(result%reduced) &
            & // " independent states (" // to_text(result%states - result%diff_states) &
            & // " coordinates and rates" // diff_words(result%diff_states) // " less " &
            & // to_text(result%states - result%reduced) // " constraint rows)" // nl
        text = text // "eigenvalues, by decreasing real part; f_natural = |lambda|/(2 pi), " &
            & // "f_damped = |Im lambda|/(2 pi), zeta = -Re lambda/|lambda|" // nl
        write(line, '(a4, 2a24, 2a16, a12)') "k", "real [1/s]", "imag [1/s]", "f_natural [Hz]", &
            & "f_damped [Hz]", "zeta [-]"
        text = text // trim(line) // nl
        do k = 1, result%reduced
            associate (re => result%real_part(k), im => result%imag_part(k))
                if (hypot(re, im) <= result%zero_limit) then
                    write(line, '(i4, 2es24.15, a44)') k, re, im, "zero"
                else
                    write(line, '(i4, 2es24.15, 2es16.7, f12.7)') k, re, im, &
                        & natural_frequency(re, im), damped_frequency(re, im), &
                        & damping_ratio(re, im)
                end if
            end associate
            text = text // trim(line) // nl
        end do
        text = text // "zero eigenvalues (|lambda| <= " // to_text(result%zero_limit) &
            & // " 1/s, 1e-6 of the largest or of the model's frequency scale): " &
            & // to_text(result%zeros) // nl
        text = text // "invariance of the tangent space, |A T - T A_red|/|A T|: " &
            & // to_text(result%invariance)
        if (result%invariant) then
            text = text // " (a steady motion: the eigenvalues are those of its linearisation)"
        else
            text = text // " -- above " // to_text(invariance_limit) // ": the start is no " &
                & // "steady motion (or the equations are not smooth there); the eigenvalues " &
                & // "are those of the equations frozen at the start"
        end if
    end function linear_table_text

    !> The eigenvalue CSV's header and rows: `real,imag` [1/s], one row per eigenvalue in the
    !> result's order, 17 significant digits as the run CSV's.
    function eigen_csv_rows(result) result(text)
        type(linear_result_type), intent(in) :: result
        character(len=:), allocatable :: text
        character(len=64) :: line
        integer :: k

        text = "real,imag" // new_line("a")
        do k = 1, result%reduced
            write(line, '(es24.16e3, ",", es24.16e3)') result%real_part(k), result%imag_part(k)
            text = text // trim(adjustl(line)) // new_line("a")
        end do
    end function eigen_csv_rows

end module rollcon_linear_report
