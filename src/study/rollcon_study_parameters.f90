! SPDX-License-Identifier: MIT
!> The parameters of a study: a `group%key = 'from to count'` (grid) or `'from to'` (random)
!> line read and checked against the scene's key table, and the values of each case.
module rollcon_study_parameters
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, input_error
    use rollcon_text, only : to_text, unquoted, comma_list
    use rollcon_namelist_lexer, only : assignment_type
    use rollcon_scene_type, only : scene_type
    use rollcon_keys, only : key_type, find_key, kind_real, kind_integer
    use rollcon_scene_keys, only : bind_keys, scene_groups
    use rollcon_key_values, only : in_range, range_text, is_real_text
    use rollcon_study_type, only : study_type, study_parameter_type, sampling_grid, &
        & sampling_random
    use rollcon_study_dataset, only : read_dataset_parameter
    implicit none
    private

    public :: read_parameter, case_count, case_values, value_text, check_case_count
    public :: max_study_cases

    !> Significant digits a grid or sample value is rounded to: its text in the CSV is then
    !> short ("0.6", not "0.59999999999999998"), and the case runs exactly that value
    integer, parameter :: value_digits = 12
    !> Most cases one study may have. A study's plan holds every case's values and texts in
    !> memory (plan_bytes_per_case), and a resume reads its whole CSV (about 260 bytes a
    !> case, at most csv_input_limit, 1 GiB): 2e6 cases take some 150 MB of plan and 0.5 GB of
    !> CSV, twice the largest study docs/studies.md works out (1e6 cases). Larger studies are
    !> split into several files, a &grid range each.
    integer, parameter :: max_study_cases = 2000000
    !> Bytes a case's value and text take per parameter in a plan (8 for the value, twice about
    !> 24 for its text in the plan and in the keys a resume compares), and per case (flags,
    !> indices)
    integer(int64), parameter :: plan_bytes_per_parameter = 56, plan_bytes_fixed = 16

contains

    !> One parameter line of &grid or &random: its key must be a numeric scene key, its range
    !> within the key's allowed range and not empty. About 85 lines: one refusal after another,
    !> each with its own message, in the order a reader meets them.
    subroutine read_parameter(file, group_name, a, sampling, dataset, parameter, error)
        character(len=*), intent(in) :: file, group_name
        type(assignment_type), intent(in) :: a
        integer, intent(in) :: sampling
        !> The study's base is a dataset: the key names a dataset value (rollcon_study_dataset)
        logical, intent(in) :: dataset
        type(study_parameter_type), intent(out) :: parameter
        type(error_type), allocatable, intent(out) :: error
        type(scene_type), target :: scene
        type(key_type), allocatable :: keys(:)
        character(len=:), allocatable :: words(:), form
        real(wp) :: ends(2)
        integer :: k, want, e

        if (dataset) then
            ! any number: the dataset's reader checks each case's value
            call read_dataset_parameter(file, group_name, a, parameter, error)
            if (allocated(error)) return
            allocate(keys(1))
            keys(1)%group = parameter%group
            keys(1)%name = parameter%key
            k = 1
        else
            call bind_keys(scene, keys)
            k = scene_key(keys, a%key)
            if (k == 0) then
                call input_error(error, file, a%line, a%key, "in &" // group_name // " is not " &
                    & // "a scene key; a parameter is group%key of a scene file " &
                    & // "(docs/scenes.md), e.g. disk%thickness, initial%speed, " &
                    & // "strike%impulse; groups: " // comma_list(scene_groups))
                return
            end if
        end if
        associate (key => keys(k))
            if (key%kind /= kind_real .and. key%kind /= kind_integer) then
                call input_error(error, file, a%line, a%key, "is not a number and cannot be " &
                    & // "varied; a study varies real and integer scene keys")
                return
            end if
            if (key%kind == kind_integer .and. sampling == sampling_random) then
                call input_error(error, file, a%line, a%key, "is a whole number: vary it on " &
                    & // "a &grid, not by &random samples")
                return
            end if
            want = merge(3, 2, sampling == sampling_grid)
            form = merge("'from to count'", "'from to'      ", sampling == sampling_grid)
            call split_words(a%value, words)
            if (size(words) /= want) then
                call input_error(error, file, a%line, a%key, "takes " // trim(form) // ", got " &
                    & // a%value)
                return
            end if
            do e = 1, 2
                if (.not. is_real_text(trim(words(e)))) then
                    call input_error(error, file, a%line, a%key, "takes " // trim(form) &
                        & // ": '" // trim(words(e)) // "' is not a number")
                    return
                end if
                read(words(e), *) ends(e)
                if (.not. in_range(key, ends(e))) then
                    call input_error(error, file, a%line, a%key, "must be " // range_text(key) &
                        & // " (the scene key's range), got " // trim(words(e)))
                    return
                end if
                if (key%kind == kind_integer .and. ends(e) /= aint(ends(e))) then
                    call input_error(error, file, a%line, a%key, "is a whole number, got " &
                        & // trim(words(e)))
                    return
                end if
            end do
            if (.not. dataset) then
                parameter%group = trim(key%group)
                parameter%key = trim(key%name)
                parameter%unit = trim(key%unit)
            end if
            parameter%lower = ends(1)
            parameter%upper = ends(2)
            parameter%line = a%line
            parameter%whole = key%kind == kind_integer
            if (sampling == sampling_grid) then
                call read_grid_count(file, a, trim(words(3)), parameter, error)
            else if (.not. ends(2) > ends(1)) then
                call input_error(error, file, a%line, a%key, "has an empty range: 'from to' " &
                    & // "needs from < to, got " // a%value)
            end if
        end associate
    end subroutine read_parameter

    !> Index of the scene key `group%key` in the table, 0 when there is none.
    pure integer function scene_key(keys, text) result(k)
        type(key_type), intent(in) :: keys(:)
        character(len=*), intent(in) :: text
        integer :: cut

        cut = index(text, "%")
        k = 0
        if (cut > 1) k = find_key(keys, text(:cut - 1), text(cut + 1:))
    end function scene_key

    !> The count of a grid line: at least 1; 1 takes the one value from = to; an integer
    !> key's points must be whole numbers.
    subroutine read_grid_count(file, a, word, parameter, error)
        character(len=*), intent(in) :: file, word
        type(assignment_type), intent(in) :: a
        type(study_parameter_type), intent(inout) :: parameter
        type(error_type), allocatable, intent(out) :: error
        integer :: stat

        read(word, *, iostat=stat) parameter%count
        if (stat /= 0 .or. verify(word, "+-0123456789") /= 0) then
            call input_error(error, file, a%line, a%key, "takes 'from to count': the count '" &
                & // word // "' is not a whole number")
        else if (parameter%count < 1) then
            call input_error(error, file, a%line, a%key, "has an empty range: the count must " &
                & // "be at least 1, got " // word)
        else if (parameter%count == 1 .and. parameter%lower /= parameter%upper) then
            call input_error(error, file, a%line, a%key, "has one point but two ends: with " &
                & // "count 1 give from = to, got " // a%value)
        else if (parameter%whole .and. parameter%count > 1) then
            if (mod(parameter%upper - parameter%lower, real(parameter%count - 1, wp)) &
                & /= 0.0_wp) call input_error(error, file, a%line, a%key, "is a whole " &
                & // "number: (to - from)/(count - 1) must be whole, got " // a%value)
        end if
    end subroutine read_grid_count

    !> The study must have at most max_study_cases cases (counted in real numbers, so that a
    !> grid of 1e5 x 1e5 cannot wrap round): else an error naming the file, the group's line,
    !> the count and the memory its plan alone would take.
    subroutine check_case_count(file, line, study, error)
        !> Study file and the line of its &grid or &random
        character(len=*), intent(in) :: file
        integer, intent(in) :: line
        type(study_type), intent(in) :: study
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: cases, bytes
        character(len=:), allocatable :: how, count_text
        integer :: k

        if (study%sampling == sampling_random) then
            cases = real(study%samples, wp)
            how = "&random samples = " // to_text(study%samples)
        else
            cases = 1.0_wp
            how = "&grid: "
            do k = 1, size(study%parameters)
                cases = cases*real(study%parameters(k)%count, wp)
                if (k > 1) how = how // " x "
                how = how // to_text(study%parameters(k)%count)
            end do
        end if
        if (cases <= real(max_study_cases, wp)) return
        ! exact while below 2**53
        count_text = to_text(cases)
        if (cases < 2.0_wp**53) count_text = to_text(nint(cases, int64))
        bytes = cases*real(plan_bytes_per_parameter*size(study%parameters) &
            & + plan_bytes_fixed, wp)
        call input_error(error, file, line, "", "the study has " // count_text // " cases (" &
            & // how // "); a study may have at most " // to_text(max_study_cases) &
            & // " (docs/studies.md): its plan alone would take about " // memory_text(bytes) &
            & // " of memory. Split it into several studies (a &grid range each), run as " &
            & // "separate jobs into separate CSVs")
    end subroutine check_case_count

    !> Bytes as "3.2 GB", "150 MB".
    pure function memory_text(bytes) result(text)
        real(wp), intent(in) :: bytes

        character(len=:), allocatable :: text

        if (bytes >= 1.0e9_wp) then
            text = to_text(anint(bytes/1.0e8_wp)/10.0_wp) // " GB"
        else
            text = to_text(anint(bytes/1.0e5_wp)/10.0_wp) // " MB"
        end if
    end function memory_text

    !> Number of cases of a study (at most max_study_cases: check_case_count).
    pure integer function case_count(study)
        type(study_type), intent(in) :: study

        if (study%sampling == sampling_random) then
            case_count = study%samples
        else
            case_count = product(study%parameters%count)
        end if
    end function case_count

    !> The parameter values of every case, values(:, i) for case i. A grid's first parameter
    !> varies slowest; random samples are uniform in each range, drawn in case order from the
    !> seed with the compiler's generator (the same binary draws the same cases).
    subroutine case_values(study, values)
        type(study_type), intent(in) :: study
        real(wp), allocatable, intent(out) :: values(:, :)
        integer, allocatable :: seed(:)
        integer :: n, i, k, rest, size_seed
        real(wp) :: u

        n = case_count(study)
        allocate(values(size(study%parameters), n))
        if (study%sampling == sampling_random) then
            call random_seed(size=size_seed)
            seed = [(study%seed + 7919*k, k = 1, size_seed)]
            call random_seed(put=seed)
        end if
        do i = 1, n
            rest = i - 1
            do k = size(study%parameters), 1, -1
                associate (p => study%parameters(k))
                    if (study%sampling == sampling_random) then
                        call random_number(u)
                    else if (p%count == 1) then
                        u = 0.0_wp
                    else
                        u = real(mod(rest, p%count), wp)/real(p%count - 1, wp)
                        rest = rest/p%count
                    end if
                    values(k, i) = rounded(p%lower + (p%upper - p%lower)*u)
                    if (p%whole) values(k, i) = anint(values(k, i))
                end associate
            end do
        end do
    end subroutine case_values

    !> A parameter value as the case's CSV row and its scene take it.
    pure function value_text(parameter, value) result(text)
        type(study_parameter_type), intent(in) :: parameter
        real(wp), intent(in) :: value
        character(len=:), allocatable :: text

        if (parameter%whole) then
            text = to_text(nint(value))
        else
            text = to_text(value)
        end if
    end function value_text

    !> value rounded to value_digits significant digits.
    real(wp) function rounded(value)
        real(wp), intent(in) :: value
        character(len=32) :: buffer

        write(buffer, "(es32." // to_text(value_digits - 1) // "e3)") value
        read(buffer, *) rounded
    end function rounded

    !> The blank-separated words of a value (its quotes removed).
    pure subroutine split_words(value, words)
        character(len=*), intent(in) :: value
        character(len=:), allocatable, intent(out) :: words(:)
        character(len=:), allocatable :: text
        integer :: j, start, n

        text = value
        if (len(text) >= 2) then
            if (scan(text(1:1), "'""") > 0) text = text(2:len(text) - 1)
        end if
        n = 0
        allocate(character(len=len(text)) :: words(0))
        j = 1
        do while (j <= len(text))
            if (text(j:j) == " " .or. text(j:j) == ",") then
                j = j + 1
                cycle
            end if
            start = j
            do while (j <= len(text))
                if (text(j:j) == " " .or. text(j:j) == ",") exit
                j = j + 1
            end do
            words = [character(len=len(text)) :: words, text(start:j - 1)]
        end do
    end subroutine split_words

end module rollcon_study_parameters
