! SPDX-License-Identifier: MIT
!> What the benchmark draws and records beside its rows: one work-precision plot per scene
!> (gnuplot through rollcon_gnuplot), the name of the machine it ran on and which SUNDIALS
!> build it measured.
module rollcon_bench_plot
    use, intrinsic :: iso_c_binding, only : c_char, c_int, c_null_char
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text
    use rollcon_gnuplot, only : run_gnuplot, gnuplot_string
    use rollcon_benchmark, only : method_type, benchmark_methods
    implicit none
    private

    public :: plot_work_precision, machine_name, sundials_build

    interface
        !> SUNDIALS' version text ("6.4.1"), from the library loaded (sundials_version.h)
        function sundials_get_version(version, length) result(stat) &
                & bind(c, name="SUNDIALSGetVersion")
            import :: c_char, c_int
            character(kind=c_char), intent(out) :: version(*)
            integer(c_int), value :: length
            integer(c_int) :: stat
        end function sundials_get_version
    end interface

contains

    !> One log-log plot per scene: largest position error against CPU time, a curve per method
    !> (the reduced ODE's among them), drawn by gnuplot through rollcon_gnuplot.
    subroutine plot_work_precision(output_dir, scene_list, error)
        character(len=*), intent(in) :: output_dir, scene_list
        type(error_type), allocatable, intent(out) :: error
        type(method_type) :: methods(size(benchmark_methods()))
        character(len=:), allocatable :: script_path, scene, csv
        integer :: unit, stat, m, start, comma

        methods = benchmark_methods()
        script_path = output_dir // "/bench.gp"
        csv = gnuplot_string(output_dir // "/bench.csv")
        open(newunit=unit, file=script_path, status="replace", action="write", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, script_path // ": cannot write", stat_io)
            return
        end if
        write(unit, '(a)') "set datafile separator ','", "set terminal png size 900,650", &
            & "set logscale xy", "set format x '10^{%L}'", "set format y '10^{%L}'", &
            & "set xlabel 'CPU time [s]'", "set key outside right", "set grid"
        start = 1
        do
            comma = index(scene_list(start:), ",")
            if (comma == 0) then
                scene = scene_list(start:)
            else
                scene = scene_list(start:start + comma - 2)
            end if
            write(unit, '(a)') "set output " // gnuplot_string(output_dir // "/bench_" // scene &
                & // ".png"), "set title " // gnuplot_string("work-precision: " // scene &
                & // " (tolerances 1e-3 to 1e-12)") // " noenhanced"
            if (scene == "bicycle" .or. index(scene, ".adm") > 0) then
                write(unit, '(a)') "set ylabel 'largest difference from the reduced ODE: " &
                    & // "roll, steer [rad], contact [m]'"
            else
                write(unit, '(a)') "set ylabel 'largest position error against the reduced " &
                    & // "ODE (Adams, rtol 1e-13) [m]'"
            end if
            do m = 1, size(methods)
                write(unit, '(a)', advance="no") merge("plot ", "     ", m == 1) // csv &
                    & // " using (strcol(1) eq " // gnuplot_string(scene) // " && strcol(2) eq " &
                    & // gnuplot_string(trim(methods(m)%name)) // " ? $4 : 1/0):" &
                    & // "($8 > 0 ? $8 : 1/0) with linespoints title " &
                    & // gnuplot_string(trim(methods(m)%name)) // " noenhanced"
                if (m < size(methods)) then
                    write(unit, '(a)') ", \"
                else
                    write(unit, '(a)') ""
                end if
            end do
            if (comma == 0) exit
            start = start + comma
        end do
        close(unit)
        call run_gnuplot(script_path, error)
    end subroutine plot_work_precision

    !> CPU model and core count, for the record.
    function machine_name() result(name)
        character(len=:), allocatable :: name
        character(len=256) :: line
        integer :: unit, stat, cores

        name = "unknown CPU"
        cores = 0
        open(newunit=unit, file="/proc/cpuinfo", status="old", action="read", iostat=stat)
        if (stat /= 0) return
        do
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (index(line, "model name") == 1) then
                name = trim(adjustl(line(index(line, ":") + 1:)))
                cores = cores + 1
            end if
        end do
        close(unit)
        name = name // ", " // to_text(cores) // " cores"
    end function machine_name

    !> Which SUNDIALS the process runs on: its version and the file of libsundials_cvode the
    !> loader mapped (/proc/self/maps), named Debian's build when it is the system's
    !> (/usr/lib/...), else by its folder (an optimised build, .ci/setup's
    !> ROLLCON_SUNDIALS=optimised).
    function sundials_build() result(text)
        character(len=:), allocatable :: text
        character(kind=c_char) :: version(32)
        character(len=1024) :: line
        character(len=:), allocatable :: path
        integer :: unit, stat, k, slash

        text = "SUNDIALS"
        if (sundials_get_version(version, size(version, kind=c_int)) == 0) then
            k = findloc(version, c_null_char, 1)
            if (k > 1) text = text // " " // transfer(version(:k - 1), repeat(" ", k - 1))
        end if
        path = ""
        open(newunit=unit, file="/proc/self/maps", status="old", action="read", iostat=stat)
        if (stat == 0) then
            do
                read(unit, '(a)', iostat=stat) line
                if (stat /= 0) exit
                if (index(line, "libsundials_cvode.so") == 0) cycle
                path = trim(line(index(line, "/"):))
                exit
            end do
            close(unit)
        end if
        if (len(path) == 0) then
            text = text // " (library file not found)"
        else if (index(path, "/usr/lib/") == 1) then
            text = text // ", Debian's build (" // path // ")"
        else
            slash = index(path, "/", back=.true.)
            text = text // ", the build in " // path(:slash - 1) // " (" // path(slash + 1:) &
                & // ")"
        end if
    end function sundials_build

end module rollcon_bench_plot
