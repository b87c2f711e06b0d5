! SPDX-License-Identifier: MIT
!> How a study classes its cases and draws its map: &classify (`class = 'measure > number'`
!> rules, the first that holds gives the class; `otherwise` names the rest) and &map (the
!> parameters on its axes, an analytic curve).
module rollcon_study_rules
    use rollcon_kinds, only : wp
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_error, only : error_type, input_error
    use rollcon_text, only : to_text, unquoted, comma_list
    use rollcon_namelist_lexer, only : group_type
    use rollcon_key_values, only : is_real_text
    use rollcon_study_type, only : study_type, study_rule_type, relation_words, &
        & relation_less, relation_less_equal, relation_greater, relation_greater_equal
    use rollcon_study_measures, only : case_result_type, measure_names, measure_index, &
        & outcome_failed, outcome_refused, outcome_words
    implicit none
    private

    public :: read_rules, read_map, classify

    !> Class of a case with no &classify rule that holds, by default
    character(len=*), parameter :: default_class = "unclassified"
    !> Curves &map can draw
    character(len=*), parameter :: curve_names(1) = ["critical_speed"]

contains

    !> &classify (group g, 0 when absent).
    subroutine read_rules(file, groups, g, study, error)
        character(len=*), intent(in) :: file
        type(group_type), intent(in) :: groups(:)
        integer, intent(in) :: g
        type(study_type), intent(inout) :: study
        type(error_type), allocatable, intent(out) :: error
        type(study_rule_type) :: rule
        character(len=:), allocatable :: text
        integer :: k, j, r, first_blank, stat

        allocate(study%rules(0))
        study%otherwise = default_class
        if (g == 0) return
        do k = 1, size(groups(g)%assignments)
            associate (a => groups(g)%assignments(k))
                text = unquoted(a%value)
                if (a%key == "otherwise") then
                    call check_class_name(file, a%line, a%key, text, error)
                    if (allocated(error)) return
                    study%otherwise = text
                    cycle
                end if
                call check_class_name(file, a%line, a%key, a%key, error)
                if (allocated(error)) return
                if (any(outcome_words(outcome_failed:) == a%key)) then
                    call input_error(error, file, a%line, a%key, "is the class of every case " &
                        & // "that " // trim(a%key) // "; give a rule another name")
                    return
                end if
                rule%class = a%key
                rule%line = a%line
                first_blank = index(adjustl(text), " ")
                text = adjustl(text)
                rule%measure = text(:max(first_blank - 1, 0))
                text = adjustl(text(first_blank + 1:))
                if (measure_index(rule%measure) == 0) then
                    call input_error(error, file, a%line, a%key, "reads 'measure relation " &
                        & // "number'; '" // rule%measure // "' is not a measure; measures " &
                        & // "are " // comma_list(measure_names))
                    return
                end if
                r = 0
                do j = size(relation_words), 1, -1
                    if (index(text, trim(relation_words(j))) == 1) then
                        r = j
                        exit
                    end if
                end do
                if (r == 0) then
                    call input_error(error, file, a%line, a%key, "reads 'measure relation " &
                        & // "number' with a relation <, <=, > or >=, got '" // a%value // "'")
                    return
                end if
                rule%relation = r
                text = adjustl(text(len_trim(relation_words(r)) + 1:))
                if (.not. is_real_text(trim(text))) then
                    call input_error(error, file, a%line, a%key, "reads 'measure relation " &
                        & // "number': '" // trim(text) // "' is not a number")
                    return
                end if
                read(text, *, iostat=stat) rule%bound
                ! NaN compares false with everything: such a rule would never hold; Infinity
                ! and numbers beyond the largest double (iostat) are no bound either
                if (stat /= 0 .or. .not. ieee_is_finite(rule%bound)) then
                    call input_error(error, file, a%line, a%key, "reads 'measure relation " &
                        & // "number': '" // trim(text) // "' is not a finite number")
                    return
                end if
                study%rules = [study%rules, rule]
            end associate
        end do
    end subroutine read_rules

    !> A class name goes into every row of the study's CSV and into the map's legend: it must
    !> not be empty and may hold no comma and no double quote (they would split or quote the
    !> CSV's class field) and no control character.
    subroutine check_class_name(file, line, key, name, error)
        character(len=*), intent(in) :: file, key, name
        integer, intent(in) :: line
        type(error_type), allocatable, intent(out) :: error
        integer :: j, code

        if (len_trim(name) == 0) then
            call input_error(error, file, line, key, "names an empty class; a class is a word " &
                & // "such as 'falls'")
            return
        end if
        do j = 1, len(name)
            code = iachar(name(j:j))
            if (name(j:j) == "," .or. name(j:j) == '"' .or. code < 32 .or. code == 127) then
                call input_error(error, file, line, key, "names the class '" // name &
                    & // "', which holds " // character_name(name(j:j)) // " (column " &
                    & // to_text(j) // "): a class name goes into every row of the study's " &
                    & // "CSV and may hold no comma, double quote or control character")
                return
            end if
        end do
    end subroutine check_class_name

    !> A character a class name may not hold, in words.
    pure function character_name(c) result(text)
        character, intent(in) :: c
        character(len=:), allocatable :: text

        select case (c)
        case (",")
            text = "a comma"
        case ('"')
            text = "a double quote"
        case default
            text = "the control character " // to_text(iachar(c))
        end select
    end function character_name

    !> &map (group g, 0 when absent): x and y name varied parameters (default: the first two),
    !> curve an analytic curve.
    subroutine read_map(file, groups, g, study, error)
        character(len=*), intent(in) :: file
        type(group_type), intent(in) :: groups(:)
        integer, intent(in) :: g
        type(study_type), intent(inout) :: study
        type(error_type), allocatable, intent(out) :: error
        integer :: k, j

        study%map%curve = ""
        if (size(study%parameters) >= 2) study%map%x = 1
        if (size(study%parameters) >= 2) study%map%y = 2
        if (g == 0) return
        do k = 1, size(groups(g)%assignments)
            associate (a => groups(g)%assignments(k))
                select case (a%key)
                case ("x", "y")
                    j = parameter_index(study, unquoted(a%value))
                    if (j == 0) then
                        call input_error(error, file, a%line, a%key, "must name a parameter " &
                            & // "the study varies (" // parameter_list(study) // "), got " &
                            & // a%value)
                        return
                    end if
                    if (a%key == "x") study%map%x = j
                    if (a%key == "y") study%map%y = j
                case ("curve")
                    study%map%curve = unquoted(a%value)
                    if (.not. any(curve_names == study%map%curve)) then
                        call input_error(error, file, a%line, a%key, "must be one of: " &
                            & // curve_names(1) // "; got " // a%value)
                        return
                    end if
                case default
                    call input_error(error, file, a%line, a%key, "is not a key of &map; its " &
                        & // "keys are x, y, curve")
                    return
                end select
            end associate
        end do
        if (study%map%x == 0 .or. study%map%y == 0 .or. study%map%x == study%map%y) then
            call input_error(error, file, groups(g)%line, "", "&map needs two different " &
                & // "parameters on its axes (x and y), of " // parameter_list(study))
        else if (study%map%curve == "critical_speed") then
            if (parameter_name(study, study%map%y) /= "initial%speed") call input_error(error, &
                & file, groups(g)%line, "curve", "'critical_speed' is a speed: it needs " &
                & // "y = 'initial%speed'")
        end if
    end subroutine read_map

    !> The class of a case: failed and refused cases are classed so; any other by the first
    !> rule that holds (a rule on a measure the case lacks does not hold), else otherwise.
    pure function classify(study, result) result(class)
        type(study_type), intent(in) :: study
        type(case_result_type), intent(in) :: result
        character(len=:), allocatable :: class
        integer :: k, m
        logical :: holds

        if (result%outcome == outcome_failed .or. result%outcome == outcome_refused) then
            class = trim(outcome_words(result%outcome))
            return
        end if
        do k = 1, size(study%rules)
            associate (rule => study%rules(k))
                m = measure_index(rule%measure)
                if (.not. result%known(m)) cycle
                select case (rule%relation)
                case (relation_less)
                    holds = result%values(m) < rule%bound
                case (relation_less_equal)
                    holds = result%values(m) <= rule%bound
                case (relation_greater)
                    holds = result%values(m) > rule%bound
                case default
                    holds = result%values(m) >= rule%bound
                end select
                if (holds) then
                    class = rule%class
                    return
                end if
            end associate
        end do
        class = study%otherwise
    end function classify

    pure integer function parameter_index(study, name) result(k)
        type(study_type), intent(in) :: study
        character(len=*), intent(in) :: name

        do k = 1, size(study%parameters)
            if (parameter_name(study, k) == name) return
        end do
        k = 0
    end function parameter_index

    pure function parameter_name(study, k) result(name)
        type(study_type), intent(in) :: study
        integer, intent(in) :: k
        character(len=:), allocatable :: name

        name = study%parameters(k)%group // "%" // study%parameters(k)%key
    end function parameter_name

    pure function parameter_list(study) result(list)
        type(study_type), intent(in) :: study
        character(len=:), allocatable :: list
        integer :: k

        list = ""
        do k = 1, size(study%parameters)
            if (k > 1) list = list // ", "
            list = list // parameter_name(study, k)
        end do
    end function parameter_list

end module rollcon_study_rules
